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

}  // namespace ahhs::evolver
