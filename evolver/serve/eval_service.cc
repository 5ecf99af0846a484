#include "evolver/serve/eval_service.h"

#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "episode/arena/episode.h"
#include "episode/fitness/fitness_monitor.h"
#include "modules/core/genome_json.h"
#include "modules/core/genome_vector.h"
#include "modules/core/random.h"
#include "sim/core/envelope.h"

namespace ahhs::evolver {

using nlohmann::json;

namespace {

// A bad request: its message is the error answer.
struct BadRequest : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

std::uint64_t SeedOf(const json& v) {
  if (v.is_number_unsigned()) return v.get<std::uint64_t>();
  if (v.is_string()) {
    const std::string text = v.get<std::string>();
    const std::string error = modules::SeedTextError(text);
    if (!error.empty()) throw BadRequest("seed: " + error);
    return std::stoull(text);
  }
  if (v.is_number_integer()) throw BadRequest("seed: a seed is not negative");
  throw BadRequest("seed: a whole number from 0 to 18446744073709551615 (or its decimal string)");
}

}  // namespace

EvalService::EvalService(ServiceSettings settings, FitnessEvaluator& evaluator, ServiceRun* run)
    : settings_(std::move(settings)), evaluator_(evaluator), run_(run) {}

json EvalService::Hello() const {
  json envelope = json::object();
  for (const auto& k : sim::EnvelopeKeys())
    if (k.Written(settings_.scenario.envelope))
      envelope[k.name] = settings_.scenario.envelope.*k.field;
  const modules::Shape& s = settings_.shape;
  json hello = {{"v", kServiceProtocolVersion},
                {"service", "ahhs-evaluate"},
                {"scenario", sim::ScenarioName(settings_.scenario.kind)},
                {"joints", sim::DockingName(settings_.scenario.docking)},
                {"modules", settings_.scenario.num_modules},
                {"duration", settings_.scenario.duration},
                {"physics", sim::PhysicsOf(settings_.scenario)},
                {"shape",
                 {{"variant", modules::VariantName(s.variant)},
                  {"hormones", s.hormones},
                  {"rules", s.rules},
                  {"sensors", s.sensors},
                  {"actuators", s.actuators}}},
                {"vector_size", modules::GenomeVectorLayout(s).size()},
                {"trials", settings_.trials},
                {"aggregate", AggregateName(settings_.aggregate)},
                {"envelope", envelope},
                {"descriptor", episode::FitnessMonitor::DescriptorNames(settings_.scenario.kind)},
                {"max_batch", kMaxServiceBatch}};
  if (run_)
    hello["run"] = {{"dir", run_->store->dir()},
                    {"optimizer", run_->optimizer},
                    {"population", run_->population},
                    {"generations", run_->generations},
                    {"next_generation", run_->store->LastGeneration() + 1},
                    {"validation", run_->validation},
                    {"post_eval", run_->post_eval}};
  return hello;
}

json EvalService::Handle(const std::string& line) {
  json id = nullptr;
  try {
    json request;
    try {
      request = json::parse(line);
    } catch (const json::exception&) {
      throw BadRequest("not a JSON line");
    }
    if (!request.is_object()) throw BadRequest("a request is a JSON object");
    if (request.contains("id")) id = request["id"];
    if (!request.contains("v") || request["v"] != kServiceProtocolVersion)
      throw BadRequest("protocol version: this service speaks \"v\": " +
                       std::to_string(kServiceProtocolVersion));
    json answer = Ask(request);
    answer["id"] = id;
    return answer;
  } catch (const BadRequest& e) {
    return {{"v", kServiceProtocolVersion}, {"id", id}, {"error", e.what()}};
  } catch (const std::exception& e) {  // the evaluator's: the farm lost its workers, ...
    return {{"v", kServiceProtocolVersion},
            {"id", id},
            {"error", std::string("evaluation failed: ") + e.what()}};
  }
}

json EvalService::Ask(const json& request) {
  for (const auto& [key, value] : request.items())
    if (key != "v" && key != "id" && key != "seed" && key != "genomes" &&
        !(run_ && key == "generation"))
      throw BadRequest("unknown key '" + key + "'");
  int generation = -1;
  if (run_) {
    const int last = run_->store->LastGeneration();
    if (!request.contains("generation") || !request["generation"].is_number_integer() ||
        request["generation"].get<std::int64_t>() < 0)
      throw BadRequest("generation: this service records a run; say which generation (from 0)");
    if (request.contains("seed")) throw BadRequest("seed: a run's seeds are the run's own");
    const std::int64_t g = request["generation"].get<std::int64_t>();
    if (g >= run_->generations)
      throw BadRequest("generation " + std::to_string(g) + ": the run has " +
                       std::to_string(run_->generations) + " generations");
    if (g > last + 1)
      throw BadRequest(
          "generation " + std::to_string(g) + ": the run holds " +
          (last < 0 ? std::string("none yet") : "generations 0 to " + std::to_string(last)) +
          "; ask generation " + std::to_string(last + 1) + " next");
    generation = static_cast<int>(g);
    if (!request.contains("genomes") || !request["genomes"].is_array() ||
        request["genomes"].size() != static_cast<std::size_t>(run_->population))
      throw BadRequest("genomes: a generation of this run has " + std::to_string(run_->population) +
                       " genomes");
  }
  if (!request.contains("genomes") || !request["genomes"].is_array())
    throw BadRequest("genomes: an array of genome documents or {\"vector\": [...]}");
  const json& docs = request["genomes"];
  if (docs.empty() || docs.size() > static_cast<std::size_t>(kMaxServiceBatch))
    throw BadRequest("genomes: 1 to " + std::to_string(kMaxServiceBatch) + " per request");
  std::vector<modules::Genome> genomes;
  for (std::size_t i = 0; i < docs.size(); ++i) {
    const std::string where = "genomes[" + std::to_string(i) + "]";
    try {
      if (docs[i].is_object() && docs[i].contains("vector")) {
        if (docs[i].size() != 1) throw BadRequest("a vector genome has only \"vector\"");
        std::vector<double> x;
        try {
          x = docs[i]["vector"].get<std::vector<double>>();
        } catch (const json::exception&) {
          throw BadRequest("vector: an array of numbers");
        }
        genomes.push_back(modules::GenomeFromVector(settings_.shape, x));
      } else {
        genomes.push_back(modules::GenomeFromJson(docs[i]));
      }
      const std::string fit = episode::CheckGenomeFits(genomes.back(), settings_.scenario);
      if (!fit.empty()) throw BadRequest(fit);
    } catch (const std::exception& e) {  // GenomeFromJson's and GenomeFromVector's messages
      throw BadRequest(where + ": " + e.what());
    }
  }
  const std::uint64_t n = requests_++;
  const std::uint64_t seed =
      run_ ? modules::DeriveSeed(settings_.seed, {static_cast<std::uint64_t>(generation)})
      : request.contains("seed") ? SeedOf(request["seed"])
                                 : modules::DeriveSeed(settings_.seed, {n});
  const double start = run_ && run_->seconds ? run_->seconds() : 0;
  std::vector<EvaluationJob> jobs;
  for (std::size_t i = 0; i < genomes.size(); ++i)
    for (int t = 0; t < settings_.trials; ++t) {
      EvaluationJob j;
      j.generation = static_cast<int>(n % (1u << 30));  // the farm's job ids: unique per request
      j.index = static_cast<int>(i);
      j.trial = t;
      j.genome = &genomes[i];
      j.seed = modules::DeriveSeed(seed, {i, static_cast<std::uint64_t>(t)});
      jobs.push_back(j);
    }
  const std::vector<Evaluation> out = evaluator_.Evaluate(jobs);
  if (out.size() != jobs.size())
    throw std::runtime_error("the evaluator returned " + std::to_string(out.size()) +
                             " results for " + std::to_string(jobs.size()) + " jobs");
  json results = json::array();
  for (std::size_t i = 0; i < genomes.size(); ++i) {
    json trials = json::array();
    std::vector<double> scores, descriptor_sum;
    int described = 0;
    for (int t = 0; t < settings_.trials; ++t) {
      const std::size_t k = i * static_cast<std::size_t>(settings_.trials) + t;
      if (!std::isfinite(out[k].fitness))
        throw std::runtime_error("a non-finite fitness for genomes[" + std::to_string(i) + "]");
      scores.push_back(out[k].fitness);
      const std::vector<double>& d = out[k].descriptor;
      trials.push_back({{"seed", jobs[k].seed},
                        {"fitness", out[k].fitness},
                        {"descriptor", d.empty() ? json(nullptr) : json(d)}});
      if (d.empty()) continue;  // the episode failed
      if (descriptor_sum.empty()) descriptor_sum.assign(d.size(), 0.0);
      if (d.size() != descriptor_sum.size())
        throw std::runtime_error("descriptors of different sizes for genomes[" + std::to_string(i) +
                                 "]");
      for (std::size_t j = 0; j < d.size(); ++j) descriptor_sum[j] += d[j];
      ++described;
    }
    json descriptor = nullptr;
    if (described > 0) {
      for (double& x : descriptor_sum) x /= described;
      descriptor = descriptor_sum;
    }
    results.push_back({{"fitness", AggregateFitness(settings_.aggregate, scores)},
                       {"descriptor", std::move(descriptor)},
                       {"genome_hash", modules::GenomeHashText(genomes[i])},
                       {"trials", std::move(trials)}});
  }
  json answer = {{"v", kServiceProtocolVersion}, {"seed", seed}, {"results", results}};
  if (run_) {
    answer["generation"] = generation;
    Record(generation, genomes, jobs, out, results, start);
  }
  return answer;
}

void EvalService::Record(int generation, const std::vector<modules::Genome>& genomes,
                         const std::vector<EvaluationJob>& jobs, const std::vector<Evaluation>& out,
                         const json& results, double start) {
  const auto k = static_cast<std::size_t>(settings_.trials);
  std::vector<IndividualRecord> records;
  std::vector<double> fitness;
  for (std::size_t i = 0; i < genomes.size(); ++i) {
    IndividualRecord r;
    r.generation = generation;
    r.index = static_cast<int>(i);
    r.genome = genomes[i];
    r.eval_seed = jobs[i * k].seed;
    r.evaluation = out[i * k];  // worker, timings and message of the first trial
    r.evaluation.fitness = results[i].at("fitness").get<double>();
    if (settings_.trials > 1)
      for (std::size_t t = 0; t < k; ++t)
        r.trials.push_back({static_cast<int>(t), jobs[i * k + t].seed, out[i * k + t]});
    fitness.push_back(r.evaluation.fitness);
    records.push_back(std::move(r));
  }
  RunStore& store = *run_->store;
  if (generation <= store.LastGeneration()) {
    const std::vector<IndividualRecord> stored = store.LoadGeneration(generation);
    for (std::size_t i = 0; i < records.size(); ++i)
      if (i >= stored.size() ||
          modules::GenomeHashText(stored[i].genome) != modules::GenomeHashText(records[i].genome) ||
          stored[i].evaluation.fitness != records[i].evaluation.fitness)
        throw BadRequest("generation " + std::to_string(generation) + ": genomes[" +
                         std::to_string(i) +
                         "] is not what the run holds for it (an optimizer state that does not "
                         "belong to this run?)");
    return;  // asked again after a resume: answered, already stored
  }
  GenerationRecord record;
  record.generation = generation;
  record.stats = Summarise(fitness);
  record.wall_time = run_->seconds ? run_->seconds() - start : 0;
  record.session = run_->session;
  store.CommitGeneration(record, records);
}

}  // namespace ahhs::evolver
