// The two scenarios of the paper behind one interface: apply actuator values, step one control
// period, read sensors, organism state and fitness (docs/scenarios.md). No LCM, no I/O. One
// stepping ODE world per process: ODE's solver draws from a process-global random seed (see
// GaitScenario).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "sim/core/envelope.h"

namespace ahhs::sim {

enum class ScenarioKind { kGait, kPendulum };
enum class DockingKind { kDamped, kFixed };

// Two choices the paper leaves open for the pendulum, as scenario settings (docs/scenarios.md,
// "Choices the paper leaves open"), on the wire in RESET and EVAL/REQUEST. The defaults are the
// scenario as it always was, bit for bit.
enum class PendulumWalls { kRigid, kSoft };
struct PendulumChoices {
  // v_cmd = top speed x clamp(gain x (A1 - A0) / 2, -1, 1): small outputs count `gain` times
  // as much, the crab is no faster. In [1, 100].
  double actuator_gain = 1;
  // Rigid: the cart stops dead at a wall (an impulse kicks the pendulum). Soft: a spring-damper
  // stop (PendulumConstants::soft_wall_*).
  PendulumWalls walls = PendulumWalls::kRigid;

  bool operator==(const PendulumChoices& o) const {
    return actuator_gain == o.actuator_gain && walls == o.walls;
  }
  bool standard() const { return *this == PendulumChoices{}; }
};
const char* PendulumWallsName(PendulumWalls walls);
PendulumWalls ParsePendulumWalls(const std::string& name);  // throws std::invalid_argument

struct ScenarioConfig {
  ScenarioKind kind = ScenarioKind::kGait;
  int num_modules = 5;  // gait: modules in the chain (>= 2); pendulum: always 2
  DockingKind docking = DockingKind::kDamped;  // the gait's docking
  double duration = 0;  // simulated seconds; 0 = the scenario's default (60 s / 3000 ticks)
  // A check, not a scenario setting: the physics step (gait, ODE) or RK4 step (pendulum) in
  // seconds; 0 = the scenario's (docs/scenarios.md). Never on the wire: only a direct replay sets
  // it, to see whether a behaviour depends on the discretisation.
  double physics_step = 0;
  // A check, not a scenario setting: scales every Coulomb friction coefficient (gait) or the pivot
  // friction (pendulum). Never on the wire: a replay perturbs the physics slightly with it to
  // tell a robust behaviour from one that deterministic chaos happened to favour.
  double friction_scale = 1;
  // The physics version to simulate: "" for this build's (PhysicsVersion), or an earlier one
  // this build still simulates (ReplayablePhysics): a replay of a run made with it, or a run
  // that keeps it (ahhs-evolve --physics). On the wire in RESET and EVAL/REQUEST, always by
  // name (PhysicsOf).
  std::string physics;
  // The envelope of noise every episode of this configuration is perturbed with (a scenario
  // setting, on the wire in RESET and EVAL/REQUEST: sim/core/envelope.h).
  Envelope envelope;
  // The pendulum's open choices (a scenario setting, on the wire in RESET and EVAL/REQUEST).
  PendulumChoices pendulum;
};

// Parses "gait"/"pendulum" and "damped"/"fixed"; throw std::invalid_argument otherwise.
ScenarioKind ParseScenarioKind(const std::string& name);
DockingKind ParseDocking(const std::string& name);
const char* ScenarioName(ScenarioKind kind);
const char* DockingName(DockingKind docking);

// The physics version (sim/core/constants.h) a fitness of this configuration is measured with.
const char* PhysicsVersion(ScenarioKind kind, DockingKind docking);
// The physics versions this build can simulate for a scenario: its own first, then earlier ones.
std::vector<std::string> ReplayablePhysics(ScenarioKind kind, DockingKind docking);
// The physics version a config simulates, by name: config.physics, or this build's own.
std::string PhysicsOf(const ScenarioConfig& config);
// Sets config->physics to `physics` as a config keeps it: "" for this build's own (by name or
// ""), else the name (CheckConfig refuses one this build does not simulate).
void KeepPhysics(const std::string& physics, ScenarioConfig* config);
// "" when this build simulates `physics` ("" is its own), else a message that lists what it does.
std::string CheckPhysics(ScenarioKind kind, DockingKind docking, const std::string& physics);

// Checks a config; returns "" or a message naming the bad field.
std::string CheckConfig(const ScenarioConfig& config);

// What a configuration's organism and episode look like, without building its world: the one
// home of these facts for the sim, the fitness monitor, the arenas and the evolver.
struct ScenarioShape {
  int compartments = 0;       // modules (the pendulum: always 2)
  int sensors = 0;            // sensor slots per compartment
  int actuators = 0;          // actuator slots per compartment
  double control_period = 0;  // seconds per tick
  std::int64_t ticks = 0;     // ticks of a full episode
};
ScenarioShape ShapeOf(const ScenarioConfig& config);

// The docking of both scenarios' organisms: a chain, compartment i's back to i + 1's front.
std::vector<std::pair<int, int>> ChainDocking(int compartments);

// Ticks of an episode of `duration` simulated seconds (0: `default_ticks`).
std::int64_t EpisodeTicks(double duration, double control_period, std::int64_t default_ticks);

// A configuration from tool options: the pendulum ignores `modules` (it always has 2).
ScenarioConfig MakeScenarioConfig(ScenarioKind kind, DockingKind docking, int modules,
                                  double duration);

// Pose and size of one rigid body, world frame (x along the initial chain, z up), metres.
struct BodyState {
  int module = -1;  // compartment the body belongs to; -1 = scenery
  enum Shape { kBox = 0, kSphere = 1, kCylinder = 2 } shape = kBox;
  double position[3] = {0, 0, 0};
  double quaternion[4] = {1, 0, 0, 0};  // w, x, y, z
  double size[3] = {0, 0, 0};           // box: full extents; sphere: size[0] = radius
  double mass = 0;                      // kg, 0 = static
};

enum class StepStatus { kRunning, kFinished, kFailed };

class Scenario {
 public:
  virtual ~Scenario() = default;

  // Starts a new episode: every random draw of the episode comes from `seed`.
  virtual void Reset(std::uint64_t seed) = 0;

  virtual int num_compartments() const = 0;
  virtual int num_sensors() const = 0;    // sensor slots per compartment
  virtual int num_actuators() const = 0;  // actuator slots per compartment
  // Ownership masks: compartment c reads sensor j iff sensor_owned(c, j).
  virtual bool sensor_owned(int compartment, int sensor) const = 0;
  virtual bool actuator_owned(int compartment, int actuator) const = 0;
  // Docked pairs (a, b), a < b: the hormone topology.
  virtual std::vector<std::pair<int, int>> Docking() const = 0;

  // Sets a compartment's actuator values for the next Step (values in [-1, 1]; slots it does not
  // own are ignored). Values persist until set again (a lost command keeps the last one).
  virtual void SetActuators(int compartment, const double* values) = 0;
  // Called after every integration substep with the simulated time reached (seconds since the
  // episode start), e.g. to publish the state more often than once per tick.
  using SubstepObserver = std::function<void(double sim_time)>;

  // Advances one control period. After kFailed (physics blew up) the episode is over and
  // error() says why; Fitness() must not be used.
  StepStatus Step() { return Step(nullptr); }
  virtual StepStatus Step(const SubstepObserver& observer) = 0;

  // Sensor values of the current tick (noise included), num_sensors() entries; 0 where absent.
  virtual void ReadSensors(int compartment, double* values) const = 0;
  // Measured main-hinge angle of a compartment, radians (0 where there is none).
  virtual double HingeAngle(int compartment) const = 0;
  // A digital twin: the compartment's hinge servos to `angle` (radians, the angle its physical
  // counterpart reports) instead of following actuator values. False where there is no hinge.
  virtual bool FollowHinge(int /*compartment*/, double /*angle*/) { return false; }
  virtual void Bodies(std::vector<BodyState>* bodies) const = 0;

  virtual double Fitness() const = 0;  // maximised; see docs/scenarios.md
  virtual double Cost() const = 0;     // pendulum: sum of |phi|; gait: displacement, metres

  virtual std::int64_t tick() const = 0;         // control periods done in this episode
  virtual std::int64_t total_ticks() const = 0;  // ticks of a full episode
  virtual double control_period() const = 0;     // seconds
  double sim_time() const { return static_cast<double>(tick()) * control_period(); }
  virtual const std::string& error() const = 0;
};

// Throws std::invalid_argument when CheckConfig fails.
std::unique_ptr<Scenario> MakeScenario(const ScenarioConfig& config);

}  // namespace ahhs::sim
