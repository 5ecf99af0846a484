// The evaluation service's protocol (evolver/serve/eval_service.h) over an analytic evaluator:
// golden answers, trial seeds, aggregates, and one error answer per bad request.
#include "evolver/serve/eval_service.h"

#include <stdlib.h>

#include <catch2/catch.hpp>
#include <filesystem>

#include "evolver/serve/service_run.h"
#include "modules/core/genome_json.h"
#include "modules/core/genome_vector.h"
#include "modules/core/random.h"
#include "modules/core/variation.h"

using namespace ahhs;
using nlohmann::json;

namespace {

// Fitness = the seed's last three digits / 1000: the answer shows which seed each trial had.
class SeedFitness : public evolver::FitnessEvaluator {
 public:
  std::vector<evolver::Evaluation> Evaluate(
      const std::vector<evolver::EvaluationJob>& jobs) override {
    std::vector<evolver::Evaluation> out;
    for (const auto& j : jobs) {
      evolver::Evaluation e;
      e.fitness = static_cast<double>(j.seed % 1000) / 1000;
      // Descriptor (trial, index); trial 2 of genome 1 "fails" (no descriptor).
      if (!(j.trial == 2 && j.index == 1)) e.descriptor = {1.0 * j.trial, 0.5 * j.index};
      out.push_back(e);
    }
    ++batches;
    return out;
  }
  int batches = 0;
};

evolver::ServiceSettings Settings() {
  evolver::ServiceSettings s;
  s.scenario = sim::MakeScenarioConfig(sim::ScenarioKind::kGait, sim::DockingKind::kFixed, 5, 4);
  s.shape = {modules::Variant::kAhhs2, 2, 3, 4, 1};
  s.trials = 3;
  s.aggregate = evolver::Aggregate::kMedian;
  s.seed = 9;
  return s;
}

}  // namespace

TEST_CASE("an ask is answered with every trial's seed and fitness and their aggregate") {
  SeedFitness f;
  evolver::EvalService service(Settings(), f);
  const json hello = service.Hello();
  CHECK(hello.at("v") == 2);
  CHECK(hello.at("vector_size") == 3 * 2 + 13 * 3);
  CHECK(hello.at("aggregate") == "median");
  CHECK(hello.at("physics") == sim::kGaitFixedPhysicsVersion);  // the build's own, named
  modules::Rng rng(4);
  const modules::Genome g = modules::RandomGenome({modules::Variant::kAhhs2, 2, 3, 4, 1}, rng);
  const json ask = {
      {"v", 2},
      {"id", {{"batch", 1}}},
      {"seed", 42},
      {"genomes", {modules::GenomeToJson(g), {{"vector", modules::GenomeToVector(g)}}}}};
  const json answer = service.Handle(ask.dump());
  REQUIRE_FALSE(answer.contains("error"));
  CHECK(answer.at("id") == json{{"batch", 1}});
  CHECK(answer.at("seed") == 42);
  REQUIRE(answer.at("results").size() == 2);
  for (std::uint64_t i = 0; i < 2; ++i) {
    const json& r = answer.at("results")[i];
    CHECK(r.at("genome_hash") == modules::GenomeHashText(g));  // the vector is the same genome
    std::vector<double> scores;
    for (std::uint64_t t = 0; t < 3; ++t) {
      const std::uint64_t seed = modules::DeriveSeed(42, {i, t});
      CHECK(r.at("trials")[t].at("seed") == seed);
      CHECK(r.at("trials")[t].at("fitness") == static_cast<double>(seed % 1000) / 1000);
      scores.push_back(static_cast<double>(seed % 1000) / 1000);
    }
    CHECK(r.at("fitness") == evolver::AggregateFitness(evolver::Aggregate::kMedian, scores));
    // Each trial's descriptor; the result's is their mean, without a trial that has none.
    CHECK(r.at("trials")[0].at("descriptor") == json{0.0, 0.5 * static_cast<double>(i)});
    if (i == 0) {
      CHECK(r.at("trials")[2].at("descriptor") == json{2.0, 0.0});
      CHECK(r.at("descriptor") == json{1.0, 0.0});  // (0 + 1 + 2) / 3
    } else {
      CHECK(r.at("trials")[2].at("descriptor") == nullptr);
      CHECK(r.at("descriptor") == json{0.5, 0.5});  // (0 + 1) / 2
    }
  }
  CHECK(hello.at("descriptor") == json{"end_x", "end_y"});
  CHECK(f.batches == 1);  // one request, one batch: its trials spread over the workers
  // Without a seed: DeriveSeed(service seed, {request number}).
  const json auto_seed = service.Handle(R"({"v": 2, "genomes": [{"vector": )" +
                                        json(modules::GenomeToVector(g)).dump() + "}]}");
  CHECK(auto_seed.at("seed") == modules::DeriveSeed(9, {1}));
  CHECK(auto_seed.at("id") == nullptr);
}

TEST_CASE("a bad request gets one error line naming what is wrong, and nothing is evaluated") {
  SeedFitness f;
  evolver::EvalService service(Settings(), f);
  const auto error = [&](const std::string& line) {
    const json a = service.Handle(line);
    REQUIRE(a.contains("error"));
    CHECK(a.at("v") == 2);
    return a.at("error").get<std::string>();
  };
  CHECK(error("{") == "not a JSON line");
  CHECK(error("[1]") == "a request is a JSON object");
  CHECK_THAT(error(R"({"id": 3, "genomes": []})"), Catch::Contains("protocol version"));
  CHECK(service.Handle(R"({"v": 2, "id": 3, "genomes": []})").at("id") == 3);
  CHECK_THAT(error(R"({"v": 2, "genomes": []})"), Catch::Contains("1 to 100000 per request"));
  CHECK_THAT(error(R"({"v": 2, "genomes": [{"vector": [1, 2]}]})"),
             Catch::Contains("genomes[0]: a vector of 2 values for a genome of 45"));
  CHECK_THAT(error(R"({"v": 2, "genomes": [{"vector": ["a"]}]})"),
             Catch::Contains("genomes[0]: vector: an array of numbers"));
  CHECK_THAT(error(R"({"v": 2, "genomes": [{"format": "ahhs-genome"}]})"),
             Catch::StartsWith("genomes[0]: "));
  CHECK_THAT(error(R"({"v": 2, "seed": -5, "genomes": [{"vector": []}]})"),
             Catch::Contains("genomes[0]"));
  const std::string vector = json(std::vector<double>(45, 0.5)).dump();
  CHECK_THAT(error(R"({"v": 2, "seed": -5, "genomes": [{"vector": )" + vector + "}]}"),
             Catch::Contains("seed"));
  CHECK_THAT(
      error(R"({"v": 2, "seed": "18446744073709551616", "genomes": [{"vector": )" + vector + "}]}"),
      Catch::Contains("seed"));
  CHECK_THAT(error(R"({"v": 2, "genome": []})"), Catch::Contains("unknown key 'genome'"));
  // A genome of the pendulum's shape does not fit the gait.
  modules::Rng rng(1);
  const json pendulum =
      modules::GenomeToJson(modules::RandomGenome({modules::Variant::kAhhs2, 2, 3, 10, 2}, rng));
  CHECK_THAT(error(json{{"v", 2}, {"genomes", {pendulum}}}.dump()), Catch::Contains("genomes[0]"));
  CHECK(f.batches == 0);
}

namespace {

struct ServiceRunDir {  // a fresh directory, removed at the end
  ServiceRunDir() {
    char tmpl[] = "/tmp/ahhs-service-run-XXXXXX";
    path = mkdtemp(tmpl);
    path += "/run";
  }
  ~ServiceRunDir() {
    std::error_code ec;
    std::filesystem::remove_all(std::filesystem::path(path).parent_path(), ec);
  }
  std::string path;
};

}  // namespace

TEST_CASE("a service that records a run commits one generation per request, in order") {
  ServiceRunDir dir;
  SeedFitness f;
  evolver::EvolveConfig config;
  config.scenario = Settings().scenario;
  config.variant = modules::Variant::kAhhs2;
  config.hormones = 2;
  config.rules = 3;
  config.ga.population = 2;
  config.ga.generations = 3;
  config.ga.trials = 3;
  config.ga.aggregate = evolver::Aggregate::kMedian;
  config.seed = 9;
  config.optimizer = "test";
  auto store = evolver::OpenServiceRun(dir.path, false, false, "run-1", &config);
  evolver::ServiceRun run;
  run.store = store.get();
  run.optimizer = "test";
  run.population = 2;
  run.generations = 3;
  evolver::EvalService service(Settings(), f, &run);
  CHECK(service.Hello().at("run").at("next_generation") == 0);
  std::string vector = json(std::vector<double>(45, 0.5)).dump();
  std::string other = json(std::vector<double>(45, 0.25)).dump();
  const auto ask = [&](const std::string& generation, const std::string& extra = "") {
    return service.Handle(R"({"v": 2, )" + extra + R"("generation": )" + generation +
                          R"(, "genomes": [{"vector": )" + vector + R"(}, {"vector": )" + other +
                          "}]}");
  };
  const auto error = [](const json& a) {
    return a.contains("error") ? a.at("error").get<std::string>() : "";
  };
  CHECK_THAT(error(ask("1")), Catch::Contains("ask generation 0 next"));
  CHECK_THAT(error(ask("0", R"("seed": 4, )")), Catch::Contains("the run's own"));
  CHECK_THAT(error(service.Handle(R"({"v": 2, "genomes": [{"vector": )" + vector + "}]}")),
             Catch::Contains("say which generation"));
  const json g0 = ask("0");
  REQUIRE(error(g0).empty());
  CHECK(g0.at("generation") == 0);
  CHECK(g0.at("seed") == modules::DeriveSeed(9, {0}));  // the run's seed, not a request's
  REQUIRE(store->LastGeneration() == 0);
  const auto stored = store->LoadGeneration(0);
  REQUIRE(stored.size() == 2);
  CHECK(stored[1].evaluation.fitness == g0.at("results")[1].at("fitness").get<double>());
  CHECK(stored[1].trials.size() == 3);
  CHECK(stored[1].eval_seed == g0.at("results")[1].at("trials")[0].at("seed").get<std::uint64_t>());
  // Asked again (an optimizer resumed from an older checkpoint): the same answer, nothing added.
  CHECK(ask("0") == g0);
  CHECK(store->LastGeneration() == 0);
  // Other genomes for a stored generation: refused.
  std::swap(vector, other);
  CHECK_THAT(error(ask("0")), Catch::Contains("not what the run holds"));
  CHECK_THAT(error(service.Handle(R"({"v": 2, "generation": 1, "genomes": [{"vector": )" + vector +
                                  "}]}")),
             Catch::Contains("a generation of this run has 2 genomes"));
  REQUIRE(error(ask("1")).empty());
  REQUIRE(error(ask("2")).empty());
  CHECK_THAT(error(ask("3")), Catch::Contains("the run has 3 generations"));
  CHECK(store->LastGeneration() == 2);
  // Every genome is stored in full (another optimizer's generations cannot be bred again).
  store.reset();
  auto reread = evolver::RunStore::Open(dir.path, evolver::StoreAccess::kRead);
  CHECK(modules::GenomeHashText(reread->LoadGeneration(1)[0].genome) ==
        modules::GenomeHashText(
            modules::GenomeFromVector(Settings().shape, std::vector<double>(45, 0.25))));
  CHECK(reread->config().at("optimizer") == "test");
}
