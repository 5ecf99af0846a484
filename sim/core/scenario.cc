#include "sim/core/scenario.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sim/core/gait.h"
#include "sim/core/pendulum.h"

namespace ahhs::sim {

ScenarioKind ParseScenarioKind(const std::string& name) {
  if (name == "gait") return ScenarioKind::kGait;
  if (name == "pendulum") return ScenarioKind::kPendulum;
  throw std::invalid_argument("unknown scenario '" + name + "' (use gait or pendulum)");
}

DockingKind ParseDocking(const std::string& name) {
  if (name == "damped") return DockingKind::kDamped;
  if (name == "fixed") return DockingKind::kFixed;
  throw std::invalid_argument("unknown docking '" + name + "' (use damped or fixed)");
}

const char* PendulumWallsName(PendulumWalls walls) {
  return walls == PendulumWalls::kRigid ? "rigid" : "soft";
}
PendulumWalls ParsePendulumWalls(const std::string& name) {
  if (name == "rigid") return PendulumWalls::kRigid;
  if (name == "soft") return PendulumWalls::kSoft;
  throw std::invalid_argument("unknown pendulum walls '" + name + "' (use rigid or soft)");
}

const char* ScenarioName(ScenarioKind kind) {
  return kind == ScenarioKind::kGait ? "gait" : "pendulum";
}
const char* DockingName(DockingKind docking) {
  return docking == DockingKind::kDamped ? "damped" : "fixed";
}

const char* PhysicsVersion(ScenarioKind kind, DockingKind docking) {
  if (kind == ScenarioKind::kPendulum) return kPendulumPhysicsVersion;
  return docking == DockingKind::kDamped ? kGaitDampedPhysicsVersion : kGaitFixedPhysicsVersion;
}

std::vector<std::string> ReplayablePhysics(ScenarioKind kind, DockingKind docking) {
  std::vector<std::string> versions{PhysicsVersion(kind, docking)};
  if (kind == ScenarioKind::kGait) {
    versions.emplace_back(kGaitChainColdPhysicsVersion);
    versions.emplace_back(docking == DockingKind::kDamped ? kGaitDampedDantzigPhysicsVersion
                                                          : kGaitFixedDantzigPhysicsVersion);
  }
  return versions;
}

std::string PhysicsOf(const ScenarioConfig& config) {
  return config.physics.empty() ? PhysicsVersion(config.kind, config.docking) : config.physics;
}

void KeepPhysics(const std::string& physics, ScenarioConfig* config) {
  config->physics = physics == PhysicsVersion(config->kind, config->docking) ? "" : physics;
}

std::string CheckPhysics(ScenarioKind kind, DockingKind docking, const std::string& physics) {
  if (physics.empty()) return "";
  const auto versions = ReplayablePhysics(kind, docking);
  if (std::find(versions.begin(), versions.end(), physics) != versions.end()) return "";
  std::string list;
  for (const auto& v : versions) list += (list.empty() ? "" : ", ") + v;
  return std::string("physics: this build simulates the ") + ScenarioName(kind) + " physics of " +
         list + ", not " + physics + " (CHANGELOG.md names the release that does)";
}

std::string CheckConfig(const ScenarioConfig& c) {
  if (c.kind != ScenarioKind::kGait && c.kind != ScenarioKind::kPendulum)
    return "scenario: unknown";
  if (c.kind == ScenarioKind::kGait && (c.num_modules < 2 || c.num_modules > 100))
    return "modules: a gait organism needs 2 to 100 modules, not " + std::to_string(c.num_modules);
  if (!std::isfinite(c.duration) || c.duration < 0)
    return "duration: must be a positive number of seconds";
  if (c.duration > 1e5) return "duration: more than 100000 s";
  if (!std::isfinite(c.physics_step) || c.physics_step < 0 || c.physics_step > 0.05)
    return "physics step: 0 (the scenario's) or up to 0.05 s";
  if (!std::isfinite(c.friction_scale) || c.friction_scale <= 0 || c.friction_scale > 10)
    return "friction scale: above 0, at most 10";
  if (std::string error = CheckPhysics(c.kind, c.docking, c.physics); !error.empty()) return error;
  if (!std::isfinite(c.pendulum.actuator_gain) || c.pendulum.actuator_gain < 1 ||
      c.pendulum.actuator_gain > 100)
    return "pendulum.actuator-gain: from 1 to 100";
  if (c.pendulum.walls != PendulumWalls::kRigid && c.pendulum.walls != PendulumWalls::kSoft)
    return "pendulum.walls: rigid or soft";
  if (c.kind == ScenarioKind::kGait && !c.pendulum.standard())
    return "pendulum.actuator-gain and pendulum.walls are the pendulum's, not the gait's";
  return CheckEnvelope(c.envelope);
}

std::int64_t EpisodeTicks(double duration, double control_period, std::int64_t default_ticks) {
  return duration > 0 ? static_cast<std::int64_t>(std::llround(duration / control_period))
                      : default_ticks;
}

ScenarioShape ShapeOf(const ScenarioConfig& config) {
  ScenarioShape shape;
  if (config.kind == ScenarioKind::kPendulum) {
    const PendulumConstants k;
    shape = {2, kPendulumSensors, 2, k.control_period, 0};
    shape.ticks = EpisodeTicks(config.duration, k.control_period, k.ticks);
  } else {
    const GaitConstants k;
    shape = {config.num_modules, kGaitSensors, 1, k.control_period, 0};
    shape.ticks = EpisodeTicks(config.duration, k.control_period,
                               EpisodeTicks(k.duration, k.control_period, 0));
  }
  return shape;
}

ScenarioConfig MakeScenarioConfig(ScenarioKind kind, DockingKind docking, int modules,
                                  double duration) {
  ScenarioConfig config;
  config.kind = kind;
  config.docking = docking;
  config.num_modules = kind == ScenarioKind::kPendulum ? 2 : modules;
  config.duration = duration;
  return config;
}

std::unique_ptr<Scenario> MakeScenario(const ScenarioConfig& config) {
  const std::string error = CheckConfig(config);
  if (!error.empty()) throw std::invalid_argument(error);
  if (config.kind == ScenarioKind::kPendulum) {
    PendulumConstants k;
    if (config.physics_step > 0) k.integration_step = config.physics_step;
    k.pivot_friction *= config.friction_scale;
    return std::make_unique<PendulumScenario>(config, k);
  }
  GaitConstants k;
  if (config.physics_step > 0) k.physics_step_fixed = k.physics_step_damped = config.physics_step;
  k.friction *= config.friction_scale;
  // The earlier physics: the same model without the warm start, or solved by dWorldStep.
  if (config.physics == kGaitChainColdPhysicsVersion) k.chain_warm_start = false;
  if (config.physics == (config.docking == DockingKind::kDamped ? kGaitDampedDantzigPhysicsVersion
                                                                : kGaitFixedDantzigPhysicsVersion))
    k.solver = GaitSolver::kDantzig;
  return std::make_unique<GaitScenario>(config, k);
}

std::vector<std::pair<int, int>> ChainDocking(int compartments) {
  std::vector<std::pair<int, int>> links;
  for (int i = 0; i + 1 < compartments; ++i) links.emplace_back(i, i + 1);
  return links;
}

}  // namespace ahhs::sim
