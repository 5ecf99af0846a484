// The simulator's protocol role over memq://, driven by fake modules in the test.
#include "sim/node/sim_node.h"

#include <ahhs/module_sensors_t.hpp>
#include <ahhs/sim_clock_t.hpp>
#include <ahhs/sim_state_t.hpp>
#include <ahhs/topology_t.hpp>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <set>

#include "bus/lcm_bus.h"
#include "sim/core/pendulum.h"

using namespace ahhs;
using namespace std::chrono_literals;

namespace {

const double kPeriod = sim::PendulumConstants{}.control_period;  // s per pendulum tick

sim_control_t Control(std::int8_t command, std::int64_t episode) {
  sim_control_t m{};
  m.command = command;
  m.episode = episode;
  m.scenario = "pendulum";
  m.num_modules = 2;
  m.joints = sim_control_t::JOINTS_DAMPED;
  m.clock_mode = sim_control_t::MODE_LOCKSTEP;
  return m;
}

// A deterministic closed-loop policy: each compartment drives its own actuator from its sensors.
double Policy(int compartment, const double* s) {
  return compartment == 0 ? std::clamp(s[0] - s[2] + 0.3 * s[8], -1.0, 1.0)
                          : std::clamp(s[1] - s[3] - 0.3 * s[9], -1.0, 1.0);
}

// Fake modules: answer SENSORS(t) with HINGE(t) computed by Policy.
struct FakeModules {
  bus::Bus& bus;
  bus::ArenaChannels ch;
  std::int64_t episode;
  std::set<int> silent;                  // modules that do not answer (until Release)
  std::map<int, module_sensors_t> held;  // the last SENSORS a silent module got
  int sensors_seen = 0;
  bus::Subscription subscription;
  FakeModules(bus::Bus& b, std::int64_t ep) : bus(b), episode(ep) {
    subscription = bus::SubscribeTyped<module_sensors_t>(
        bus, "AHHS/MODULE[0-9]+/SENSORS", [this](const std::string&, const module_sensors_t& m) {
          ++sensors_seen;
          if (silent.count(m.module)) {
            held[m.module] = m;
            return;
          }
          Answer(m);
        });
  }
  // A silent module answers what it holds, late, and from then on every tick.
  void Release(int module) {
    silent.erase(module);
    if (held.count(module)) Answer(held[module]);
  }
  void Answer(const module_sensors_t& m) {
    hinge_command_t h{};
    h.episode = m.episode;
    h.tick = m.tick;
    h.module = m.module;
    h.num_actuators = 2;
    h.values = {0, 0};
    h.present = {m.module == 0, m.module == 1};
    h.values[static_cast<std::size_t>(m.module)] = Policy(m.module, m.values.data());
    h.target_angle = std::nan("");
    bus::PublishTyped(bus, ch.Hinge(m.module), h);
  }
};

// The fitness of Policy run in-process for `ticks` from `seed`.
double InProcessFitness(std::uint64_t seed, int ticks) {
  sim::ScenarioConfig config;
  config.kind = sim::ScenarioKind::kPendulum;
  config.duration = ticks * kPeriod;
  sim::PendulumScenario direct(config);
  direct.Reset(seed);
  double s[10], a[2];
  while (true) {
    for (int c = 0; c < 2; ++c) {
      direct.ReadSensors(c, s);
      a[0] = a[1] = 0;
      a[c] = Policy(c, s);
      direct.SetActuators(c, a);
    }
    if (direct.Step() != sim::StepStatus::kRunning) break;
  }
  return direct.Fitness();
}

void RunToEnd(sim::SimNode& node) {
  for (int k = 0; k < 100000 && node.phase() == sim::SimNode::Phase::kRunning; ++k) node.Poll(10ms);
}

}  // namespace

TEST_CASE("lockstep over the bus equals the same policy run in-process, bit for bit",
          "[sim][node]") {
  bus::LcmBus bus("memq://");
  sim::SimNode node(&bus, {});
  FakeModules modules(bus, 7);
  int states = 0, clocks = 0, topologies = 0, scenes = 0;
  double last_state_time = -1;
  // SIM/STATE: the cart and the bob (they move); SIM/SCENE: the two walls (static, mass 0).
  auto subscription_79 = bus::SubscribeTyped<sim_state_t>(
      bus, "AHHS/SIM/STATE", [&](const std::string&, const sim_state_t& m) {
        ++states;
        CHECK(m.sim_time >= last_state_time);
        // on a tick boundary, numbered by the control periods done (as ahhs-replay logs it)
        CHECK(std::fabs(m.sim_time / kPeriod - std::round(m.sim_time / kPeriod)) < 1e-6);
        CHECK(m.tick == std::llround(m.sim_time / kPeriod));
        last_state_time = m.sim_time;
        REQUIRE(m.num_bodies == 2);
        CHECK(m.module[0] == 0);
        CHECK(m.mass[0] > 0);
        CHECK(m.mass[1] > 0);
      });
  auto subscription_91 = bus::SubscribeTyped<sim_state_t>(
      bus, "AHHS/SIM/SCENE", [&](const std::string&, const sim_state_t& m) {
        ++scenes;
        REQUIRE(m.num_bodies == 2);
        CHECK(m.mass[0] == 0);
        CHECK(m.px[0] == -m.px[1]);  // the walls, symmetric
        CHECK(m.px[1] > 1.0);
      });
  auto subscription_99 = bus::SubscribeTyped<sim_clock_t>(
      bus, "AHHS/SIM/CLOCK", [&](const std::string&, const sim_clock_t&) { ++clocks; });
  auto subscription_101 = bus::SubscribeTyped<topology_t>(
      bus, "AHHS/TOPOLOGY", [&](const std::string&, const topology_t& t) {
        ++topologies;
        CHECK(t.num_links == 1);
      });

  auto reset = Control(sim_control_t::RESET, 7);
  reset.seed = 99;
  reset.duration = 400 * kPeriod;
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", reset);
  node.Poll(10ms);
  REQUIRE(node.phase() == sim::SimNode::Phase::kReady);
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", Control(sim_control_t::START, 7));
  node.Poll(10ms);
  RunToEnd(node);
  REQUIRE(node.phase() == sim::SimNode::Phase::kFinished);
  CHECK(node.stats().missed_commands == 0);
  CHECK(node.stats().ticks == 400);

  CHECK(node.scenario()->Fitness() == InProcessFitness(99, 400));  // the same policy
  CHECK(node.scenario()->Fitness() != 0.0);
  bus.Handle(0us);
  // Lockstep: one state per tick boundary (what the fitness monitor uses), plus the one at reset
  // and the final one; the clock at RESET, at the start, once per simulated second (ticks 20,
  // 40, ..., 380) and three times at the end.
  CHECK(states == 1 + 400 + 1);
  CHECK(clocks == 1 + 1 + 19 + 3);
  CHECK(topologies == 1);
  CHECK(scenes == 1 + 400 / 20 - 1);  // at reset, then every 20 ticks (20, 40, ..., 380)
}

TEST_CASE("bad commands are counted and dropped, a silent module times out", "[sim][node]") {
  bus::LcmBus bus("memq://");
  sim::SimNodeOptions options;
  options.lockstep_timeout = 5ms;
  sim::SimNode node(&bus, options);
  FakeModules modules(bus, 3);
  modules.silent = {1};
  auto reset = Control(sim_control_t::RESET, 3);
  reset.duration = 20 * kPeriod;
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", reset);
  node.Poll(1ms);
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", Control(sim_control_t::START, 3));
  node.Poll(1ms);
  // Garbage, a foreign episode, NaN, a module speaking for another, a future tick.
  const char junk[] = "garbage";
  bus.Publish("AHHS/MODULE1/HINGE", junk, sizeof junk);
  hinge_command_t h{};
  h.episode = 4;
  h.module = 1;
  h.num_actuators = 2;
  h.values = {0, 1};
  h.present = {false, true};
  bus::PublishTyped(bus, "AHHS/MODULE1/HINGE", h);
  h.episode = 3;
  h.values = {0, std::nan("")};
  bus::PublishTyped(bus, "AHHS/MODULE1/HINGE", h);
  h.values = {0, 1};
  bus::PublishTyped(bus, "AHHS/MODULE0/HINGE", h);
  h.tick = 1000;
  bus::PublishTyped(bus, "AHHS/MODULE1/HINGE", h);
  RunToEnd(node);
  REQUIRE(node.phase() == sim::SimNode::Phase::kFinished);
  CHECK(node.stats().dropped_messages == 5);
  CHECK(node.stats().missed_commands == 20);  // module 1, every tick
  // None of the dropped messages reached the physics: the run equals one where module 1's
  // actuator stayed 0 throughout.
  sim::ScenarioConfig config;
  config.kind = sim::ScenarioKind::kPendulum;
  config.duration = 20 * kPeriod;
  sim::PendulumScenario direct(config);
  direct.Reset(0);
  double s[10], a[2] = {0, 0};
  while (true) {
    direct.ReadSensors(0, s);
    a[0] = Policy(0, s);
    direct.SetActuators(0, a);
    if (direct.Step() != sim::StepStatus::kRunning) break;
  }
  const auto& p = static_cast<const sim::PendulumScenario&>(*node.scenario());
  CHECK(p.state().x == direct.state().x);
  CHECK(p.Fitness() == direct.Fitness());
}

TEST_CASE("exact lockstep waits for a stalled module as long as it takes: the run is unchanged",
          "[sim][node]") {
  bus::LcmBus bus("memq://");
  sim::SimNodeOptions options;
  options.lockstep_timeout = 0ms;  // exact
  sim::SimNode node(&bus, options);
  FakeModules modules(bus, 5);
  auto reset = Control(sim_control_t::RESET, 5);
  reset.seed = 99;
  reset.duration = 60 * kPeriod;
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", reset);
  node.Poll(1ms);
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", Control(sim_control_t::START, 5));
  for (int k = 0; k < 10; ++k) node.Poll(1ms);  // some ticks with both modules
  modules.silent = {1};                         // module 1 stops answering
  for (int k = 0; k < 3; ++k) node.Poll(1ms);
  const auto stalled_at = node.scenario()->tick();
  REQUIRE(stalled_at > 0);
  for (int k = 0; k < 30; ++k) node.Poll(10ms);  // 300 ms: 60 times a 5 ms timeout
  CHECK(node.scenario()->tick() == stalled_at);
  CHECK(node.phase() == sim::SimNode::Phase::kRunning);
  CHECK(node.stats().missed_commands == 0);
  modules.Release(1);
  RunToEnd(node);
  REQUIRE(node.phase() == sim::SimNode::Phase::kFinished);
  CHECK(node.stats().missed_commands == 0);
  CHECK(node.stats().late_commands == 0);
  CHECK(node.scenario()->Fitness() == InProcessFitness(99, 60));
}

TEST_CASE("STEP advances exactly N ticks, PAUSE holds, STOP ends", "[sim][node]") {
  bus::LcmBus bus("memq://");
  sim::SimNode node(&bus, {});
  FakeModules modules(bus, 5);
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", Control(sim_control_t::RESET, 5));
  node.Poll(1ms);
  auto step = Control(sim_control_t::STEP, 5);
  step.steps = 7;
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", step);
  for (int k = 0; k < 100; ++k) node.Poll(1ms);
  CHECK(node.phase() == sim::SimNode::Phase::kPaused);
  CHECK(node.scenario()->tick() == 7);
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", Control(sim_control_t::START, 5));
  for (int k = 0; k < 10; ++k) node.Poll(1ms);
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", Control(sim_control_t::PAUSE, 5));
  node.Poll(1ms);
  const auto held = node.scenario()->tick();
  CHECK(held > 7);
  for (int k = 0; k < 10; ++k) node.Poll(1ms);
  CHECK(node.scenario()->tick() == held);
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", Control(sim_control_t::STOP, 6));  // another episode
  node.Poll(1ms);
  CHECK(node.phase() == sim::SimNode::Phase::kPaused);
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", Control(sim_control_t::STOP, 5));
  node.Poll(1ms);
  CHECK(node.phase() == sim::SimNode::Phase::kFinished);
}

TEST_CASE("a bad reset is refused with a reason", "[sim][node]") {
  bus::LcmBus bus("memq://");
  sim::SimNode node(&bus, {});
  auto reset = Control(sim_control_t::RESET, 1);
  reset.scenario = "walker";
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", reset);
  node.Poll(1ms);
  CHECK(node.phase() == sim::SimNode::Phase::kIdle);
  CHECK_THAT(node.stats().last_error, Catch::Contains("unknown scenario"));
  reset.scenario = "gait";
  reset.num_modules = 1;
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", reset);
  node.Poll(1ms);
  CHECK(node.stats().refused_resets == 2);
}

TEST_CASE("a late copy of RESET does not restart the episode it belongs to", "[sim][node]") {
  // The launcher repeats RESET until the sim answers; datagrams of two senders can overtake each
  // other, so a repeat may arrive after START.
  bus::LcmBus bus("memq://");
  sim::SimNode node(&bus, {});
  FakeModules modules(bus, 3);
  auto reset = Control(sim_control_t::RESET, 3);
  reset.seed = 5;
  reset.duration = 20 * kPeriod;
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", reset);
  node.Poll(1ms);
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", reset);  // a repeat before START: answered again
  node.Poll(1ms);
  CHECK(node.stats().episodes == 2);
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", Control(sim_control_t::START, 3));
  for (int k = 0; k < 1000 && node.scenario()->tick() < 5; ++k) node.Poll(1ms);
  REQUIRE(node.scenario()->tick() >= 5);
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", reset);  // late
  RunToEnd(node);
  REQUIRE(node.phase() == sim::SimNode::Phase::kFinished);
  CHECK(node.stats().ticks == 20);
  CHECK(node.stats().episodes == 2);
  CHECK(node.stats().dropped_messages == 1);
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", reset);  // after the end: still the same episode
  node.Poll(1ms);
  CHECK(node.phase() == sim::SimNode::Phase::kFinished);
  reset.episode = 4;  // a new episode id starts afresh
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", reset);
  node.Poll(1ms);
  CHECK(node.phase() == sim::SimNode::Phase::kReady);
}

TEST_CASE("real time: the latest command is used whatever tick it answered", "[sim][node]") {
  bus::LcmBus bus("memq://");
  sim::SimNode node(&bus, {});
  int states = 0, clocks = 0;
  auto subscription_281 = bus::SubscribeTyped<sim_state_t>(
      bus, "AHHS/SIM/STATE", [&](const std::string&, const sim_state_t&) { ++states; });
  auto subscription_283 = bus::SubscribeTyped<sim_clock_t>(
      bus, "AHHS/SIM/CLOCK", [&](const std::string&, const sim_clock_t&) { ++clocks; });
  auto reset = Control(sim_control_t::RESET, 9);
  reset.clock_mode = sim_control_t::MODE_REALTIME;
  reset.duration = 20 * kPeriod;  // 0.35 s of wall time
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", reset);
  node.Poll(1ms);
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", Control(sim_control_t::START, 9));
  node.Poll(1ms);
  hinge_command_t h{};
  h.episode = 9;
  h.tick = 0;
  h.module = 1;
  h.num_actuators = 2;
  h.values = {0, 1};
  h.present = {false, true};
  bus::PublishTyped(bus, "AHHS/MODULE1/HINGE", h);  // sent once, used every tick
  RunToEnd(node);
  REQUIRE(node.phase() == sim::SimNode::Phase::kFinished);
  CHECK(node.stats().missed_commands == 0);
  const auto& p = static_cast<const sim::PendulumScenario&>(*node.scenario());
  CHECK(p.state().x > 0.05);  // pushed right all along
  bus.Handle(0us);
  // Real time: STATE at 40 Hz for viewers (14 in 0.35 s, plus reset and final); the clock at
  // RESET, every tick, and three times at the end.
  CHECK(states == 1 + 14 + 1);
  CHECK(clocks == 1 + 20 + 3);
}

TEST_CASE("a hardware module: no SENSORS from the sim, its body follows the reported hinge angle",
          "[sim][node][wall]") {
  bus::LcmBus bus("memq://");
  sim::SimNodeOptions options;
  options.hardware_modules = {1};
  sim::SimNode node(&bus, options);
  std::set<int> sensors_from_sim;
  auto sensors = bus::SubscribeTyped<module_sensors_t>(
      bus, "AHHS/MODULE[0-9]+/SENSORS", [&](const std::string&, const module_sensors_t& m) {
        if (m.num_sensors != 1) sensors_from_sim.insert(m.module);  // ours have 1 slot
      });
  auto reset = Control(sim_control_t::RESET, 12);
  reset.scenario = "gait";
  reset.num_modules = 3;
  reset.duration = 1.0;                               // 20 ticks of 50 ms
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", reset);  // lockstep: refused
  node.Poll(1ms);
  CHECK(node.phase() == sim::SimNode::Phase::kIdle);
  CHECK_THAT(node.stats().last_error, Catch::Contains("need real time"));
  reset.clock_mode = sim_control_t::MODE_REALTIME;
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", reset);
  node.Poll(1ms);
  REQUIRE(node.phase() == sim::SimNode::Phase::kReady);
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", Control(sim_control_t::START, 12));
  module_sensors_t firmware{};
  firmware.episode = 12;
  firmware.module = 1;
  firmware.num_sensors = 1;
  firmware.values = {0.5};
  firmware.present = {true};
  firmware.hinge_angle = 0.6;  // radians: the real hinge stands there
  firmware.num_actuators = 1;
  firmware.actuator_present = {true};
  while (node.phase() != sim::SimNode::Phase::kFinished) {
    firmware.tick = node.scenario()->tick();
    bus::PublishTyped(bus, "AHHS/MODULE1/SENSORS", firmware);
    node.Poll(5ms);
  }
  bus.Handle(0us);
  CHECK(sensors_from_sim == std::set<int>{0, 2});
  CHECK(node.stats().twin_readings >= 15);
  CHECK(node.scenario()->HingeAngle(1) == Approx(0.6).margin(0.05));
  CHECK(std::abs(node.scenario()->HingeAngle(0)) < 0.05);  // no command: it stays straight

  auto pendulum = Control(sim_control_t::RESET, 13);
  pendulum.clock_mode = sim_control_t::MODE_REALTIME;
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", pendulum);
  node.Poll(1ms);
  CHECK(node.episode() == 12);
  CHECK_THAT(node.stats().last_error, Catch::Contains("only the gait"));
}
