// ahhs-replay's episode and everything it writes: logs and traces, mutants, robustness,
// post-evaluation, the comparison with the stored fitness, videos (through ahhs-view).
#pragma once

#include "tools/replay/replay_options.h"
#include "tools/replay/replay_target.h"

namespace ahhs::replay {

// Runs the replay; returns the process's exit code (messages already printed).
int RunReplay(const ReplayOptions& o, const ReplayTarget& t);

}  // namespace ahhs::replay
