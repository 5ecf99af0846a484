// The GA core on analytic fitness functions and against hand-checked selection behaviour.
#include "evolver/ga/ga.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <set>

using namespace ahhs;
using evolver::Evaluation;
using evolver::EvaluationJob;
using evolver::GaParams;

namespace {

// Analytic fitness: how close every hormone's alpha, mu and D are to 0.5 (maximum 0 when
// all are). A random genome starts with all of them in [0, 0.1], so the GA must climb.
class DistanceToTarget : public evolver::FitnessEvaluator {
 public:
  std::vector<Evaluation> Evaluate(const std::vector<EvaluationJob>& jobs) override {
    std::vector<Evaluation> out;
    for (const auto& j : jobs) {
      double d = 0;
      for (const auto& h : j.genome->hormones)
        d += std::fabs(h.alpha - 0.5) + std::fabs(h.mu - 0.5) + std::fabs(h.diffusion - 0.5);
      Evaluation e;
      e.fitness = -d;
      out.push_back(e);
      ++calls;
    }
    return out;
  }
  int calls = 0;
};

// Fitness = the evaluation seed's low bits: checks that the seeds reach the evaluator.
class SeedEcho : public evolver::FitnessEvaluator {
 public:
  std::vector<Evaluation> Evaluate(const std::vector<EvaluationJob>& jobs) override {
    std::vector<Evaluation> out;
    for (const auto& j : jobs) {
      Evaluation e;
      e.fitness = static_cast<double>(j.seed % 1000);
      seeds.push_back(j.seed);
      out.push_back(e);
    }
    return out;
  }
  std::vector<std::uint64_t> seeds;
};

modules::Shape SmallShape() { return {modules::Variant::kAhhs2, 4, 6, 3, 1}; }

}  // namespace

TEST_CASE("proportional selection follows f - f_min + epsilon") {
  // Weights: 0 - 0 + eps, 1 + eps, 3 + eps -> probabilities ~ 0, 1/4, 3/4.
  const std::vector<double> fitness{2.0, 3.0, 5.0};
  modules::Rng rng(7);
  std::map<int, int> counts;
  const int n = 200000;
  for (int i = 0; i < n; ++i) ++counts[evolver::SelectProportional(fitness, 1e-9, rng)];
  CHECK(counts[0] < 5);
  CHECK(static_cast<double>(counts[1]) / n == Approx(0.25).margin(0.005));
  CHECK(static_cast<double>(counts[2]) / n == Approx(0.75).margin(0.005));
}

TEST_CASE("equal fitness gives uniform selection, bad input is refused") {
  modules::Rng rng(3);
  std::map<int, int> counts;
  for (int i = 0; i < 40000; ++i)
    ++counts[evolver::SelectProportional({1.0, 1.0, 1.0, 1.0}, 1e-6, rng)];
  for (int k = 0; k < 4; ++k) CHECK(counts[k] / 40000.0 == Approx(0.25).margin(0.01));
  CHECK_THROWS_AS(evolver::SelectProportional({}, 1e-6, rng), std::invalid_argument);
  CHECK_THROWS_AS(evolver::SelectProportional({1.0, NAN}, 1e-6, rng), std::invalid_argument);
}

TEST_CASE("rank and summary statistics") {
  const std::vector<double> f{0.5, 0.9, 0.1, 0.9};
  CHECK(evolver::RankByFitness(f) == std::vector<int>{1, 3, 0, 2});
  const auto s = evolver::Summarise(f);
  CHECK(s.best == 0.9);
  CHECK(s.best_index == 1);
  CHECK(s.worst == 0.1);
  CHECK(s.mean == Approx(0.6));
  CHECK(s.median == Approx(0.7));
  CHECK(evolver::Summarise({3.0, 1.0, 2.0}).median == 2.0);
}

TEST_CASE("elitism copies the best unchanged into slot 0, the rest are fresh offspring") {
  GaParams p;
  p.population = 10;
  auto parents = evolver::InitialPopulation(SmallShape(), p, 5);
  std::vector<double> fitness(10, 0.0);
  fitness[6] = 1.0;
  const auto next = evolver::Breed(parents, fitness, p, 5, 1);
  REQUIRE(next.size() == 10);
  CHECK(modules::GenomeHash(next[0]) == modules::GenomeHash(parents[6]));
  for (const auto& g : next) CHECK(modules::CheckGenome(g).empty());
  // Mutation at rate 0.15 over 10 genes leaves most offspring changed.
  int changed = 0;
  for (std::size_t i = 1; i < next.size(); ++i) {
    bool same_as_a_parent = false;
    for (const auto& q : parents)
      if (modules::GenomeHash(q) == modules::GenomeHash(next[i])) same_as_a_parent = true;
    if (!same_as_a_parent) ++changed;
  }
  CHECK(changed >= 6);
}

TEST_CASE("breeding is a pure function of (parents, fitness, params, seed, generation)") {
  GaParams p;
  p.population = 12;
  p.crossover_rate = 0.5;  // exercise crossover too
  const auto parents = evolver::InitialPopulation(SmallShape(), p, 11);
  std::vector<double> fitness;
  for (int i = 0; i < 12; ++i) fitness.push_back(std::sin(i));
  const auto a = evolver::Breed(parents, fitness, p, 11, 3);
  const auto b = evolver::Breed(parents, fitness, p, 11, 3);
  const auto c = evolver::Breed(parents, fitness, p, 11, 4);
  bool all_equal = true, any_different = false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    all_equal &= modules::GenomeHash(a[i]) == modules::GenomeHash(b[i]);
    any_different |= modules::GenomeHash(a[i]) != modules::GenomeHash(c[i]);
  }
  CHECK(all_equal);
  CHECK(any_different);
}

TEST_CASE("the GA climbs an analytic fitness function, with the paper's rates") {
  GaParams p;
  p.population = 30;
  p.generations = 150;
  DistanceToTarget f;
  std::vector<modules::Genome> final_population;
  const auto stats = evolver::RunGa(SmallShape(), p, 42, f, &final_population);
  REQUIRE(stats.size() == 150);
  CHECK(f.calls == 30 * 150);
  // 4 hormones x 3 fields start ~0.45 from the target each: distance ~5.4.
  CHECK(stats.front().best < -4.5);
  CHECK(stats.back().best > -2.5);
  // Elitism: the best never gets worse on a noise-free function.
  for (std::size_t g = 1; g < stats.size(); ++g) CHECK(stats[g].best >= stats[g - 1].best);
  // And without selection pressure (a flat function) there is no such climb.
  class Flat : public evolver::FitnessEvaluator {
   public:
    std::vector<Evaluation> Evaluate(const std::vector<EvaluationJob>& jobs) override {
      return std::vector<Evaluation>(jobs.size());
    }
  } flat;
  std::vector<modules::Genome> drifted;
  evolver::RunGa(SmallShape(), p, 42, flat, &drifted);
  std::vector<EvaluationJob> jobs;
  for (auto& g : drifted) jobs.push_back({0, 0, 0, &g, 0});
  double best_drift = -1e9;
  for (const auto& e : f.Evaluate(jobs)) best_drift = std::max(best_drift, e.fitness);
  CHECK(best_drift < stats.back().best - 1.0);
}

TEST_CASE("evaluation seeds derive from (run seed, generation, individual)") {
  GaParams p;
  p.population = 5;
  p.generations = 3;
  SeedEcho f;
  evolver::RunGa(SmallShape(), p, 9, f);
  REQUIRE(f.seeds.size() == 15);
  CHECK(f.seeds[0] == evolver::EvaluationSeed(9, 0, 0));
  CHECK(f.seeds[7] == evolver::EvaluationSeed(9, 1, 2));
  std::set<std::uint64_t> distinct(f.seeds.begin(), f.seeds.end());
  CHECK(distinct.size() == 15);
  CHECK(evolver::EvaluationSeed(9, 1, 2) != evolver::EvaluationSeed(10, 1, 2));
}

TEST_CASE("GA parameters are checked") {
  GaParams p;
  CHECK(evolver::CheckGaParams(p).empty());
  p.population = 1;
  CHECK_THAT(evolver::CheckGaParams(p), Catch::Contains("population"));
  p = {};
  p.elitism = 20;
  CHECK_THAT(evolver::CheckGaParams(p), Catch::Contains("elitism"));
  p = {};
  p.mutation.gene_rate = 1.5;
  CHECK_THAT(evolver::CheckGaParams(p), Catch::Contains("mutation rate"));
  p = {};
  p.crossover_rate = -0.1;
  CHECK_THAT(evolver::CheckGaParams(p), Catch::Contains("crossover"));
}

TEST_CASE("trial seeds: trial 0 is the paper's evaluation seed, all others are fresh") {
  std::set<std::uint64_t> seen;
  for (int g = 0; g < 4; ++g)
    for (int i = 0; i < 6; ++i) {
      CHECK(evolver::TrialSeed(5, g, i, 0) == evolver::EvaluationSeed(5, g, i));
      for (int t = 0; t < 5; ++t) seen.insert(evolver::TrialSeed(5, g, i, t));
    }
  CHECK(seen.size() == 4 * 6 * 5);
}

TEST_CASE("an individual's fitness is the mean, median or min of its trials") {
  using evolver::Aggregate;
  const std::vector<double> odd{0.5, 2.0, -1.0};
  CHECK(evolver::AggregateFitness(Aggregate::kMean, odd) == 0.5);
  CHECK(evolver::AggregateFitness(Aggregate::kMedian, odd) == 0.5);
  CHECK(evolver::AggregateFitness(Aggregate::kMin, odd) == -1.0);
  const std::vector<double> even{4.0, 1.0, 3.0, 2.0};
  CHECK(evolver::AggregateFitness(Aggregate::kMean, even) == 2.5);
  CHECK(evolver::AggregateFitness(Aggregate::kMedian, even) == 2.5);
  CHECK(evolver::AggregateFitness(Aggregate::kMin, even) == 1.0);
  CHECK_THROWS(evolver::AggregateFitness(Aggregate::kMean, {}));
  CHECK(evolver::ParseAggregate("median") == Aggregate::kMedian);
  CHECK_THROWS_WITH(evolver::ParseAggregate("max"), Catch::Contains("mean, median or min"));
}

TEST_CASE("with k trials every individual, the elite too, runs k jobs with fresh seeds") {
  GaParams p;
  p.population = 4;
  p.generations = 3;
  p.trials = 3;
  p.aggregate = evolver::Aggregate::kMin;
  SeedEcho f;
  std::vector<modules::Genome> population;
  std::vector<double> fitness;
  evolver::RunGa(SmallShape(), p, 9, f, &population, &fitness);
  REQUIRE(f.seeds.size() == 3 * 4 * 3);
  // Job order: generation, individual, trial.
  CHECK(f.seeds[0] == evolver::TrialSeed(9, 0, 0, 0));
  CHECK(f.seeds[1] == evolver::TrialSeed(9, 0, 0, 1));
  CHECK(f.seeds[3 * 4 + 3 * 2 + 1] == evolver::TrialSeed(9, 1, 2, 1));
  // The last generation's fitness is each individual's worst trial (seed % 1000).
  for (int i = 0; i < 4; ++i) {
    double worst = 1e9;
    for (int t = 0; t < 3; ++t)
      worst = std::min(worst, static_cast<double>(evolver::TrialSeed(9, 2, i, t) % 1000));
    CHECK(fitness[static_cast<std::size_t>(i)] == worst);
  }
}

TEST_CASE("one trial is the paper's GA bit for bit, and trial 0 of k keeps its seed") {
  GaParams one;
  one.population = 5;
  one.generations = 4;
  DistanceToTarget a, b;
  std::vector<modules::Genome> pa, pb;
  std::vector<double> fa, fb;
  const auto sa = evolver::RunGa(SmallShape(), one, 3, a, &pa, &fa);
  GaParams three = one;
  three.trials = 3;  // a seed-independent fitness: every trial scores the same
  three.aggregate = evolver::Aggregate::kMedian;  // exact (a mean of three may round)
  const auto sb = evolver::RunGa(SmallShape(), three, 3, b, &pb, &fb);
  CHECK(b.calls == 3 * a.calls);
  CHECK(fa == fb);
  for (std::size_t i = 0; i < pa.size(); ++i)
    CHECK(modules::GenomeHash(pa[i]) == modules::GenomeHash(pb[i]));
}
