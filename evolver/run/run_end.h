// The end of an ahhs-evolve run: its summary and the held-out post-evaluation of its best.
#pragma once

#include "evolver/evolve/evolution.h"
#include "evolver/store/run_store.h"

namespace ahhs::evolver {

// Where a finished run is, its best fitness, and the command that replays the best genome.
void PrintRunSummary(const RunStore& store, const EvolveConfig& config);

// The run's held-out post-evaluation (its config's post_eval episodes): printed, and kept in
// RUN/post-eval.json, written once for the run's final best (a resume of a finished run that has
// it only prints it again).
void PostEvaluateBest(const RunStore& store, const EvolveConfig& config);

}  // namespace ahhs::evolver
