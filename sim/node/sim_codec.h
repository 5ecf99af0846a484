// Scenario state <-> LCM messages (pure functions; no transport).
#pragma once

#include <ahhs/hinge_command_t.hpp>
#include <ahhs/module_sensors_t.hpp>
#include <ahhs/sim_clock_t.hpp>
#include <ahhs/sim_control_t.hpp>
#include <ahhs/sim_state_t.hpp>
#include <ahhs/topology_t.hpp>
#include <string>
#include <vector>

#include "sim/core/scenario.h"

namespace ahhs::sim {

module_sensors_t SensorsMessage(const Scenario& scenario, int module, std::int64_t episode);
sim_state_t StateMessage(const std::vector<BodyState>& bodies, std::int64_t episode,
                         std::int64_t tick, double sim_time);
// The same, filling *m in place: its arrays keep their capacity, so a sim that reuses one
// message per kind allocates nothing per tick. utime is left as it was.
void FillSensorsMessage(const Scenario& scenario, int module, std::int64_t episode,
                        module_sensors_t* m);
void FillStateMessage(const std::vector<BodyState>& bodies, std::int64_t episode, std::int64_t tick,
                      double sim_time, sim_state_t* m);
topology_t TopologyMessage(const Scenario& scenario, std::int64_t episode);
// SIM/CLOCK of `episode` at `tick` (sim_time = tick x control_period); the sender sets utime.
sim_clock_t ClockMessage(std::int64_t episode, std::int64_t tick, double control_period,
                         bool realtime, std::int8_t run_state);
// The same from an organism's shape alone (the episode server has no Scenario).
topology_t TopologyMessage(int compartments, const std::vector<std::pair<int, int>>& docking,
                           std::int64_t episode, std::int64_t tick);

// SIM/STATE carries the bodies that move (mass > 0), SIM/SCENE the static ones (mass 0: walls,
// cubes), so the state stream does not repeat what never changes. Keeps, in order, the bodies
// of that kind and drops the others.
void KeepMovingBodies(std::vector<BodyState>* bodies);
void KeepStaticBodies(std::vector<BodyState>* bodies);
// SIM/SCENE goes out at the start of tick 0 (with RESET) and of every 20th tick after it (once
// per gait second, for late joiners); its tick and sim_time are the tick's start.
inline constexpr std::int64_t kSceneEveryTicks = 20;
inline bool SceneDue(std::int64_t tick) { return tick % kSceneEveryTicks == 0; }

// The one wire form of a ScenarioConfig: the fields (scenario, num_modules, docking, duration,
// the envelope's half-widths, the pendulum's choices, the physics version) that sim_control_t
// (RESET) and eval_request_t both carry. The physics always travels by name (this build's when
// the config asks for "its own"), so that a receiver of another build never answers in another
// physics unnoticed.
std::int8_t DockingToWire(DockingKind docking);
// Checks the fields and makes the config (physics "" or this build's own becomes ""); returns ""
// or why they are refused.
std::string ScenarioFromFields(const std::string& scenario, std::int32_t num_modules,
                               std::int8_t docking, double duration, const Envelope& envelope,
                               double pendulum_actuator_gain, std::int8_t pendulum_walls,
                               const std::string& physics, ScenarioConfig* config);
template <class Message>
void ScenarioToWire(const ScenarioConfig& config, Message* m) {
  m->scenario = ScenarioName(config.kind);
  m->num_modules = ShapeOf(config).compartments;
  m->joints = DockingToWire(config.docking);
  m->duration = config.duration;
  const Envelope& e = config.envelope;
  m->envelope_friction = e.friction;
  m->envelope_mass = e.mass;
  m->envelope_servo_torque = e.servo_torque;
  m->envelope_servo_speed = e.servo_speed;
  m->envelope_start_heading = e.start_heading;
  m->envelope_start_offset = e.start_offset;
  m->envelope_sensor_noise = e.sensor_noise;
  m->envelope_start_angle = e.start_angle;
  m->envelope_cart_speed = e.cart_speed;
  m->envelope_command_delay = e.command_delay;
  m->envelope_start_hinge = e.start_hinge;
  m->pendulum_actuator_gain = config.pendulum.actuator_gain;
  m->pendulum_walls = config.pendulum.walls == PendulumWalls::kSoft ? 1 : 0;
  m->physics = PhysicsOf(config);
}
template <class Message>
std::string ScenarioFromWire(const Message& m, ScenarioConfig* config) {
  Envelope e;
  e.friction = m.envelope_friction;
  e.mass = m.envelope_mass;
  e.servo_torque = m.envelope_servo_torque;
  e.servo_speed = m.envelope_servo_speed;
  e.start_heading = m.envelope_start_heading;
  e.start_offset = m.envelope_start_offset;
  e.sensor_noise = m.envelope_sensor_noise;
  e.start_angle = m.envelope_start_angle;
  e.cart_speed = m.envelope_cart_speed;
  e.command_delay = m.envelope_command_delay;
  e.start_hinge = m.envelope_start_hinge;
  return ScenarioFromFields(m.scenario, m.num_modules, m.joints, m.duration, e,
                            m.pendulum_actuator_gain, m.pendulum_walls, m.physics, config);
}

// Validates a RESET and turns it into a scenario config; returns "" or why it is refused.
std::string ConfigFromReset(const sim_control_t& reset, ScenarioConfig* config);

// Checks a hinge command against the scenario: module id, sizes, finite values in [-1, 1] for
// the slots it owns. Returns "" or why it is dropped.
std::string CheckHinge(const hinge_command_t& cmd, const Scenario& scenario);

}  // namespace ahhs::sim
