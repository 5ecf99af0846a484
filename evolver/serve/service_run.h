// The run that ahhs-evaluate records for an optimizer (--out, --resume; docs/protocol.md,
// "Evaluation service", "A run of your optimizer"): a run directory like ahhs-evolve's, whose
// config names the optimizer, so that ahhs-report, ahhs-replay and ahhs-view --run read it.
#pragma once

#include <memory>
#include <string>

#include "evolver/evolve/evolution.h"
#include "evolver/store/run_store.h"

namespace ahhs::evolver {

// A new run in `dir` of `config` (whose `optimizer` must be set), or, when `resume` is true, the
// run in `dir`, whose stored config replaces `*config`. Refuses a run of the GA, a run of other
// physics, a directory that is not a run (std::invalid_argument, RunStoreError).
std::unique_ptr<RunStore> OpenServiceRun(const std::string& dir, bool resume, bool overwrite,
                                         const std::string& run_id, EvolveConfig* config);

}  // namespace ahhs::evolver
