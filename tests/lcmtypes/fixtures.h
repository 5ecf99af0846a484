// One fixed, fully populated message of every ahhs type, for golden-bytes and codec tests.
// Values are chosen so that every field is non-zero and distinguishable.
#pragma once

#include <ahhs/eval_request_t.hpp>
#include <ahhs/eval_result_t.hpp>
#include <ahhs/fitness_t.hpp>
#include <ahhs/genome_t.hpp>
#include <ahhs/hinge_command_t.hpp>
#include <ahhs/hormone_packet_t.hpp>
#include <ahhs/module_sensors_t.hpp>
#include <ahhs/module_status_t.hpp>
#include <ahhs/sim_clock_t.hpp>
#include <ahhs/sim_control_t.hpp>
#include <ahhs/sim_state_t.hpp>
#include <ahhs/topology_t.hpp>
#include <ahhs/worker_status_t.hpp>

namespace ahhs::testing {

template <class Msg>
Msg Fixture();

template <>
inline module_sensors_t Fixture<module_sensors_t>() {
  module_sensors_t m;
  m.utime = 1700000000000001;
  m.episode = 42;
  m.tick = 7;
  m.module = 3;
  m.sim_time = 0.35;
  m.num_sensors = 4;
  m.values = {0.0, 0.25, 0.5, 1.0};
  m.present = {true, true, false, true};
  m.hinge_angle = -0.5;
  m.num_actuators = 2;
  m.actuator_present = {false, true};
  return m;
}

template <>
inline hinge_command_t Fixture<hinge_command_t>() {
  hinge_command_t m;
  m.utime = 1700000000000002;
  m.episode = 42;
  m.tick = 7;
  m.module = 3;
  m.num_actuators = 2;
  m.values = {-1.0, 0.75};
  m.present = {true, false};
  m.target_angle = -1.5707963267948966;
  return m;
}

template <>
inline hormone_packet_t Fixture<hormone_packet_t>() {
  hormone_packet_t m;
  m.utime = 1700000000000003;
  m.episode = 42;
  m.tick = 7;
  m.from_module = 1;
  m.to_module = 2;
  m.num_hormones = 3;
  m.amounts = {0.125, 0.0, 0.5};
  return m;
}

template <>
inline module_status_t Fixture<module_status_t>() {
  module_status_t m;
  m.utime = 1700000000000004;
  m.episode = 42;
  m.tick = 7;
  m.module = 3;
  m.state = module_status_t::RUNNING;
  m.genome_hash = 0x0123456789abcdefLL;
  m.missed_ticks = 1;
  m.late_messages = 2;
  m.dropped_messages = 5;
  m.message = "ok";
  return m;
}

template <>
inline topology_t Fixture<topology_t>() {
  topology_t m;
  m.utime = 1700000000000005;
  m.episode = 42;
  m.tick = 0;
  m.num_modules = 3;
  m.ports_per_module = 4;
  m.num_links = 2;
  m.module_a = {0, 1};
  m.port_a = {2, 2};
  m.module_b = {1, 2};
  m.port_b = {0, 0};
  return m;
}

template <>
inline sim_control_t Fixture<sim_control_t>() {
  sim_control_t m;
  m.utime = 1700000000000006;
  m.command = sim_control_t::RESET;
  m.episode = 42;
  m.seed = 123456789;
  m.scenario = "gait";
  m.num_modules = 5;
  m.joints = sim_control_t::JOINTS_FIXED;
  m.duration = 60.0;
  m.clock_mode = sim_control_t::MODE_LOCKSTEP;
  m.steps = 10;
  return m;
}

template <>
inline sim_clock_t Fixture<sim_clock_t>() {
  sim_clock_t m;
  m.utime = 1700000000000007;
  m.episode = 42;
  m.tick = 7;
  m.sim_time = 0.35;
  m.control_period = 0.05;
  m.clock_mode = sim_clock_t::MODE_REALTIME;
  m.run_state = sim_clock_t::RUNNING;
  return m;
}

template <>
inline sim_state_t Fixture<sim_state_t>() {
  sim_state_t m;
  m.utime = 1700000000000008;
  m.episode = 42;
  m.tick = 7;
  m.sim_time = 0.35;
  m.num_bodies = 2;
  m.module = {0, -1};
  m.shape = {sim_state_t::SHAPE_BOX, sim_state_t::SHAPE_SPHERE};
  m.px = {0.1, 1.0};
  m.py = {0.2, 0.0};
  m.pz = {0.05, 0.5};
  m.qw = {1.0, 0.5};
  m.qx = {0.0, 0.5};
  m.qy = {0.0, 0.5};
  m.qz = {0.0, 0.5};
  m.sx = {0.05, 0.02};
  m.sy = {0.1, 0.0};
  m.sz = {0.1, 0.0};
  m.mass = {0.25, 0.0};
  return m;
}

template <>
inline genome_t Fixture<genome_t>() {
  genome_t m;
  m.utime = 1700000000000009;
  m.episode = 42;
  m.genome_hash = -77;
  m.variant = genome_t::AHHS1;
  m.num_sensors = 4;
  m.num_actuators = 1;
  m.num_hormones = 2;
  m.alpha = {0.01, 0.02};
  m.mu = {0.1, 0.2};
  m.diffusion = {0.3, 0.4};
  m.num_rules = 1;
  m.fields_per_rule = 7;
  m.num_rule_values = 7;
  m.rule_values = {1, 2, 0, 0.5, 1, -0.25, 0.125};
  return m;
}

template <>
inline fitness_t Fixture<fitness_t>() {
  fitness_t m;
  m.utime = 1700000000000010;
  m.episode = 42;
  m.tick = 1199;
  m.sim_time = 60.0;
  m.fitness = 0.7;
  m.cost = 1.0;
  m.is_final = true;
  m.status = fitness_t::OK;
  m.states_seen = 1200;
  m.states_missed = 0;
  m.message = "";
  return m;
}

template <>
inline eval_request_t Fixture<eval_request_t>() {
  eval_request_t m;
  m.utime = 1700000000000011;
  m.protocol_version = 1;
  m.run = "run-1";
  m.job = 17;
  m.attempt = 1;
  m.worker = "host:123";
  m.scenario = "pendulum";
  m.num_modules = 2;
  m.joints = 0;
  m.duration = 150.0;
  m.seed = 99;
  m.deadline_utime = 1700000000500000;
  m.genome = Fixture<genome_t>();
  m.genome.episode = 0;
  return m;
}

template <>
inline eval_result_t Fixture<eval_result_t>() {
  eval_result_t m;
  m.utime = 1700000000000012;
  m.protocol_version = 1;
  m.run = "run-1";
  m.job = 17;
  m.attempt = 1;
  m.worker = "host:123";
  m.status = eval_result_t::OK;
  m.fitness = 0.42;
  m.cost = 2.5;
  m.wall_time = 0.125;
  m.late_messages = 0;
  m.message = "";
  return m;
}

template <>
inline worker_status_t Fixture<worker_status_t>() {
  worker_status_t m;
  m.utime = 1700000000000013;
  m.protocol_version = 1;
  m.worker = "host:123";
  m.host = "host";
  m.slots = 2;
  m.free_slots = 1;
  m.evaluations_done = 1000;
  m.num_jobs = 1;
  m.jobs = {17};
  m.run = "run-1";
  return m;
}

}  // namespace ahhs::testing
