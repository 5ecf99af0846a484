#include "tools/bench/bench_sim.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <vector>

#include "modules/core/random.h"
#include "sim/core/constants.h"
#include "sim/core/drive.h"
#include "sim/core/gait.h"
#include "sim/core/scenario.h"

namespace cli = ahhs::base::cli;

namespace ahhs::bench {
namespace {
using Clock = std::chrono::steady_clock;

// Wall time of physics-only episodes with the built-in drive, one core: for each seed the median
// of `repeats` runs, then the median over the seeds. Each seed is a different trajectory of a
// chaotic system (ODE's solver order is seeded), and the cost of a physics step follows the
// number of ground contacts, so one seed alone is a poor estimate.
void BenchSim(const ahhs::sim::ScenarioConfig& config, const char* drive_name, int repeats,
              std::uint64_t first_seed, int seeds, bool chain_solver) {
  namespace as = ahhs::sim;
  const as::DriveKind drive = as::ParseDrive(drive_name);
  std::unique_ptr<as::Scenario> sim;
  if (!chain_solver && config.kind == as::ScenarioKind::kGait) {
    as::GaitConstants constants;
    constants.solver = as::GaitSolver::kDantzig;
    sim = std::make_unique<as::GaitScenario>(config, constants);
  } else {
    sim = as::MakeScenario(config);
  }
  std::vector<double> per_seed, fitnesses;
  std::vector<double> command(static_cast<std::size_t>(sim->num_actuators()));
  for (int k = 0; k < seeds; ++k) {
    std::vector<double> walls;
    for (int rep = 0; rep < repeats; ++rep) {
      const auto t0 = Clock::now();
      sim->Reset(first_seed + static_cast<std::uint64_t>(k));
      while (true) {
        for (int c = 0; c < sim->num_compartments(); ++c) {
          as::DriveCommand(drive, *sim, c, command.data());
          sim->SetActuators(c, command.data());
        }
        if (sim->Step() != as::StepStatus::kRunning) break;
      }
      walls.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    }
    std::sort(walls.begin(), walls.end());
    per_seed.push_back(walls[walls.size() / 2]);
    fitnesses.push_back(sim->Fitness());
  }
  std::vector<double> sorted = per_seed;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted[sorted.size() / 2];
  std::printf(
      "%-8s %-6s %-6s %2d modules %6.1f s simulated: %7.1f ms wall (seeds: min %.1f, max %.1f), "
      "%5.0fx real time, fitness %.4f",
      as::ScenarioName(config.kind),
      config.kind == as::ScenarioKind::kGait ? as::DockingName(config.docking) : "-", drive_name,
      sim->num_compartments(), sim->sim_time(), 1e3 * median, 1e3 * sorted.front(),
      1e3 * sorted.back(), sim->sim_time() / median, fitnesses.front());
  if (seeds > 1) {
    std::sort(fitnesses.begin(), fitnesses.end());
    std::printf(" (seeds: %.4f-%.4f)", fitnesses.front(), fitnesses.back());
  }
  std::printf("\n");
}

}  // namespace

cli::App* SimBench::Add(cli::App& app) {
  auto* sub = app.add_subcommand("sim", "physics-only episodes with built-in drives");
  sub->add_option("--repeats", repeats, "repeats (the median is reported)")
      ->check(cli::Range(1, 1000))
      ->capture_default_str();
  sub->add_option("--seed", seed, "first episode seed")
      ->check(ahhs::modules::SeedTextError)
      ->capture_default_str();
  sub->add_option("--seeds", seeds, "seeds seed, seed+1, ... (the median over them is reported)")
      ->check(cli::Range(1, 1000))
      ->capture_default_str();
  sub->add_option("--solver", solver,
                  "the gait's solver: chain (this build's physics, sim/core/chain_step.h), "
                  "chain-cold (without its warm start, the physics of 2026-12-04) or ode (ODE's "
                  "dWorldStep, the same model, the physics of 2026-12-01)")
      ->check(cli::IsMember({"ode", "chain", "chain-cold"}))
      ->capture_default_str();
  return sub;
}

void SimBench::Run() const {
  namespace as = ahhs::sim;
  std::printf("physics-only episodes, median of %d runs per seed, seeds %llu-%llu, %s solver\n",
              repeats, static_cast<unsigned long long>(seed),
              static_cast<unsigned long long>(seed) + static_cast<unsigned long long>(seeds) - 1,
              solver.c_str());
  for (const char* drive : {"wave", "zero"}) {
    for (as::DockingKind docking : {as::DockingKind::kDamped, as::DockingKind::kFixed}) {
      as::ScenarioConfig gait;
      gait.docking = docking;
      if (solver == "chain-cold") gait.physics = as::kGaitChainColdPhysicsVersion;
      BenchSim(gait, drive, repeats, seed, seeds, solver != "ode");
    }
  }
  as::ScenarioConfig pendulum;
  pendulum.kind = as::ScenarioKind::kPendulum;
  BenchSim(pendulum, "wave", repeats, seed, seeds, false);
}

}  // namespace ahhs::bench
