#pragma once

#include "episode/arena/episode.h"

namespace ahhs::episode {

// The fused arena: sim node, one module node per compartment and the fitness node in this
// process on a fresh bus of `spec.fused_url`. A URL that leaves the process is an error result.
EpisodeResult RunFused(const EpisodeSpec& spec);

}  // namespace ahhs::episode
