// The paper's genetic algorithm (docs/evolution.md, "The GA"; docs/model.md, "Variation"), with no
// I/O and no LCM: linear proportional (roulette-wheel) selection, elitism with re-evaluation,
// per-gene mutation and two-point crossover. Every random draw of generation g comes from
// DeriveSeed(run_seed, {kBreedStream, g}), so breeding generation g+1 needs nothing but
// generation g's genomes and fitness: a resumed run breeds exactly what the uninterrupted run
// would have bred.
//
// Beyond the paper (robust evolution, docs/evolution.md "Trials"): each individual may be
// evaluated on `trials` episodes with seeds fresh every generation, and its fitness is their
// aggregate (mean, median or min). The elite is evaluated again like everyone else and keeps only
// its new aggregate. With one trial everything is the paper's, bit for bit.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "modules/core/genome.h"
#include "modules/core/variation.h"

namespace ahhs::evolver {

// How an individual's trials make its fitness.
enum class Aggregate { kMean, kMedian, kMin };
const char* AggregateName(Aggregate a);
// Throws std::invalid_argument for anything but "mean", "median" or "min".
Aggregate ParseAggregate(const std::string& name);
// The aggregate of one individual's trial fitnesses (in trial order; the mean sums in that
// order). Throws std::invalid_argument for an empty vector.
double AggregateFitness(Aggregate a, const std::vector<double>& trials);

inline constexpr int kMaxTrials = 64;

struct GaParams {
  int population = 20;
  int generations = 200;
  int elitism = 1;  // best individuals copied unchanged (and re-evaluated) into the next generation
  modules::MutationParams mutation;  // per-gene rate 0.15, max change 0.1
  double crossover_rate = 0.05;      // probability that an offspring comes from two parents
  double selection_epsilon = 1e-6;   // weight of the worst individual in the roulette wheel
  int trials = 1;                    // episodes per individual and generation (not the paper's)
  Aggregate aggregate = Aggregate::kMean;
};

// "" or a message naming the bad parameter.
std::string CheckGaParams(const GaParams& params);

// The parameters as a run's config stores them, flat keys: population, generations, elitism,
// mutation_rate, mutation_max_change, mutation_profile, crossover_rate, selection_epsilon; and
// trials and aggregate only when trials > 1 (a paper run's config is what it always was).
void GaParamsToJson(const GaParams& params, nlohmann::json* doc);
// Throws nlohmann::json::exception for a missing or mistyped key.
GaParams GaParamsFromJson(const nlohmann::json& doc);

// One job of a generation: evaluate `genome` with evaluation seed `seed`.
struct EvaluationJob {
  int generation = 0;
  int index = 0;  // individual within the generation
  int trial = 0;  // episode of that individual, 0 to trials - 1
  const modules::Genome* genome = nullptr;
  std::uint64_t seed = 0;
};

// The outcome of one evaluation. Only `fitness` matters to the GA; the rest is recorded.
struct Evaluation {
  double fitness = 0;
  double cost = 0;
  std::vector<double> descriptor;  // the episode's behaviour descriptor (EpisodeResult)
  std::string worker;              // who evaluated it ("" in-process)
  int attempt = 0;  // how often the job was issued before this result (0 = first issue)
  double wall_time = 0;
  std::string message;  // e.g. why an episode failed (its fitness is then 0)
};

// Fitness behind an interface (pagmo2's problem): the evaluation farm, an in-process arena or
// an analytic function in tests. Must return one finite fitness per job, in job order, and be a
// pure function of (genome, seed) for the run to be reproducible.
class FitnessEvaluator {
 public:
  virtual ~FitnessEvaluator() = default;
  virtual std::vector<Evaluation> Evaluate(const std::vector<EvaluationJob>& jobs) = 0;
};

// Seed streams (the first id given to DeriveSeed after the run seed).
inline constexpr std::uint64_t kInitStream = 1, kBreedStream = 2, kEvalStream = 3;

// Evaluation seed of individual `index` in `generation` (its first trial).
std::uint64_t EvaluationSeed(std::uint64_t run_seed, int generation, int index);
// Seed of trial `trial` of that individual: EvaluationSeed for trial 0, so a run with one trial
// has the paper's seeds and trial 0 of a run with k trials the same seed.
std::uint64_t TrialSeed(std::uint64_t run_seed, int generation, int index, int trial);

// Generation 0: `params.population` random genomes of the given shape.
std::vector<modules::Genome> InitialPopulation(const modules::Shape& shape, const GaParams& params,
                                               std::uint64_t run_seed);

// Roulette wheel over weights f_i - f_min + epsilon. Throws std::invalid_argument for an empty
// or non-finite fitness vector.
int SelectProportional(const std::vector<double>& fitness, double epsilon, modules::Rng& rng);

// Indices sorted by fitness, best first; ties keep the lower index first.
std::vector<int> RankByFitness(const std::vector<double>& fitness);

// Generation `next_generation` bred from the previous one: the `elitism` best unchanged first,
// then offspring of proportional selection (crossover with crossover_rate, then mutation).
std::vector<modules::Genome> Breed(const std::vector<modules::Genome>& parents,
                                   const std::vector<double>& fitness, const GaParams& params,
                                   std::uint64_t run_seed, int next_generation);

struct GenerationStats {
  double best = 0, mean = 0, median = 0, worst = 0;
  int best_index = 0;  // lowest index among the best
};
GenerationStats Summarise(const std::vector<double>& fitness);

// One generation of the GA, the step both RunGa and the stored evolution loop take: the
// population of generation `g` (the initial one, or bred from `parents` and their `fitness`),
// evaluated. `population` receives the genomes; `jobs` the evaluation jobs, individual-major
// (job i * trials + t is trial t of individual i), pointing into `population`; `trial_results`
// (optional) each job's evaluation. Returns one evaluation per individual: with one trial its
// job's, otherwise the aggregate fitness with the trials' summed cost and wall time, the most
// attempts, the first trial's worker and the first message. Throws when the evaluator returns
// the wrong number of results.
std::vector<Evaluation> StepGeneration(
    const modules::Shape& shape, const GaParams& params, std::uint64_t run_seed, int g,
    const std::vector<modules::Genome>& parents, const std::vector<double>& fitness,
    FitnessEvaluator& evaluator, std::vector<modules::Genome>* population,
    std::vector<EvaluationJob>* jobs, std::vector<Evaluation>* trial_results = nullptr);

// A whole run in memory (tests and analytic benchmarks): evaluates, breeds, repeats. Returns
// the statistics of every generation; `final_population` gets the last generation's genomes.
std::vector<GenerationStats> RunGa(const modules::Shape& shape, const GaParams& params,
                                   std::uint64_t run_seed, FitnessEvaluator& evaluator,
                                   std::vector<modules::Genome>* final_population = nullptr,
                                   std::vector<double>* final_fitness = nullptr);

}  // namespace ahhs::evolver
