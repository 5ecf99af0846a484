#include "sim/node/sim_codec.h"

#include <algorithm>
#include <cmath>

namespace ahhs::sim {

void FillSensorsMessage(const Scenario& scenario, int module, std::int64_t episode,
                        module_sensors_t* m) {
  m->episode = episode;
  m->tick = scenario.tick();
  m->module = module;
  m->sim_time = scenario.sim_time();
  const int n = scenario.num_sensors();
  m->num_sensors = static_cast<std::int16_t>(n);
  m->values.resize(static_cast<std::size_t>(n));
  scenario.ReadSensors(module, m->values.data());
  m->present.resize(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j)
    m->present[static_cast<std::size_t>(j)] = scenario.sensor_owned(module, j);
  m->hinge_angle = scenario.HingeAngle(module);
  m->num_actuators = static_cast<std::int16_t>(scenario.num_actuators());
  m->actuator_present.resize(static_cast<std::size_t>(scenario.num_actuators()));
  for (int a = 0; a < scenario.num_actuators(); ++a)
    m->actuator_present[static_cast<std::size_t>(a)] = scenario.actuator_owned(module, a);
}

module_sensors_t SensorsMessage(const Scenario& scenario, int module, std::int64_t episode) {
  module_sensors_t m{};
  FillSensorsMessage(scenario, module, episode, &m);
  return m;
}

void FillStateMessage(const std::vector<BodyState>& bodies, std::int64_t episode, std::int64_t tick,
                      double sim_time, sim_state_t* m) {
  m->episode = episode;
  m->tick = tick;
  m->sim_time = sim_time;
  m->num_bodies = static_cast<std::int16_t>(bodies.size());
  m->module.clear();
  m->shape.clear();
  for (auto* v :
       {&m->px, &m->py, &m->pz, &m->qw, &m->qx, &m->qy, &m->qz, &m->sx, &m->sy, &m->sz, &m->mass})
    v->clear();
  for (const BodyState& b : bodies) {
    m->module.push_back(b.module);
    m->shape.push_back(static_cast<std::int8_t>(b.shape));
    m->px.push_back(b.position[0]);
    m->py.push_back(b.position[1]);
    m->pz.push_back(b.position[2]);
    m->qw.push_back(b.quaternion[0]);
    m->qx.push_back(b.quaternion[1]);
    m->qy.push_back(b.quaternion[2]);
    m->qz.push_back(b.quaternion[3]);
    m->sx.push_back(b.size[0]);
    m->sy.push_back(b.size[1]);
    m->sz.push_back(b.size[2]);
    m->mass.push_back(b.mass);
  }
}

void KeepMovingBodies(std::vector<BodyState>* bodies) {
  bodies->erase(std::remove_if(bodies->begin(), bodies->end(),
                               [](const BodyState& b) { return !(b.mass > 0); }),
                bodies->end());
}

void KeepStaticBodies(std::vector<BodyState>* bodies) {
  bodies->erase(
      std::remove_if(bodies->begin(), bodies->end(), [](const BodyState& b) { return b.mass > 0; }),
      bodies->end());
}

sim_state_t StateMessage(const std::vector<BodyState>& bodies, std::int64_t episode,
                         std::int64_t tick, double sim_time) {
  sim_state_t m{};
  FillStateMessage(bodies, episode, tick, sim_time, &m);
  return m;
}

topology_t TopologyMessage(const Scenario& scenario, std::int64_t episode) {
  return TopologyMessage(scenario.num_compartments(), scenario.Docking(), episode, scenario.tick());
}

sim_clock_t ClockMessage(std::int64_t episode, std::int64_t tick, double control_period,
                         bool realtime, std::int8_t run_state) {
  sim_clock_t c{};
  c.episode = episode;
  c.tick = tick;
  c.sim_time = static_cast<double>(tick) * control_period;
  c.control_period = control_period;
  c.clock_mode = realtime ? sim_clock_t::MODE_REALTIME : sim_clock_t::MODE_LOCKSTEP;
  c.run_state = run_state;
  return c;
}

topology_t TopologyMessage(int compartments, const std::vector<std::pair<int, int>>& docking,
                           std::int64_t episode, std::int64_t tick) {
  topology_t m{};
  m.episode = episode;
  m.tick = tick;
  m.num_modules = compartments;
  m.ports_per_module = 4;
  for (const auto& [a, b] : docking) {
    m.module_a.push_back(a);
    m.port_a.push_back(2);  // back port of the module in front
    m.module_b.push_back(b);
    m.port_b.push_back(0);  // front port of the one behind
  }
  m.num_links = static_cast<std::int16_t>(m.module_a.size());
  return m;
}

std::int8_t DockingToWire(DockingKind docking) {
  return docking == DockingKind::kFixed ? sim_control_t::JOINTS_FIXED
                                        : sim_control_t::JOINTS_DAMPED;
}

std::string ScenarioFromFields(const std::string& scenario, std::int32_t num_modules,
                               std::int8_t docking, double duration, const Envelope& envelope,
                               double pendulum_actuator_gain, std::int8_t pendulum_walls,
                               const std::string& physics, ScenarioConfig* config) {
  ScenarioConfig c;
  if (scenario == "gait") {
    c.kind = ScenarioKind::kGait;
  } else if (scenario == "pendulum") {
    c.kind = ScenarioKind::kPendulum;
  } else {
    return "unknown scenario '" + scenario + "'";
  }
  if (docking == sim_control_t::JOINTS_DAMPED) {
    c.docking = DockingKind::kDamped;
  } else if (docking == sim_control_t::JOINTS_FIXED) {
    c.docking = DockingKind::kFixed;
  } else {
    return "unknown docking value " + std::to_string(docking);
  }
  c = MakeScenarioConfig(c.kind, c.docking, num_modules, duration);
  c.envelope = envelope;
  if (pendulum_walls != 0 && pendulum_walls != 1)
    return "unknown pendulum walls value " + std::to_string(pendulum_walls);
  // 0 is the default too, so that a RESET made field by field without it asks for the scenario.
  c.pendulum.actuator_gain = pendulum_actuator_gain == 0 ? 1 : pendulum_actuator_gain;
  c.pendulum.walls = pendulum_walls == 1 ? PendulumWalls::kSoft : PendulumWalls::kRigid;
  KeepPhysics(physics, &c);
  const std::string error = CheckConfig(c);
  if (!error.empty()) return error;
  *config = c;
  return "";
}

std::string ConfigFromReset(const sim_control_t& reset, ScenarioConfig* config) {
  ScenarioConfig c;
  const std::string error = ScenarioFromWire(reset, &c);
  if (!error.empty()) return error;
  if (reset.clock_mode != sim_control_t::MODE_LOCKSTEP &&
      reset.clock_mode != sim_control_t::MODE_REALTIME)
    return "unknown clock mode " + std::to_string(reset.clock_mode);
  *config = c;
  return "";
}

std::string CheckHinge(const hinge_command_t& cmd, const Scenario& scenario) {
  if (cmd.module < 0 || cmd.module >= scenario.num_compartments()) return "unknown module";
  if (cmd.num_actuators != scenario.num_actuators() || cmd.values.size() != cmd.present.size())
    return "wrong number of actuators";
  for (int a = 0; a < scenario.num_actuators(); ++a) {
    if (!scenario.actuator_owned(cmd.module, a)) continue;
    const double v = cmd.values[static_cast<std::size_t>(a)];
    if (!std::isfinite(v)) return "non-finite actuator value";
    if (v < -1.0 || v > 1.0) return "actuator value outside [-1, 1]";
  }
  return "";
}

}  // namespace ahhs::sim
