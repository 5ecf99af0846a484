// The bus-free reference: scenario and organism stepped in one loop, in the lockstep order.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "episode/arena/episode.h"
#include "modules/core/organism.h"

namespace ahhs::episode {

// What RunDirectEpisode shows an observer after every tick (ahhs-replay's trace): the sensors
// the controllers read in the tick, the organism after its step, the scenario after the tick's
// physics.
struct DirectTick {
  std::int64_t tick = 0;  // the tick just completed, 0-based
  const sim::Scenario* scenario = nullptr;
  const modules::Organism* organism = nullptr;
  const std::vector<std::vector<double>>* sensors = nullptr;  // [compartment][slot]
};
using DirectObserver = std::function<void(const DirectTick&)>;

// The reference without any bus: scenario and organism stepped in one loop (lockstep order).
// Returns the scenario's own fitness and cost; the arenas must reproduce them.
EpisodeResult RunDirectEpisode(const EpisodeSpec& spec, const DirectObserver& observer = {});
// RunDirectEpisode's fitness (tests and benchmarks of episodes that do not fail).
double RunDirect(const EpisodeSpec& spec);

}  // namespace ahhs::episode
