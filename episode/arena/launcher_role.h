// The launcher's protocol role (docs/protocol.md, "Episode"): one episode with a given genome on
// a bus where a sim, one module per compartment and a fitness monitor listen. The fused and the
// process arenas, ahhs-launch and the external roles all run episodes through it.
#pragma once

#include <chrono>
#include <functional>
#include <string>

#include "bus/bus.h"
#include "episode/arena/episode.h"

namespace ahhs::episode {

// Runs the episode on `bus`. `pump(wait)` must dispatch the bus (and, for the fused arena, poll
// every node); `alive()` is asked every loop and aborts the episode when it returns false (e.g.
// a child process died or Ctrl-C); its message goes into the result.
EpisodeResult RunEpisode(bus::Bus& bus, const EpisodeSpec& spec,
                         const std::function<void(std::chrono::microseconds)>& pump,
                         const std::function<bool(std::string*)>& alive);

}  // namespace ahhs::episode
