#include "evolver/ga/ga.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace ahhs::evolver {

using modules::Genome;
using modules::Rng;

const char* AggregateName(Aggregate a) {
  switch (a) {
    case Aggregate::kMean:
      return "mean";
    case Aggregate::kMedian:
      return "median";
    case Aggregate::kMin:
      return "min";
  }
  return "?";
}

Aggregate ParseAggregate(const std::string& name) {
  if (name == "mean") return Aggregate::kMean;
  if (name == "median") return Aggregate::kMedian;
  if (name == "min") return Aggregate::kMin;
  throw std::invalid_argument("aggregate must be mean, median or min, not '" + name + "'");
}

double AggregateFitness(Aggregate a, const std::vector<double>& trials) {
  if (trials.empty()) throw std::invalid_argument("AggregateFitness: no trials");
  switch (a) {
    case Aggregate::kMean: {
      double sum = 0;
      for (double f : trials) sum += f;
      return sum / static_cast<double>(trials.size());
    }
    case Aggregate::kMedian: {
      std::vector<double> sorted = trials;
      std::sort(sorted.begin(), sorted.end());
      const std::size_t n = sorted.size();
      return n % 2 == 1 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
    }
    case Aggregate::kMin:
      return *std::min_element(trials.begin(), trials.end());
  }
  return 0;
}

void GaParamsToJson(const GaParams& p, nlohmann::json* doc) {
  (*doc)["population"] = p.population;
  (*doc)["generations"] = p.generations;
  (*doc)["elitism"] = p.elitism;
  (*doc)["mutation_rate"] = p.mutation.gene_rate;
  (*doc)["mutation_max_change"] = p.mutation.max_change;
  (*doc)["mutation_profile"] = modules::MutationProfileName(p.mutation.profile);
  (*doc)["crossover_rate"] = p.crossover_rate;
  (*doc)["selection_epsilon"] = p.selection_epsilon;
  if (p.trials != 1) {
    (*doc)["trials"] = p.trials;
    (*doc)["aggregate"] = AggregateName(p.aggregate);
  }
}

GaParams GaParamsFromJson(const nlohmann::json& doc) {
  GaParams p;
  p.population = doc.at("population").get<int>();
  p.generations = doc.at("generations").get<int>();
  p.elitism = doc.at("elitism").get<int>();
  p.mutation.gene_rate = doc.at("mutation_rate").get<double>();
  p.mutation.max_change = doc.at("mutation_max_change").get<double>();
  // Runs stored before profiles existed mutated with what is now "fine-doses".
  p.mutation.profile = modules::ParseMutationProfile(
      doc.value("mutation_profile",
                std::string(modules::MutationProfileName(modules::MutationProfile::kFineDoses))));
  p.crossover_rate = doc.at("crossover_rate").get<double>();
  p.selection_epsilon = doc.at("selection_epsilon").get<double>();
  p.trials = doc.value("trials", 1);
  if (doc.contains("aggregate"))
    p.aggregate = ParseAggregate(doc.at("aggregate").get<std::string>());
  return p;
}

std::string CheckGaParams(const GaParams& p) {
  if (p.population < 2) return "population must be at least 2";
  if (p.generations < 1) return "generations must be at least 1";
  if (p.elitism < 0 || p.elitism >= p.population) return "elitism must be in [0, population - 1]";
  if (!(p.mutation.gene_rate >= 0 && p.mutation.gene_rate <= 1))
    return "mutation rate must be in [0, 1]";
  if (!(p.mutation.max_change > 0 && p.mutation.max_change <= 1))
    return "mutation max change must be in (0, 1]";
  if (!(p.crossover_rate >= 0 && p.crossover_rate <= 1)) return "crossover rate must be in [0, 1]";
  if (!(p.selection_epsilon > 0 && std::isfinite(p.selection_epsilon)))
    return "selection epsilon must be positive";
  if (p.trials < 1 || p.trials > kMaxTrials)
    return "trials must be in [1, " + std::to_string(kMaxTrials) + "]";
  return "";
}

std::uint64_t EvaluationSeed(std::uint64_t run_seed, int generation, int index) {
  return modules::DeriveSeed(run_seed, {kEvalStream, static_cast<std::uint64_t>(generation),
                                        static_cast<std::uint64_t>(index)});
}

std::uint64_t TrialSeed(std::uint64_t run_seed, int generation, int index, int trial) {
  if (trial == 0) return EvaluationSeed(run_seed, generation, index);
  return modules::DeriveSeed(
      run_seed, {kEvalStream, static_cast<std::uint64_t>(generation),
                 static_cast<std::uint64_t>(index), static_cast<std::uint64_t>(trial)});
}

std::vector<Genome> InitialPopulation(const modules::Shape& shape, const GaParams& params,
                                      std::uint64_t run_seed) {
  std::vector<Genome> population;
  population.reserve(static_cast<std::size_t>(params.population));
  for (int i = 0; i < params.population; ++i) {
    // One stream per individual: individual i does not depend on the population size.
    Rng rng(modules::DeriveSeed(run_seed, {kInitStream, static_cast<std::uint64_t>(i)}));
    population.push_back(modules::RandomGenome(shape, rng));
  }
  return population;
}

int SelectProportional(const std::vector<double>& fitness, double epsilon, Rng& rng) {
  if (fitness.empty()) throw std::invalid_argument("selection from an empty generation");
  double lowest = fitness[0];
  for (double f : fitness) {
    if (!std::isfinite(f)) throw std::invalid_argument("selection needs finite fitness values");
    lowest = std::min(lowest, f);
  }
  double total = 0;
  for (double f : fitness) total += f - lowest + epsilon;
  // Walk the wheel; the last individual takes any rounding remainder.
  double ball = rng.Uniform() * total;
  for (std::size_t i = 0; i + 1 < fitness.size(); ++i) {
    ball -= fitness[i] - lowest + epsilon;
    if (ball < 0) return static_cast<int>(i);
  }
  return static_cast<int>(fitness.size() - 1);
}

std::vector<int> RankByFitness(const std::vector<double>& fitness) {
  std::vector<int> order(fitness.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return fitness[static_cast<std::size_t>(a)] > fitness[static_cast<std::size_t>(b)];
  });
  return order;
}

std::vector<Genome> Breed(const std::vector<Genome>& parents, const std::vector<double>& fitness,
                          const GaParams& params, std::uint64_t run_seed, int next_generation) {
  if (parents.size() != fitness.size() || parents.empty())
    throw std::invalid_argument("Breed: parents and fitness differ in size");
  Rng rng(
      modules::DeriveSeed(run_seed, {kBreedStream, static_cast<std::uint64_t>(next_generation)}));
  std::vector<Genome> next;
  next.reserve(static_cast<std::size_t>(params.population));
  const std::vector<int> ranked = RankByFitness(fitness);
  for (int e = 0; e < params.elitism && e < static_cast<int>(ranked.size()); ++e)
    next.push_back(parents[static_cast<std::size_t>(ranked[static_cast<std::size_t>(e)])]);
  while (static_cast<int>(next.size()) < params.population) {
    const auto a =
        static_cast<std::size_t>(SelectProportional(fitness, params.selection_epsilon, rng));
    Genome child = parents[a];
    if (rng.Bernoulli(params.crossover_rate)) {
      const auto b =
          static_cast<std::size_t>(SelectProportional(fitness, params.selection_epsilon, rng));
      child = modules::Crossover(parents[a], parents[b], rng).first;
    }
    modules::Mutate(&child, params.mutation, rng);
    next.push_back(std::move(child));
  }
  return next;
}

GenerationStats Summarise(const std::vector<double>& fitness) {
  if (fitness.empty()) throw std::invalid_argument("Summarise: no fitness values");
  GenerationStats s;
  const std::vector<int> ranked = RankByFitness(fitness);
  s.best_index = ranked.front();
  s.best = fitness[static_cast<std::size_t>(ranked.front())];
  s.worst = fitness[static_cast<std::size_t>(ranked.back())];
  double sum = 0;
  for (double f : fitness) sum += f;
  s.mean = sum / static_cast<double>(fitness.size());
  std::vector<double> sorted = fitness;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t n = sorted.size();
  s.median = n % 2 == 1 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
  return s;
}

std::vector<Evaluation> StepGeneration(const modules::Shape& shape, const GaParams& params,
                                       std::uint64_t run_seed, int g,
                                       const std::vector<Genome>& parents,
                                       const std::vector<double>& fitness,
                                       FitnessEvaluator& evaluator, std::vector<Genome>* population,
                                       std::vector<EvaluationJob>* jobs,
                                       std::vector<Evaluation>* trial_results) {
  *population = g == 0 ? InitialPopulation(shape, params, run_seed)
                       : Breed(parents, fitness, params, run_seed, g);
  const int k = params.trials;
  jobs->clear();
  for (int i = 0; i < params.population; ++i)
    for (int t = 0; t < k; ++t)
      jobs->push_back(
          {g, i, t, &(*population)[static_cast<std::size_t>(i)], TrialSeed(run_seed, g, i, t)});
  std::vector<Evaluation> results = evaluator.Evaluate(*jobs);
  if (results.size() != jobs->size())
    throw std::runtime_error("the evaluator returned the wrong number of results");
  if (trial_results) *trial_results = results;
  if (k == 1) return results;
  std::vector<Evaluation> individuals;
  for (int i = 0; i < params.population; ++i) {
    Evaluation sum;
    std::vector<double> scores;
    for (int t = 0; t < k; ++t) {
      const Evaluation& e = results[static_cast<std::size_t>(i * k + t)];
      scores.push_back(e.fitness);
      sum.cost += e.cost;
      sum.wall_time += e.wall_time;
      sum.attempt = std::max(sum.attempt, e.attempt);
      if (t == 0) sum.worker = e.worker;
      if (sum.message.empty() && !e.message.empty())
        sum.message = "trial " + std::to_string(t) + ": " + e.message;
    }
    sum.fitness = AggregateFitness(params.aggregate, scores);
    individuals.push_back(std::move(sum));
  }
  return individuals;
}

std::vector<GenerationStats> RunGa(const modules::Shape& shape, const GaParams& params,
                                   std::uint64_t run_seed, FitnessEvaluator& evaluator,
                                   std::vector<Genome>* final_population,
                                   std::vector<double>* final_fitness) {
  const std::string error = CheckGaParams(params);
  if (!error.empty()) throw std::invalid_argument(error);
  std::vector<GenerationStats> stats;
  std::vector<Genome> population, parents;
  std::vector<double> fitness;
  std::vector<EvaluationJob> jobs;
  for (int g = 0; g < params.generations; ++g) {
    parents.swap(population);
    const std::vector<Evaluation> results =
        StepGeneration(shape, params, run_seed, g, parents, fitness, evaluator, &population, &jobs);
    fitness.clear();
    for (const auto& r : results) fitness.push_back(r.fitness);
    stats.push_back(Summarise(fitness));
  }
  if (final_population) *final_population = population;
  if (final_fitness) *final_fitness = fitness;
  return stats;
}

}  // namespace ahhs::evolver
