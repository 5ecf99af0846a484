// The ask/tell evaluation service's protocol and logic (docs/protocol.md, "Evaluation service"),
// with no I/O and no LCM: one request line in, one answer line out, the episodes evaluated by an
// injected FitnessEvaluator (the farm in ahhs-evaluate, an in-process arena or a function in
// tests). Version 2, JSON lines:
//   hello  {"v": 2, "service": "ahhs-evaluate", "scenario": ..., "physics": VERSION,
//           "shape": {...}, "vector_size": N, "trials": K, "aggregate": ..., "envelope": {...},
//           "descriptor": [NAME, ...]} (first line, once; a client ignores keys it does not know)
//   ask    {"v": 2, "id": ANY, "seed": S, "genomes": [G, ...]}
//          G is a genome document (docs/genome.md) or {"vector": [x, ...]} of the service's shape
//          (docs/genome.md, "Genome vectors"); "seed" (a uint64, as a number or a decimal string)
//          is optional: without it the service takes its next request seed.
//   tell   {"v": 2, "id": ANY, "seed": S, "results": [{"fitness": F, "descriptor": D,
//           "genome_hash": H, "trials": [{"seed": s, "fitness": f, "descriptor": d}, ...]}, ...]}
//   error  {"v": 2, "id": ANY or null, "error": "one line"}
// Trial t of genome i has seed DeriveSeed(S, {i, t}); `ahhs-launch --genome G --seed s` with the
// service's scenario and envelope gives its fitness and descriptor bit for bit. F is the trials'
// aggregate, D the mean of their descriptors (a trial whose episode failed has d = null and is
// left out of D; D is null when every trial failed).
#pragma once

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "evolver/ga/ga.h"
#include "evolver/store/run_store.h"
#include "modules/core/genome.h"
#include "sim/core/scenario.h"

namespace ahhs::evolver {

inline constexpr int kServiceProtocolVersion = 2;  // 2: behaviour descriptors
inline std::string ServiceVersionLine() {          // for --version
  return "evaluation service protocol " + std::to_string(kServiceProtocolVersion);
}
inline constexpr int kMaxServiceBatch = 100000;

struct ServiceSettings {
  sim::ScenarioConfig scenario;  // the envelope included
  modules::Shape shape;          // of vectors (a genome document brings its own)
  int trials = 1;
  Aggregate aggregate = Aggregate::kMean;
  std::uint64_t seed = 1;  // request seeds when a request gives none: DeriveSeed(seed, {n})
};

// A service that records what it answers as a run (ahhs-evaluate --out; docs/protocol.md,
// "Evaluation service", "A run of your optimizer"): every request is one generation of
// `population` genomes, named by its "generation" and seeded by the run, committed to `store`
// in order; a generation the store already holds is evaluated again and must give what it holds
// (an optimizer resumed from a checkpoint older than the store). ServiceSettings::seed is then
// the run's seed: generation g's request seed is DeriveSeed(seed, {g}).
struct ServiceRun {
  RunStore* store = nullptr;
  std::string optimizer;
  int population = 0;
  int generations = 0;
  int session = 0;
  int validation = 0;  // episodes of the validation that chooses the run's best when it ends
  int post_eval = 0;   // held-out episodes of the best's post-evaluation when it ends
  std::function<double()> seconds;  // wall clock for the generation records (any origin)
};

class EvalService {
 public:
  // `run` (may be null: no run) must outlive the service.
  EvalService(ServiceSettings settings, FitnessEvaluator& evaluator, ServiceRun* run = nullptr);

  // The first line the service writes.
  nlohmann::json Hello() const;
  // One request line's answer (a tell or an error; never throws for bad input). Exceptions of
  // the evaluator become an error answer too.
  nlohmann::json Handle(const std::string& line);

 private:
  nlohmann::json Ask(const nlohmann::json& request);
  // Commits an evaluated generation to the run, or checks it against the stored one.
  void Record(int generation, const std::vector<modules::Genome>& genomes,
              const std::vector<EvaluationJob>& jobs, const std::vector<Evaluation>& out,
              const nlohmann::json& results, double start);

  ServiceSettings settings_;
  FitnessEvaluator& evaluator_;
  ServiceRun* run_;
  std::uint64_t requests_ = 0;
};

}  // namespace ahhs::evolver
