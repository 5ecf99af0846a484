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

EvalService::EvalService(ServiceSettings settings, FitnessEvaluator& evaluator)
    : settings_(std::move(settings)), evaluator_(evaluator) {}

json EvalService::Hello() const {
  json envelope = json::object();
  for (const auto& k : sim::EnvelopeKeys()) envelope[k.name] = settings_.task.envelope.*k.field;
  const modules::Shape& s = settings_.shape;
  return {{"v", kServiceProtocolVersion},
          {"service", "ahhs-evaluate"},
          {"scenario", sim::ScenarioName(settings_.task.kind)},
          {"joints", sim::JointsName(settings_.task.joints)},
          {"modules", settings_.task.num_modules},
          {"duration", settings_.task.duration},
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
          {"descriptor", episode::FitnessMonitor::DescriptorNames(settings_.task.kind)},
          {"max_batch", kMaxServiceBatch}};
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
    if (key != "v" && key != "id" && key != "seed" && key != "genomes")
      throw BadRequest("unknown key '" + key + "'");
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
      const std::string fit = episode::CheckGenomeFits(genomes.back(), settings_.task);
      if (!fit.empty()) throw BadRequest(fit);
    } catch (const std::exception& e) {  // GenomeFromJson's and GenomeFromVector's messages
      throw BadRequest(where + ": " + e.what());
    }
  }
  const std::uint64_t n = requests_++;
  const std::uint64_t seed =
      request.contains("seed") ? SeedOf(request["seed"]) : modules::DeriveSeed(settings_.seed, {n});
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
  return {{"v", kServiceProtocolVersion}, {"seed", seed}, {"results", std::move(results)}};
}

}  // namespace ahhs::evolver
