// Drives a separate ahhs-sim process over the bus in lockstep, as the launcher and the module
// controllers would (RESET handshake, START, HINGE(t) answering SENSORS(t)), with a fixed
// closed-loop policy; then runs the same policy in-process and prints that run's fitness, which
// tests/sim/multiprocess_sim.sh compares with the fitness the sim process reports.
//   sim_driver --lcm-url URL [--scenario pendulum|gait] [--seed S] [--duration D] [--modules N]
#include <ahhs/hinge_command_t.hpp>
#include <ahhs/module_sensors_t.hpp>
#include <ahhs/sim_clock_t.hpp>
#include <ahhs/sim_control_t.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "base/cli.h"
#include "bus/channels.h"
#include "bus/lcm_bus.h"
#include "bus/typed.h"
#include "sim/core/scenario.h"

namespace cli = ahhs::base::cli;

using namespace ahhs;
using Clock = std::chrono::steady_clock;

namespace {
// Deterministic closed-loop policies, one value per compartment.
double Policy(const std::string& scenario, int module, std::int64_t tick, const double* s) {
  if (scenario == "pendulum")
    return module == 0 ? std::clamp(s[0] - s[2] + 0.3 * s[8], -1.0, 1.0)
                       : std::clamp(s[1] - s[3] - 0.3 * s[9], -1.0, 1.0);
  const double t = 0.05 * static_cast<double>(tick);
  return std::clamp(0.8 * std::sin(2 * M_PI * 0.5 * t - module * M_PI / 2) + 0.1 * (s[1] - s[3]),
                    -1.0, 1.0);
}
}  // namespace

int main(int argc, char** argv) {
  cli::App app{"test driver for a separate ahhs-sim process"};
  std::string url, scenario = "pendulum";
  std::int64_t seed = 1;
  double duration = 5;
  int modules = 5;
  app.add_option("--lcm-url", url)->required();
  app.add_option("--scenario", scenario);
  app.add_option("--seed", seed);
  app.add_option("--duration", duration);
  app.add_option("--modules", modules);
  if (const int code = ahhs::base::Parse(app, argc, argv); code >= 0) return code;

  bus::LcmBus bus(url);
  bus::ArenaChannels ch;
  const std::int64_t episode = 4242;
  std::int8_t run_state = -1;
  std::int64_t last_tick = -1;
  auto subscription_53 = bus::SubscribeTyped<sim_clock_t>(
      bus, ch.SimClock(), [&](const std::string&, const sim_clock_t& c) {
        if (c.episode != episode) return;
        run_state = c.run_state;
        last_tick = c.tick;
      });
  auto subscription_59 = bus::SubscribeTyped<module_sensors_t>(
      bus, "AHHS/MODULE[0-9]+/SENSORS", [&](const std::string&, const module_sensors_t& m) {
        if (m.episode != episode) return;
        hinge_command_t h{};
        h.utime = bus::NowUtime();
        h.episode = episode;
        h.tick = m.tick;
        h.module = m.module;
        h.num_actuators = static_cast<std::int16_t>(scenario == "pendulum" ? 2 : 1);
        h.values.assign(static_cast<std::size_t>(h.num_actuators), 0.0);
        h.present.assign(static_cast<std::size_t>(h.num_actuators), scenario != "pendulum");
        const auto own = static_cast<std::size_t>(scenario == "pendulum" ? m.module : 0);
        h.values[own] = Policy(scenario, m.module, m.tick, m.values.data());
        h.present[own] = true;
        h.target_angle = 0;
        bus::PublishTyped(bus, ch.Hinge(m.module), h);
      });

  sim_control_t c{};
  c.episode = episode;
  c.seed = seed;
  c.scenario = scenario;
  c.num_modules = modules;
  c.joints = sim_control_t::JOINTS_DAMPED;
  c.duration = duration;
  c.clock_mode = sim_control_t::MODE_LOCKSTEP;
  // Handshake: repeat RESET until the sim's clock says it is ready (the sim may start later).
  const auto give_up = Clock::now() + std::chrono::seconds(10);
  while (run_state != sim_clock_t::RESET && Clock::now() < give_up) {
    c.command = sim_control_t::RESET;
    c.utime = bus::NowUtime();
    bus::PublishTyped(bus, ch.SimControl(), c);
    bus.Handle(std::chrono::milliseconds(100));
  }
  if (run_state != sim_clock_t::RESET) {
    std::fprintf(stderr, "sim_driver: the sim never acknowledged RESET\n");
    return 1;
  }
  c.command = sim_control_t::START;
  bus::PublishTyped(bus, ch.SimControl(), c);
  const auto deadline = Clock::now() + std::chrono::seconds(60);
  while (run_state != sim_clock_t::FINISHED && run_state != sim_clock_t::FAILED &&
         Clock::now() < deadline)
    bus.Handle(std::chrono::milliseconds(100));
  if (run_state != sim_clock_t::FINISHED) {
    std::fprintf(stderr, "sim_driver: episode did not finish (state %d)\n", run_state);
    return 1;
  }

  sim::ScenarioConfig config;
  config.kind = sim::ParseScenarioKind(scenario);
  config.num_modules = modules;
  config.duration = duration;
  auto direct = sim::MakeScenario(config);
  direct->Reset(static_cast<std::uint64_t>(seed));
  std::vector<double> s(static_cast<std::size_t>(direct->num_sensors())),
      a(static_cast<std::size_t>(direct->num_actuators()));
  while (true) {
    for (int m = 0; m < direct->num_compartments(); ++m) {
      direct->ReadSensors(m, s.data());
      std::fill(a.begin(), a.end(), 0.0);
      a[static_cast<std::size_t>(scenario == "pendulum" ? m : 0)] =
          Policy(scenario, m, direct->tick(), s.data());
      direct->SetActuators(m, a.data());
    }
    if (direct->Step() != sim::StepStatus::kRunning) break;
  }
  std::printf("bus ticks: %lld\n", static_cast<long long>(last_tick));
  std::printf("direct ticks: %lld\n", static_cast<long long>(direct->tick()));
  std::printf("fitness %.17g\n", direct->Fitness());
  return 0;
}
