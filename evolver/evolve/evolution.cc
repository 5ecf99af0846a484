#include "evolver/evolve/evolution.h"

#include <chrono>
#include <stdexcept>
#include <string_view>

namespace ahhs::evolver {

using nlohmann::json;

namespace {

// EnvelopeKeys() names "envelope.friction", ...; the config's envelope object "friction", ...
constexpr std::string_view kEnvelopePrefix = "envelope.";

json EnvelopeToJson(const sim::Envelope& e) {
  json doc = json::object();
  for (const auto& k : sim::EnvelopeKeys())
    doc[std::string(k.name).substr(kEnvelopePrefix.size())] = e.*k.field;
  return doc;
}

sim::Envelope EnvelopeFromJson(const json& doc) {
  if (!doc.is_object()) throw std::invalid_argument("envelope must be an object");
  sim::Envelope e;
  for (const auto& [key, value] : doc.items()) {
    bool known = false;
    for (const auto& k : sim::EnvelopeKeys())
      if (std::string(k.name).substr(kEnvelopePrefix.size()) == key) {
        e.*k.field = value.get<double>();
        known = true;
      }
    if (!known) throw std::invalid_argument("unknown envelope key '" + key + "'");
  }
  return e;
}

}  // namespace

modules::Shape EvolveConfig::shape() const {
  auto probe = sim::MakeScenario(scenario);
  return {variant, hormones, rules, probe->num_sensors(), probe->num_actuators()};
}

std::string CheckEvolveConfig(const EvolveConfig& c) {
  std::string e = sim::CheckConfig(c.scenario);
  if (!e.empty()) return e;
  e = sim::CheckEnvelope(c.scenario.envelope);
  if (!e.empty()) return "envelope: " + e;
  if (c.post_eval < 0 || c.post_eval > kMaxPostEval)
    return "post-eval must be in [0, " + std::to_string(kMaxPostEval) + "] episodes";
  e = sim::CheckEnvelope(c.post_eval_envelope);
  if (!e.empty()) return "post-eval envelope: " + e;
  if (c.hormones < 1 || c.hormones > modules::Ranges::kMaxHormones)
    return "hormones must be in [1, " + std::to_string(modules::Ranges::kMaxHormones) + "]";
  if (c.rules < 1 || c.rules > modules::Ranges::kMaxRules)
    return "rules must be in [1, " + std::to_string(modules::Ranges::kMaxRules) + "]";
  return CheckGaParams(c.ga);
}

json ConfigToJson(const EvolveConfig& c) {
  json doc{{"scenario", sim::ScenarioName(c.scenario.kind)},
           {"joints", sim::JointsName(c.scenario.joints)},
           {"modules", c.scenario.num_modules},
           {"duration", c.scenario.duration},
           {"variant", modules::VariantName(c.variant)},
           {"hormones", c.hormones},
           {"rules", c.rules},
           {"seed", c.seed}};
  GaParamsToJson(c.ga, &doc);
  // A paper run's config is what it always was: the new keys only when they are used.
  if (!c.scenario.envelope.none()) doc["envelope"] = EnvelopeToJson(c.scenario.envelope);
  if (c.post_eval > 0)
    doc["post_eval"] = {{"episodes", c.post_eval},
                        {"envelope", EnvelopeToJson(c.post_eval_envelope)}};
  return doc;
}

EvolveConfig ConfigFromJson(const json& doc) {
  EvolveConfig c;
  try {
    c.scenario.kind = sim::ParseScenarioKind(doc.at("scenario").get<std::string>());
    c.scenario.joints = sim::ParseJoints(doc.at("joints").get<std::string>());
    c.scenario.num_modules = doc.at("modules").get<int>();
    c.scenario.duration = doc.at("duration").get<double>();
    const std::string variant = doc.at("variant").get<std::string>();
    if (variant != "ahhs1" && variant != "ahhs2")
      throw std::invalid_argument("variant must be ahhs1 or ahhs2");
    c.variant = variant == "ahhs1" ? modules::Variant::kAhhs1 : modules::Variant::kAhhs2;
    c.hormones = doc.at("hormones").get<int>();
    c.rules = doc.at("rules").get<int>();
    c.ga = GaParamsFromJson(doc);
    c.seed = doc.at("seed").get<std::uint64_t>();
    if (doc.contains("envelope")) c.scenario.envelope = EnvelopeFromJson(doc.at("envelope"));
    if (doc.contains("post_eval")) {
      const json& post = doc.at("post_eval");
      c.post_eval = post.at("episodes").get<int>();
      c.post_eval_envelope = EnvelopeFromJson(post.at("envelope"));
    }
  } catch (const json::exception& e) {
    throw std::invalid_argument(std::string("run config: ") + e.what());
  }
  const std::string error = CheckEvolveConfig(c);
  if (!error.empty()) throw std::invalid_argument("run config: " + error);
  return c;
}

bool RunEvolution(RunStore& store, const EvolveConfig& config, FitnessEvaluator& evaluator,
                  int session, const EvolutionHooks& hooks) {
  auto seconds = hooks.seconds ? hooks.seconds : [] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
  };
  const GaParams& ga = config.ga;
  std::vector<modules::Genome> population;
  std::vector<double> fitness;
  const int last = store.LastGeneration();
  if (last >= 0) {
    for (const auto& r : store.LoadGeneration(last)) {
      population.push_back(r.genome);
      fitness.push_back(r.evaluation.fitness);
    }
    if (static_cast<int>(population.size()) != ga.population)
      throw RunStoreError(store.dir() + ": generation " + std::to_string(last) + " holds " +
                          std::to_string(population.size()) + " individuals, the config says " +
                          std::to_string(ga.population));
  }
  for (int g = last + 1; g < ga.generations; ++g) {
    if (hooks.stop()) return false;
    const double start = seconds();
    const std::vector<modules::Genome> parents = std::move(population);
    std::vector<EvaluationJob> jobs;
    std::vector<Evaluation> trials;
    const std::vector<Evaluation> results =
        StepGeneration(config.shape(), ga, config.seed, g, parents, fitness, evaluator, &population,
                       &jobs, &trials);
    std::vector<IndividualRecord> records;
    fitness.clear();
    for (int i = 0; i < ga.population; ++i) {
      const auto k = static_cast<std::size_t>(i);
      IndividualRecord r;
      r.generation = g;
      r.index = i;
      r.genome = population[k];
      r.elite = g > 0 && i < ga.elitism;
      r.eval_seed = jobs[k * static_cast<std::size_t>(ga.trials)].seed;
      r.evaluation = results[k];
      if (ga.trials > 1)
        for (int t = 0; t < ga.trials; ++t) {
          const std::size_t j =
              k * static_cast<std::size_t>(ga.trials) + static_cast<std::size_t>(t);
          r.trials.push_back({t, jobs[j].seed, trials[j]});
        }
      fitness.push_back(results[k].fitness);
      records.push_back(std::move(r));
    }
    GenerationRecord record;
    record.generation = g;
    record.stats = Summarise(fitness);
    record.wall_time = seconds() - start;
    record.session = session;
    store.CommitGeneration(record, records);
    hooks.on_generation(record);
  }
  return true;
}

}  // namespace ahhs::evolver
