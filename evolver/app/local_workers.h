// Local ahhs-worker processes for a tool that evaluates through the farm (ahhs-evolve,
// ahhs-evaluate): started beside the tool's own binary, serving one run.
#pragma once

#include <string>

#include "base/children.h"

namespace ahhs::evolver {

// Starts `count` workers on `url` with arena kind `arena`, dedicated to `run`. Throws
// std::runtime_error when one cannot be started.
void StartLocalWorkers(base::ChildProcesses* local, int count, const std::string& url,
                       const std::string& arena, const std::string& run);

}  // namespace ahhs::evolver
