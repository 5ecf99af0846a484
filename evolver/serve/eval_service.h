// The ask/tell evaluation service's protocol and logic (docs/protocol.md, "Evaluation service"),
// with no I/O and no LCM: one request line in, one answer line out, the episodes evaluated by an
// injected FitnessEvaluator (the farm in ahhs-evaluate, an in-process arena or a function in
// tests). Version 2, JSON lines:
//   hello  {"v": 2, "service": "ahhs-evaluate", "scenario": ..., "shape": {...}, "vector_size": N,
//           "trials": K, "aggregate": ..., "envelope": {...}, "descriptor": [NAME, ...]}
//           (first line, once)
//   ask    {"v": 2, "id": ANY, "seed": S, "genomes": [G, ...]}
//          G is a genome document (docs/genome.md) or {"vector": [x, ...]} of the service's shape
//          (docs/genome.md, "Genome vectors"); "seed" (a uint64, as a number or a decimal string)
//          is optional: without it the service takes its next request seed.
//   tell   {"v": 2, "id": ANY, "seed": S, "results": [{"fitness": F, "descriptor": D,
//           "genome_hash": H, "trials": [{"seed": s, "fitness": f, "descriptor": d}, ...]}, ...]}
//   error  {"v": 2, "id": ANY or null, "error": "one line"}
// Trial t of genome i has seed DeriveSeed(S, {i, t}); `ahhs-launch --genome G --seed s` with the
// service's task and envelope gives its fitness and descriptor bit for bit. F is the trials'
// aggregate, D the mean of their descriptors (a trial whose episode failed has d = null and is
// left out of D; D is null when every trial failed).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "evolver/ga/ga.h"
#include "modules/core/genome.h"
#include "sim/core/scenario.h"

namespace ahhs::evolver {

inline constexpr int kServiceProtocolVersion = 2;  // 2: behaviour descriptors
inline std::string ServiceVersionLine() {          // for --version
  return "evaluation service protocol " + std::to_string(kServiceProtocolVersion);
}
inline constexpr int kMaxServiceBatch = 100000;

struct ServiceSettings {
  sim::ScenarioConfig task;  // the envelope included
  modules::Shape shape;      // of vectors (a genome document brings its own)
  int trials = 1;
  Aggregate aggregate = Aggregate::kMean;
  std::uint64_t seed = 1;  // request seeds when a request gives none: DeriveSeed(seed, {n})
};

class EvalService {
 public:
  EvalService(ServiceSettings settings, FitnessEvaluator& evaluator);

  // The first line the service writes.
  nlohmann::json Hello() const;
  // One request line's answer (a tell or an error; never throws for bad input). Exceptions of
  // the evaluator become an error answer too.
  nlohmann::json Handle(const std::string& line);

 private:
  nlohmann::json Ask(const nlohmann::json& request);

  ServiceSettings settings_;
  FitnessEvaluator& evaluator_;
  std::uint64_t requests_ = 0;
};

}  // namespace ahhs::evolver
