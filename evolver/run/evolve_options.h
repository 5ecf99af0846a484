// ahhs-evolve's options, and how they open a run: a new one, or the stored one (--resume), whose
// configuration the options may not change.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "base/cli.h"
#include "bus/lcm_bus.h"
#include "evolver/evolve/evolution.h"
#include "evolver/farm/farm_evaluator.h"
#include "evolver/run/shared_options.h"
#include "evolver/store/run_store.h"
#include "sim/node/envelope_options.h"
#include "sim/node/scenario_options.h"

namespace ahhs::evolver {

// What a run without --config or --scenario (the README's main job) has beyond the defaults
// below: the robust damped gait of configs/gait-damped-ahhs2-30-robust.toml
// (tests/evolver/presets_test.sh checks that the two agree).
struct MainJobSettings {
  int trials;
  const char* envelope;
  int post_eval;
  int validation;
};
inline constexpr MainJobSettings kMainJob{3, "paper", 50, 20};

// ahhs-evolve's command line.
struct EvolveOptions {
  sim::ScenarioOptions scenario;
  std::string variant = "ahhs2", out_dir, resume_dir, mutation_profile = "paper";
  int hormones = 5, rules = 30, population = 20, generations = 200, elitism = 1, trials = 1;
  std::string aggregate = "mean";
  sim::EnvelopeOptions envelope;
  double mutation_rate = 0.15, mutation_max_change = 0.1, crossover_rate = 0.05;
  std::uint64_t seed = 1;
  FarmCliOptions farm;
  RunEndCliOptions end;
  bool overwrite = false, show_config = false;
};

// Declares every option (and --config, a strict TOML preset) on `app`.
void AddEvolveOptions(base::cli::App& app, EvolveOptions* o);

// The run: a new one from the options, or the stored one (--resume). Returns nullptr after
// --show-config printed the configuration. Throws with a message for the user.
std::unique_ptr<RunStore> OpenRun(const base::cli::App& app, EvolveOptions& o,
                                  EvolveConfig* config);

// The farm's options for this run (`wire_run`: the run's name on the bus).
FarmOptions FarmOptionsFor(const EvolveOptions& o, const EvolveConfig& config,
                           const std::string& wire_run);

}  // namespace ahhs::evolver
