// ahhs-evaluate's command line and its setup (docs/protocol.md, "Evaluation service"): the
// options, their checks, and the run that --out or --resume records.
#pragma once

#include <cstdio>
#include <memory>
#include <string>

#include "base/cli.h"
#include "evolver/evolve/evolution.h"
#include "evolver/farm/farm_evaluator.h"
#include "evolver/run/shared_options.h"
#include "evolver/serve/eval_service.h"
#include "evolver/store/run_store.h"
#include "sim/node/envelope_options.h"
#include "sim/node/scenario_options.h"

namespace ahhs::evolver {

struct EvaluateOptions {
  sim::ScenarioOptions scenario;
  sim::EnvelopeOptions envelope;
  std::string variant = "ahhs2", aggregate = "mean";
  int hormones = 5, rules = 30, trials = 1;
  std::uint64_t seed = 1;
  FarmCliOptions farm;
  std::string out_dir, resume_dir, optimizer = "external";
  int population = 0, generations = 0;
  RunEndCliOptions end;  // with --out
  bool overwrite = false;
};

// Declares every option on `app` (`o` holds the defaults).
void AddEvaluateOptions(base::cli::App& app, EvaluateOptions* o);

// What the service runs with, once the options are checked: with --out or --resume, the run's
// store is open and its stored config (`config`) has replaced the options (`run.store` points
// into `store`).
struct EvaluateSetup {
  ServiceSettings settings;
  FarmOptions farm;
  std::unique_ptr<RunStore> store;
  EvolveConfig config;
  ServiceRun run;
};

// After parsing. Throws std::invalid_argument (or RunStoreError) for a usage error: options
// that do not go together, a scenario that does not check, a directory that is not such a run.
EvaluateSetup SetUpEvaluate(const base::cli::App& app, const EvaluateOptions& o,
                            const std::string& command_line);

// At the end of the service's input, for a recorded run whose last generation is stored: chooses
// its best by validation and post-evaluates it, as ahhs-evolve does when a run ends (its config's
// `validation` and `post_eval`; docs/protocol.md, "A run of your optimizer"), writing what it
// says to `out` (stdout is the protocol's). Nothing to do for a run that is not complete.
// Exceptions of the farm pass through; a validation is stored whole or not at all.
void FinishRun(const EvaluateSetup& setup, FitnessEvaluator& farm, std::FILE* out);

}  // namespace ahhs::evolver
