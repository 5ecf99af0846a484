// ahhs-sim: the ODE arena. Standalone mode (--drive) runs one episode with built-in commands
// and prints "fitness: <value>" as its last line.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <iostream>

#include "sim/core/drive.h"
#include "sim/core/scenario.h"

namespace as = ahhs::sim;

int main(int argc, char** argv) {
  CLI::App app{"ahhs-sim: physics of the gait and pendulum arenas"};
  std::string scenario = "gait", joints = "damped", drive = "zero";
  int modules = 5;
  double duration = 0;
  std::uint64_t seed = 1;
  bool verbose = false;
  app.add_option("--scenario", scenario, "gait or pendulum")->capture_default_str();
  app.add_option("--drive", drive, "built-in commands: zero or wave")->capture_default_str();
  app.add_option("--joints", joints, "gait docking: damped or fixed")->capture_default_str();
  app.add_option("--modules", modules, "gait: modules in the chain (>= 2)")->capture_default_str();
  app.add_option("--seed", seed, "episode seed")->capture_default_str();
  app.add_option("--duration", duration, "episode length, simulated seconds (default: the task's)");
  app.add_flag("-v,--verbose", verbose, "print the state once per simulated second");
  CLI11_PARSE(app, argc, argv);

  try {
    as::ScenarioConfig config;
    config.kind = as::ParseScenarioKind(scenario);
    config.joints = as::ParseJoints(joints);
    config.num_modules = config.kind == as::ScenarioKind::kPendulum ? 2 : modules;
    if (app.count("--duration") && !(duration > 0))
      throw std::invalid_argument("--duration must be a positive number of seconds");
    config.duration = duration;
    if (config.kind == as::ScenarioKind::kGait && modules < 2)
      throw std::invalid_argument("--modules: a gait organism needs at least 2 modules");
    const as::DriveKind drive_kind = as::ParseDrive(drive);
    auto sim = as::MakeScenario(config);
    sim->Reset(seed);
    std::vector<double> command(static_cast<std::size_t>(sim->num_actuators()));
    const auto t0 = std::chrono::steady_clock::now();
    as::StepStatus status = as::StepStatus::kRunning;
    while (status == as::StepStatus::kRunning) {
      for (int c = 0; c < sim->num_compartments(); ++c) {
        as::DriveCommand(drive_kind, *sim, c, command.data());
        sim->SetActuators(c, command.data());
      }
      status = sim->Step();
      if (verbose && sim->tick() % static_cast<std::int64_t>(1.0 / sim->control_period()) == 0)
        std::printf("t %7.2f s  fitness %.6f  cost %.6f\n", sim->sim_time(), sim->Fitness(),
                    sim->Cost());
    }
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (status == as::StepStatus::kFailed) {
      std::cerr << "ahhs-sim: episode failed: " << sim->error() << '\n';
      return 2;
    }
    std::printf(
        "scenario %s, drive %s, seed %llu: %lld ticks, %.1f s simulated in %.3f s wall (%.0fx real "
        "time)\n",
        as::ScenarioName(config.kind), drive.c_str(), static_cast<unsigned long long>(seed),
        static_cast<long long>(sim->tick()), sim->sim_time(), wall, sim->sim_time() / wall);
    std::printf("cost: %.17g\n", sim->Cost());
    std::printf("fitness: %.17g\n", sim->Fitness());
  } catch (const std::exception& e) {
    std::cerr << "ahhs-sim: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
