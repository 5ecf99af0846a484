#include "evolver/app/evaluate_app.h"

#include <unistd.h>

#include <chrono>
#include <stdexcept>

#include "base/children.h"
#include "bus/lcm_bus.h"
#include "evolver/evolve/evolution.h"
#include "evolver/run/run_end.h"
#include "evolver/serve/service_run.h"
#include "modules/core/random.h"
#include "sim/core/scenario.h"

namespace ahhs::evolver {

namespace cli = base::cli;

void AddEvaluateOptions(cli::App& app, EvaluateOptions* o) {
  o->scenario.Add(app, "", "episode length in simulated seconds (default: the scenario's)");
  o->scenario.AddPhysics(app);
  o->envelope.Add(app,
                  "envelope of noise of every episode: none, paper or wide (docs/scenarios.md)");
  app.add_option("--variant", o->variant, "the shape of vector genomes: ahhs1 or ahhs2")
      ->check(cli::IsMember({"ahhs1", "ahhs2"}))
      ->capture_default_str();
  app.add_option("--hormones", o->hormones, "hormones of vector genomes")
      ->check(cli::Range(1, modules::Ranges::kMaxHormones))
      ->capture_default_str();
  app.add_option("--rules", o->rules, "rules of vector genomes")
      ->check(cli::Range(0, modules::Ranges::kMaxRules))
      ->capture_default_str();
  app.add_option("--trials", o->trials, "episodes per genome, each with its own seed")
      ->check(cli::Range(1, kMaxTrials))
      ->capture_default_str();
  app.add_option("--aggregate", o->aggregate,
                 "a genome's fitness from its trials: mean, median, min")
      ->check(cli::IsMember({"mean", "median", "min"}))
      ->capture_default_str();
  app.add_option("--seed", o->seed, "seed of the requests that bring none")
      ->check(modules::SeedTextError)
      ->capture_default_str();
  AddFarmOptions(app, &o->farm, "seconds without any worker before a request fails");
  app.add_option(
      "--out", o->out_dir,
      "record the run in this directory: each request one generation (docs/protocol.md)");
  app.add_option("--resume", o->resume_dir, "go on recording the run in this directory");
  app.add_option("--population", o->population, "--out: genomes per generation (per request)")
      ->check(cli::Range(1, kMaxServiceBatch));
  app.add_option("--generations", o->generations, "--out: generations of the run")
      ->check(cli::Range(1, 10000000));
  app.add_option("--optimizer", o->optimizer, "--out: the optimizer's name, stored with the run")
      ->capture_default_str();
  app.add_flag("--overwrite", o->overwrite, "--out: replace a run already in the directory");
  AddRunEndOptions(app, &o->end, "--out: ");
}

namespace {

void CheckCombinations(const cli::App& app, const EvaluateOptions& o) {
  if (!o.out_dir.empty() && !o.resume_dir.empty())
    throw std::invalid_argument("give --out or --resume, not both");
  if (!o.resume_dir.empty()) {
    for (const char* name :
         {"--scenario", "--docking", "--joints", "--modules", "--duration", "--variant",
          "--hormones", "--rules", "--trials", "--aggregate", "--seed", "--population",
          "--generations", "--optimizer", "--overwrite", "--pendulum.actuator-gain",
          "--pendulum.walls", "--physics"})
      if (app.count(name))
        throw std::invalid_argument(std::string(name) +
                                    " cannot be given with --resume: the run keeps its own");
    for (const char* name : kRunEndOptionNames)
      if (app.count(name))
        throw std::invalid_argument(std::string(name) +
                                    " cannot be given with --resume: the run keeps its own");
    if (o.envelope.given())
      throw std::invalid_argument(
          "--envelope cannot be given with --resume: the run keeps its own");
  }
  if (!o.out_dir.empty() && (o.population == 0 || o.generations == 0))
    throw std::invalid_argument("--out needs --population and --generations");
  if (o.out_dir.empty() && o.resume_dir.empty() &&
      (app.count("--population") || app.count("--generations") || app.count("--overwrite") ||
       app.count("--validation") || app.count("--validation-candidates") ||
       app.count("--post-eval") || app.count("--post-eval-envelope")))
    throw std::invalid_argument(
        "--population, --generations, --overwrite, --validation, --validation-candidates, "
        "--post-eval and --post-eval-envelope go with --out");
}

// Opens the run of --out or --resume; a resumed run's stored config replaces the settings.
void OpenRun(const EvaluateOptions& o, const std::string& command_line, EvaluateSetup* s) {
  EvolveConfig config;
  config.scenario = s->settings.scenario;
  config.variant = s->settings.shape.variant;
  config.hormones = s->settings.shape.hormones;
  config.rules = s->settings.shape.rules;
  config.ga.population = o.population;
  config.ga.generations = o.generations;
  config.ga.trials = s->settings.trials;
  config.ga.aggregate = s->settings.aggregate;
  config.seed = s->settings.seed;
  config.optimizer = o.optimizer;
  ApplyRunEndOptions(o.end, &config);
  const bool resume = !o.resume_dir.empty();
  s->store =
      OpenServiceRun(resume ? o.resume_dir : o.out_dir, resume, o.overwrite, s->farm.run, &config);
  s->settings.scenario = config.scenario;
  s->settings.shape = config.shape();
  s->settings.trials = config.ga.trials;
  s->settings.aggregate = config.ga.aggregate;
  s->settings.seed = config.seed;
  s->run.store = s->store.get();
  s->run.optimizer = config.optimizer;
  s->run.population = config.ga.population;
  s->run.generations = config.ga.generations;
  s->run.validation = config.validation;
  s->run.post_eval = config.post_eval;
  s->config = config;
  s->run.session = s->store->BeginSession(command_line);
  s->run.seconds = [] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
  };
}

}  // namespace

EvaluateSetup SetUpEvaluate(const cli::App& app, const EvaluateOptions& o,
                            const std::string& command_line) {
  CheckCombinations(app, o);
  EvaluateSetup s;
  s.settings.scenario = o.scenario.Config();
  s.settings.scenario.envelope = o.envelope.Resolve();
  const std::string error = sim::CheckConfig(s.settings.scenario);
  if (!error.empty()) throw std::invalid_argument(error);
  const auto probe = sim::MakeScenario(s.settings.scenario);
  s.settings.shape.variant =
      o.variant == "ahhs1" ? modules::Variant::kAhhs1 : modules::Variant::kAhhs2;
  s.settings.shape.hormones = o.hormones;
  s.settings.shape.rules = o.rules;
  s.settings.shape.sensors = probe->num_sensors();
  s.settings.shape.actuators = probe->num_actuators();
  s.settings.trials = o.trials;
  s.settings.aggregate = ParseAggregate(o.aggregate);
  s.settings.seed = o.seed;
  s.farm.run = base::HostName() + "-" + std::to_string(getpid()) + "-evaluate";
  if (!o.out_dir.empty() || !o.resume_dir.empty()) OpenRun(o, command_line, &s);
  s.farm.config = s.settings.scenario;  // (a resumed run's own)
  s.farm.population = kMaxServiceBatch;
  s.farm.trials = s.settings.trials;
  ApplyFarmOptions(o.farm, &s.farm);
  return s;
}

void FinishRun(const EvaluateSetup& setup, FitnessEvaluator& farm, std::FILE* out) {
  if (!setup.store) return;
  RunStore& store = *setup.store;
  if (store.LastGeneration() + 1 < setup.config.ga.generations) return;
  if (ValidateRun(store, setup.config, farm)) {
    const auto validation = store.LoadValidation();
    const IndividualRecord best = store.Best();
    std::fprintf(out, "validation: the best is generation %d, individual %d (%zu candidates)\n",
                 best.generation, best.index, validation.size());
  }
  if (setup.config.post_eval > 0) PostEvaluateBest(store, setup.config, out);
  store.Export(true);
}

}  // namespace ahhs::evolver
