// How a worker evaluates one job (ahhs-worker --arena): a farm job as an episode of an arena
// (episode/arena/arena.h), its result as the job's outcome. All arenas give bit-identical fitness
// (tests/arena, tests/evolver). An episode whose physics fails scores kFailedEpisodeFitness, with
// the reason in the outcome's message.
#pragma once

#include <memory>
#include <string>

#include "episode/arena/arena.h"
#include "evolver/farm/farm_protocol.h"

namespace ahhs::evolver {

inline constexpr double kFailedEpisodeFitness = 0.0;

class ArenaEvaluator {
 public:
  // `options.url` and `options.name` are used by the process arena only (its own traffic).
  explicit ArenaEvaluator(episode::ArenaOptions options);
  ~ArenaEvaluator();
  ArenaEvaluator(const ArenaEvaluator&) = delete;
  ArenaEvaluator& operator=(const ArenaEvaluator&) = delete;

  FarmResult Evaluate(const FarmJob& job);

 private:
  episode::ArenaOptions options_;
  std::unique_ptr<episode::Arena> arena_;
  int arena_compartments_ = 0;  // the process arena has one module process per compartment
  std::int64_t episodes_ = 0;
};

}  // namespace ahhs::evolver
