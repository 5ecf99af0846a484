// Episodes for the arena tests, and their reference fitness without any bus.
#pragma once

#include <string>

#include "episode/arena/direct_arena.h"
#include "episode/arena/episode.h"
#include "modules/core/genome.h"
#include "sim/core/scenario.h"

namespace ahhs::testing {

struct Episode {
  std::string scenario;
  int modules;
  double duration;
  std::int64_t seed;
};

inline sim::ScenarioConfig ConfigOf(const Episode& e) {
  sim::ScenarioConfig c;
  c.kind = sim::ParseScenarioKind(e.scenario);
  c.num_modules = e.modules;
  c.duration = e.duration;
  return c;
}

// The reference: scenario and organism stepped directly (episode::RunDirect).
inline double DirectFitness(const Episode& e, const modules::Genome& genome) {
  episode::EpisodeSpec spec;
  spec.config = ConfigOf(e);
  spec.genome = genome;
  spec.seed = e.seed;
  return episode::RunDirect(spec);
}

}  // namespace ahhs::testing
