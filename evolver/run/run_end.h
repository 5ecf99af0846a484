// What ahhs-evolve says of a run: its setting when it starts, and at its end the summary and the
// held-out post-evaluation of its best.
#pragma once

#include <cstdio>
#include <string>

#include "evolver/evolve/evolution.h"
#include "evolver/store/run_store.h"

namespace ahhs::evolver {

// The run's setting in one line: "gait damped docking, 5 modules, ahhs2 5 hormones x 30 rules,
// population 20, generations 200, 3 trials (mean), envelope paper, seed 1" (and where a resumed
// run goes on from: `first`).
std::string DescribeRun(const EvolveConfig& config, int first);

// Where a finished run is, its best fitness, and the command that replays the best genome.
void PrintRunSummary(const RunStore& store, const EvolveConfig& config);

// The run's held-out post-evaluation (its config's post_eval episodes): printed, and kept in
// RUN/post-eval.json, written once for the run's final best (a resume of a finished run that has
// it only prints it again).
void PostEvaluateBest(const RunStore& store, const EvolveConfig& config, std::FILE* out = stdout);

}  // namespace ahhs::evolver
