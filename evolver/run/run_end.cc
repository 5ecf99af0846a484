#include "evolver/run/run_end.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "base/atomic_file.h"
#include "base/children.h"
#include "base/format.h"
#include "episode/arena/post_eval.h"
#include "modules/core/genome.h"
#include "sim/node/envelope_options.h"

namespace ahhs::evolver {

std::string DescribeRun(const EvolveConfig& config, int first) {
  std::string robust;
  if (config.ga.trials > 1 || !config.scenario.envelope.none())
    robust = ", " + std::to_string(config.ga.trials) + " trial" +
             (config.ga.trials > 1 ? std::string("s (") + AggregateName(config.ga.aggregate) + ")"
                                   : std::string()) +
             ", envelope " + sim::EnvelopeName(config.scenario.envelope) +
             (config.validation > 0
                  ? ", best chosen on " + std::to_string(config.validation) + " validation episodes"
                  : std::string());
  const std::string body = config.scenario.kind == sim::ScenarioKind::kGait
                               ? std::string(sim::DockingName(config.scenario.docking)) +
                                     " docking, " + std::to_string(config.scenario.num_modules) +
                                     " modules"
                               : std::string("cart and pole");
  return std::string(sim::ScenarioName(config.scenario.kind)) + " " + body + ", " +
         modules::VariantName(config.variant) + " " + std::to_string(config.hormones) +
         " hormones x " + std::to_string(config.rules) + " rules, population " +
         std::to_string(config.ga.population) + ", generations " +
         std::to_string(config.ga.generations) + robust + ", seed " + std::to_string(config.seed) +
         (first > 0 ? ", resuming at generation " + std::to_string(first) : std::string());
}

void PrintRunSummary(const RunStore& store, const EvolveConfig& config) {
  const IndividualRecord best = store.Best();
  std::string replay = base::ExecutableDir() + "/ahhs-launch --scenario " +
                       std::string(sim::ScenarioName(config.scenario.kind));
  if (config.scenario.kind == sim::ScenarioKind::kGait)
    replay += " --docking " + std::string(sim::DockingName(config.scenario.docking)) +
              " --modules " + std::to_string(config.scenario.num_modules);
  if (config.scenario.duration > 0) {
    replay += " --duration " + base::ExactDouble(config.scenario.duration);
  }
  replay += sim::EnvelopeArguments(config.scenario.envelope);
  if (!config.scenario.physics.empty()) replay += " --physics " + config.scenario.physics;
  replay += " --genome " + store.dir() + "/best.json --seed " + std::to_string(best.eval_seed);
  std::printf("done: %d generations in %s\n", config.ga.generations, store.dir().c_str());
  if (best.trials.empty()) {
    std::printf("best fitness: %.17g (generation %d, individual %d)\n", best.evaluation.fitness,
                best.generation, best.index);
    std::printf("replay the best genome: %s\n", replay.c_str());
  } else {
    std::printf("best fitness: %.17g (generation %d, individual %d; the %s of %zu trials)\n",
                best.evaluation.fitness, best.generation, best.index,
                AggregateName(config.ga.aggregate), best.trials.size());
    std::printf("replay the best genome's first trial (fitness %.17g): %s\n",
                best.trials.front().evaluation.fitness, replay.c_str());
  }
  const std::vector<ValidationRecord> validation = store.LoadValidation();
  for (const auto& v : validation)
    if (v.generation == best.generation && v.index == best.index) {
      const IndividualRecord top = store.TrainingBest();
      std::printf(
          "chosen by validation among %zu candidates: median %.6g on %zu episodes (the highest "
          "training fitness, %.6g, is generation %d, individual %d)\n",
          validation.size(), v.Median(), v.fitness.size(), top.evaluation.fitness, top.generation,
          top.index);
    }
}

void PostEvaluateBest(const RunStore& store, const EvolveConfig& config, std::FILE* out) {
  const IndividualRecord best = store.Best();
  const std::string path = store.dir() + "/post-eval.json";
  const std::string hash = modules::GenomeHashText(best.genome);
  std::error_code ec;
  if (std::filesystem::is_regular_file(path, ec)) {
    try {
      std::ifstream in(path);
      const auto doc = nlohmann::json::parse(in);
      if (doc.at("genome_hash") == hash && doc.at("episodes") == config.post_eval) {
        std::fprintf(out, "%s\n", doc.at("description").get<std::string>().c_str());
        return;
      }
    } catch (const std::exception&) {
    }  // damaged or another best's: evaluated again below
  }
  std::fprintf(out, "post-evaluating the best on %d held-out episodes ...\n", config.post_eval);
  std::fflush(out);
  episode::EpisodeSpec spec;
  spec.config = config.scenario;
  spec.genome = best.genome;
  spec.episode = 1;
  const episode::PostEvaluation p =
      episode::PostEvaluate(spec, config.post_eval_envelope, config.post_eval);
  const std::string line = p.Describe();
  nlohmann::json doc = p.ToJson();
  doc["description"] = line;
  doc["generation"] = best.generation;
  doc["individual"] = best.index;
  doc["genome_hash"] = hash;
  doc["training_fitness"] = best.evaluation.fitness;
  base::WriteFileAtomically(path, doc.dump(2) + "\n");
  std::fprintf(out, "%s\n", line.c_str());
}

}  // namespace ahhs::evolver
