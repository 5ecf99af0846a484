// One evolution run over a run store (docs/evolution.md): the configuration, and the loop that
// breeds, evaluates and commits generation after generation, from scratch or from the last
// committed generation of a resumed run. No LCM: the evaluator is injected.
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

inline constexpr int kMaxPostEval = 10000;
inline constexpr int kMaxValidation = 1000;

struct EvolveConfig {
  sim::ScenarioConfig scenario;
  modules::Variant variant = modules::Variant::kAhhs2;
  int hormones = 5;
  int rules = 30;
  GaParams ga;
  std::uint64_t seed = 1;
  // Held-out post-evaluation of the run's best when it ends (episode/arena/post_eval.h):
  // episodes (0: none) and their envelope.
  int post_eval = 0;
  sim::Envelope post_eval_envelope;
  // Validation (docs/evolution.md, "Validation"): when the run ends, its best is chosen among
  // candidates (its `validation_candidates` best distinct genomes and its last generation's)
  // by their median on `validation` episodes of the training envelope (0: the highest fitness).
  int validation = 0;
  int validation_candidates = 10;
  // "" for the paper's GA (ahhs-evolve); else the name of the optimizer whose generations
  // ahhs-evaluate --out recorded (docs/protocol.md): the GA's settings other than population,
  // generations, trials and aggregate then mean nothing, and every genome is stored in full.
  std::string optimizer;

  // The genome shape: sensors and actuators come from the scenario.
  modules::Shape shape() const;
};

// "" or a message naming the bad setting.
std::string CheckEvolveConfig(const EvolveConfig& config);
nlohmann::json ConfigToJson(const EvolveConfig& config);
// Throws std::invalid_argument naming the bad field.
EvolveConfig ConfigFromJson(const nlohmann::json& doc);

struct EvolutionHooks {
  // After each committed generation.
  std::function<void(const GenerationRecord&)> on_generation = [](const GenerationRecord&) {};
  // Before each generation: true stops the run cleanly (it stays resumable).
  std::function<bool()> stop = [] { return false; };
  // Wall-clock time source for the generation records (seconds, any origin).
  std::function<double()> seconds;
};

// Runs the remaining generations of `store`'s run with `evaluator`. Returns false when `stop`
// ended it early. Exceptions of the evaluator pass through; the generation in progress is then
// not committed.
bool RunEvolution(RunStore& store, const EvolveConfig& config, FitnessEvaluator& evaluator,
                  int session, const EvolutionHooks& hooks = {});

// Seed stream of the validation episodes: DeriveSeed(run_seed, {kValidationStream, k}), apart
// from the training seeds (kEvalStream) and from the held-out ones (episode/arena/post_eval.h).
inline constexpr std::uint64_t kValidationStream = 4;
std::uint64_t ValidationSeed(std::uint64_t run_seed, int episode);

// The candidates of a finished run's validation: its `count` best distinct genomes by fitness,
// then its last generation's best distinct genomes not among them (up to `count` more).
std::vector<IndividualRecord> ValidationCandidates(const RunStore& store, int count);

// Chooses a finished run's best by validation when its config asks for one and the store has
// none yet: evaluates every candidate on ValidationSeed(0 .. validation - 1) under the training
// envelope (one batch of jobs) and commits the result (RunStore::CommitValidation). Returns false
// when there was nothing to do. Exceptions of the evaluator pass through; nothing is stored then.
bool ValidateRun(RunStore& store, const EvolveConfig& config, FitnessEvaluator& evaluator);

}  // namespace ahhs::evolver
