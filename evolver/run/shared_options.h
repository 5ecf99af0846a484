// The command-line options that ahhs-evolve and ahhs-evaluate share: how their evaluation farm
// runs, and what a run does when it ends (validation and held-out post-evaluation).
#pragma once

#include <string>

#include "base/cli.h"
#include "bus/lcm_bus.h"
#include "evolver/evolve/evolution.h"
#include "evolver/farm/farm_evaluator.h"

namespace ahhs::evolver {

struct FarmCliOptions {
  int workers = -1;  // local workers; -1: one per core
  std::string arena = "direct", url = bus::kDefaultLcmUrl;
  double job_deadline = 300, worker_wait = 60;  // s
  int wait_for_workers = 0;  // before the first evaluation; 0: start with the first worker heard
};

// --workers, --arena-kind, --lcm-url, --job-deadline, --worker-wait (`worker_wait_help` says
// what running out of workers does to this tool) and --wait-for-workers.
void AddFarmOptions(base::cli::App& app, FarmCliOptions* o, const std::string& worker_wait_help);

// The farm's lease deadline and the wait for a worker.
void ApplyFarmOptions(const FarmCliOptions& o, FarmOptions* farm);

struct RunEndCliOptions {
  int validation = 0, validation_candidates = 10, post_eval = 0;
  std::string post_eval_envelope;  // empty: the run's, or paper for a run without one
};

// --validation, --validation-candidates, --post-eval and --post-eval-envelope. Each help text
// starts with `prefix`; the defaults shown for --validation and --post-eval are the given texts,
// or the values in `o` when null.
void AddRunEndOptions(base::cli::App& app, RunEndCliOptions* o, const std::string& prefix,
                      const char* validation_default = nullptr,
                      const char* post_eval_default = nullptr);
inline constexpr const char* kRunEndOptionNames[] = {"--validation", "--validation-candidates",
                                                     "--post-eval", "--post-eval-envelope"};

// The farm options that differ from their defaults, as command-line words (" --lcm-url '...'"),
// for the follow-up command a run prints: a resumed LAN run finds its workers again.
std::string FarmArgs(const FarmCliOptions& o);

// --wait-for-workers N: waits until N workers are ready to serve (at most --worker-wait s) and
// returns the line that says so, "" when not asked; throws FarmError naming the workers heard
// when fewer are.
std::string WaitForFarmWorkers(const FarmCliOptions& o, FarmEvaluator* farm);

// Into a run's config, whose scenario (and so its envelope) is already set.
void ApplyRunEndOptions(const RunEndCliOptions& o, EvolveConfig* config);

}  // namespace ahhs::evolver
