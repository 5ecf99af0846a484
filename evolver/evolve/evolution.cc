#include "evolver/evolve/evolution.h"

#include <chrono>
#include <set>
#include <stdexcept>
#include <string_view>

#include "modules/core/random.h"

namespace ahhs::evolver {

using nlohmann::json;

namespace {

// EnvelopeKeys() names "envelope.friction", ...; the config's envelope object "friction", ...
constexpr std::string_view kEnvelopePrefix = "envelope.";

json EnvelopeToJson(const sim::Envelope& e) {
  json doc = json::object();
  for (const auto& k : sim::EnvelopeKeys())
    if (k.Written(e)) doc[std::string(k.name).substr(kEnvelopePrefix.size())] = e.*k.field;
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
  if (c.validation < 0 || c.validation > kMaxValidation)
    return "validation must be in [0, " + std::to_string(kMaxValidation) + "] episodes";
  if (c.validation_candidates < 1 || c.validation_candidates > kMaxValidation)
    return "validation-candidates must be in [1, " + std::to_string(kMaxValidation) + "]";
  if (c.hormones < 1 || c.hormones > modules::Ranges::kMaxHormones)
    return "hormones must be in [1, " + std::to_string(modules::Ranges::kMaxHormones) + "]";
  if (c.rules < 1 || c.rules > modules::Ranges::kMaxRules)
    return "rules must be in [1, " + std::to_string(modules::Ranges::kMaxRules) + "]";
  return CheckGaParams(c.ga);
}

json ConfigToJson(const EvolveConfig& c) {
  json doc{{"scenario", sim::ScenarioName(c.scenario.kind)},
           {"joints", sim::DockingName(c.scenario.docking)},
           {"modules", c.scenario.num_modules},
           {"duration", c.scenario.duration},
           {"variant", modules::VariantName(c.variant)},
           {"hormones", c.hormones},
           {"rules", c.rules},
           {"seed", c.seed}};
  GaParamsToJson(c.ga, &doc);
  // A paper run's config is what it always was: the new keys only when they are used.
  if (!c.scenario.envelope.none()) doc["envelope"] = EnvelopeToJson(c.scenario.envelope);
  if (!c.scenario.pendulum.standard())
    doc["pendulum"] = {{"actuator_gain", c.scenario.pendulum.actuator_gain},
                       {"walls", sim::PendulumWallsName(c.scenario.pendulum.walls)}};
  if (c.post_eval > 0)
    doc["post_eval"] = {{"episodes", c.post_eval},
                        {"envelope", EnvelopeToJson(c.post_eval_envelope)}};
  if (c.validation > 0)
    doc["validation"] = {{"episodes", c.validation}, {"candidates", c.validation_candidates}};
  if (!c.optimizer.empty()) doc["optimizer"] = c.optimizer;
  // An earlier physics kept by name (the store records the physics of every run too).
  if (!c.scenario.physics.empty()) doc["physics"] = c.scenario.physics;
  return doc;
}

EvolveConfig ConfigFromJson(const json& doc) {
  EvolveConfig c;
  try {
    c.scenario.kind = sim::ParseScenarioKind(doc.at("scenario").get<std::string>());
    c.scenario.docking = sim::ParseDocking(doc.at("joints").get<std::string>());
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
    if (doc.contains("pendulum")) {
      c.scenario.pendulum.actuator_gain = doc.at("pendulum").at("actuator_gain").get<double>();
      c.scenario.pendulum.walls =
          sim::ParsePendulumWalls(doc.at("pendulum").at("walls").get<std::string>());
    }
    if (doc.contains("post_eval")) {
      const json& post = doc.at("post_eval");
      c.post_eval = post.at("episodes").get<int>();
      c.post_eval_envelope = EnvelopeFromJson(post.at("envelope"));
    }
    if (doc.contains("validation")) {
      c.validation = doc.at("validation").at("episodes").get<int>();
      c.validation_candidates = doc.at("validation").at("candidates").get<int>();
    }
    if (doc.contains("optimizer")) c.optimizer = doc.at("optimizer").get<std::string>();
    if (doc.contains("physics"))
      sim::KeepPhysics(doc.at("physics").get<std::string>(), &c.scenario);
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

std::uint64_t ValidationSeed(std::uint64_t run_seed, int episode) {
  return modules::DeriveSeed(run_seed, {kValidationStream, static_cast<std::uint64_t>(episode)});
}

std::vector<IndividualRecord> ValidationCandidates(const RunStore& store, int count) {
  std::vector<IndividualRecord> out = store.BestDistinct(count);
  std::set<std::string> seen;
  for (const auto& r : out) seen.insert(modules::GenomeHashText(r.genome));
  std::vector<IndividualRecord> last = store.LoadGeneration(store.LastGeneration());
  std::vector<double> fitness;
  for (const auto& r : last) fitness.push_back(r.evaluation.fitness);
  int added = 0;
  for (int i : RankByFitness(fitness)) {
    if (added == count) break;
    auto& r = last[static_cast<std::size_t>(i)];
    if (!seen.insert(modules::GenomeHashText(r.genome)).second) continue;
    out.push_back(std::move(r));
    ++added;
  }
  return out;
}

bool ValidateRun(RunStore& store, const EvolveConfig& config, FitnessEvaluator& evaluator) {
  if (config.validation <= 0 || store.LastGeneration() + 1 < config.ga.generations ||
      !store.LoadValidation().empty())
    return false;
  const std::vector<IndividualRecord> candidates =
      ValidationCandidates(store, config.validation_candidates);
  // Validation jobs are numbered as if they were further generations (generation G, G + 1,
  // ...), so that every job id the farm derives from them is one no training job had.
  const int per_generation = config.ga.population * config.ga.trials;
  std::vector<EvaluationJob> jobs;
  for (std::size_t c = 0; c < candidates.size(); ++c)
    for (int k = 0; k < config.validation; ++k) {
      const int n = static_cast<int>(c) * config.validation + k;
      EvaluationJob j;
      j.generation = config.ga.generations + n / per_generation;
      j.index = (n % per_generation) / config.ga.trials;
      j.trial = n % config.ga.trials;
      j.genome = &candidates[c].genome;
      j.seed = ValidationSeed(config.seed, k);
      jobs.push_back(j);
    }
  const std::vector<Evaluation> results = evaluator.Evaluate(jobs);
  if (results.size() != jobs.size())
    throw std::runtime_error("the evaluator returned " + std::to_string(results.size()) +
                             " results for " + std::to_string(jobs.size()) + " validation jobs");
  std::vector<ValidationRecord> records;
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    ValidationRecord v;
    v.candidate = static_cast<int>(c);
    v.generation = candidates[c].generation;
    v.index = candidates[c].index;
    for (int k = 0; k < config.validation; ++k) {
      const std::size_t j =
          c * static_cast<std::size_t>(config.validation) + static_cast<std::size_t>(k);
      v.seeds.push_back(jobs[j].seed);
      v.fitness.push_back(results[j].fitness);
    }
    records.push_back(std::move(v));
  }
  store.CommitValidation(records);
  return true;
}

}  // namespace ahhs::evolver
