// How a worker evaluates one job (ahhs-worker --arena):
//   direct     scenario and controllers stepped in one loop, no bus (the fastest; default)
//   fused      the arena's node classes in this process on an in-process bus (RunFused)
//   processes  ahhs-sim, ahhs-fitness and ahhs-module processes over LCM, kept between jobs
// All three give bit-identical fitness (tests/arena, tests/evolver). An episode whose physics
// fails scores kFailedEpisodeFitness, with the reason in the outcome's message.
#pragma once

#include <memory>
#include <string>

#include "evolver/farm/farm_protocol.h"

namespace ahhs::launch {
class ProcessArena;
}

namespace ahhs::evolver {

enum class ArenaKind { kDirect, kFused, kProcesses };
ArenaKind ParseArenaKind(const std::string& name);  // throws std::invalid_argument
const char* ArenaKindName(ArenaKind kind);

inline constexpr double kFailedEpisodeFitness = 0.0;

class ArenaEvaluator {
 public:
  // `url` and `arena_name` are used by the process arena only (its own traffic).
  ArenaEvaluator(ArenaKind kind, std::string url, std::string arena_name);
  ~ArenaEvaluator();
  ArenaEvaluator(const ArenaEvaluator&) = delete;
  ArenaEvaluator& operator=(const ArenaEvaluator&) = delete;

  EvalOutcome Evaluate(const EvalJob& job);

 private:
  ArenaKind kind_;
  std::string url_, arena_name_;
  std::unique_ptr<launch::ProcessArena> processes_;
  std::int64_t episodes_ = 0;
};

}  // namespace ahhs::evolver
