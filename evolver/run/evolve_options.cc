#include "evolver/run/evolve_options.h"

#include <unistd.h>

#include <ctime>
#include <filesystem>
#include <iostream>

#include "base/children.h"
#include "base/cli.h"
#include "base/cli_toml.h"
#include "modules/core/random.h"

namespace cli = ahhs::base::cli;

namespace ahhs::evolver {

void AddEvolveOptions(cli::App& app, EvolveOptions* o) {
  base::AddStrictTomlConfig(app, "preset file (TOML, e.g. configs/gait-damped-ahhs2-30.toml)");
  o->scenario.Add(app, "",
                  "episode length, simulated seconds (0: the scenario's, 60 s gait / 3000 ticks)");
  o->scenario.AddPhysics(app);
  app.add_option("--variant", o->variant, "controller: ahhs1 or ahhs2")
      ->check(cli::IsMember({"ahhs1", "ahhs2"}))
      ->capture_default_str();
  app.add_option("--hormones", o->hormones, "hormones per controller")->capture_default_str();
  app.add_option("--rules", o->rules, "rules per controller")->capture_default_str();
  app.add_option("--population", o->population, "individuals per generation")
      ->capture_default_str();
  app.add_option("--generations", o->generations, "generations")->capture_default_str();
  app.add_option("--elitism", o->elitism, "best individuals copied (and re-evaluated)")
      ->capture_default_str();
  app.add_option("--mutation-rate", o->mutation_rate, "probability that a gene mutates")
      ->capture_default_str();
  app.add_option("--mutation-max-change", o->mutation_max_change, "largest change of a real field")
      ->capture_default_str();
  app.add_option("--mutation-profile", o->mutation_profile,
                 "step of each mutated field: paper (every real field by at most the max change) "
                 "or fine-doses (the first briefing's: AHHS2 doses by 1/50 of it, indices by 1)")
      ->check(cli::IsMember({"paper", "fine-doses"}))
      ->capture_default_str();
  app.add_option("--crossover-rate", o->crossover_rate, "two-point crossover rate")
      ->capture_default_str();
  app.add_option("--trials", o->trials,
                 "episodes per individual and generation, each with a fresh seed (robust "
                 "evolution; the paper: 1)")
      ->check(cli::Range(1, kMaxTrials))
      ->default_str("1; 3 without --config and --scenario");
  app.add_option("--aggregate", o->aggregate, "an individual's fitness from its trials")
      ->check(cli::IsMember({"mean", "median", "min"}))
      ->capture_default_str();
  AddRunEndOptions(app, &o->end, "", "0; 20 without --config and --scenario",
                   "0; 50 without --config and --scenario");
  o->envelope.Add(app,
                  "envelope of noise every episode is perturbed with: none (the paper), paper or "
                  "wide (docs/scenarios.md); default none, paper without --config and --scenario");
  app.add_option("--seed", o->seed, "run seed (every random draw of the run derives from it)")
      ->check(modules::SeedTextError)
      ->capture_default_str();
  auto* out_opt =
      app.add_option("--out", o->out_dir, "run directory (default: runs/<time>-<scenario>)");
  auto* resume_opt =
      app.add_option("--resume", o->resume_dir, "continue the run stored in this directory");
  out_opt->excludes(resume_opt);
  app.add_flag("--overwrite", o->overwrite, "replace an existing run directory given with --out");
  app.add_flag("--show-config", o->show_config,
               "print the run's configuration as JSON and exit (nothing is created or run)");
  AddFarmOptions(app, &o->farm,
                 "seconds to wait for any worker before giving up (the run stays resumable)");
}

std::unique_ptr<RunStore> OpenRun(const cli::App& app, EvolveOptions& o, EvolveConfig* config) {
  std::unique_ptr<RunStore> store;
  if (!o.resume_dir.empty()) {
    for (const char* name : {"--scenario",
                             "--docking",
                             "--joints",
                             "--modules",
                             "--duration",
                             "--variant",
                             "--hormones",
                             "--rules",
                             "--population",
                             "--generations",
                             "--elitism",
                             "--mutation-rate",
                             "--mutation-max-change",
                             "--mutation-profile",
                             "--crossover-rate",
                             "--seed",
                             "--overwrite",
                             "--trials",
                             "--aggregate",
                             "--pendulum.actuator-gain",
                             "--pendulum.walls",
                             "--physics",
                             kRunEndOptionNames[0],
                             kRunEndOptionNames[1],
                             kRunEndOptionNames[2],
                             kRunEndOptionNames[3]})
      if (app.count(name))
        throw std::invalid_argument(std::string(name) +
                                    " cannot be given with --resume: a resumed run keeps "
                                    "its stored configuration");
    if (o.envelope.given())
      throw std::invalid_argument(
          "--envelope cannot be given with --resume: a resumed run keeps its stored "
          "configuration");
    store = RunStore::Open(o.resume_dir, o.show_config ? StoreAccess::kRead : StoreAccess::kWrite);
    *config = ConfigFromJson(store->config());
    if (!config->optimizer.empty())
      throw std::invalid_argument(o.resume_dir + " is a run of " + config->optimizer +
                                  " recorded by ahhs-evaluate, not of the GA: resume it with "
                                  "that optimizer");
    // A run goes on in the physics it was made with, if this build still simulates it.
    const std::string own = sim::PhysicsVersion(config->scenario.kind, config->scenario.docking);
    if (!store->physics().empty()) {
      if (!sim::CheckPhysics(config->scenario.kind, config->scenario.docking, store->physics())
               .empty())
        throw std::invalid_argument(
            o.resume_dir + " was made with the " + sim::ScenarioName(config->scenario.kind) +
            " physics of " + store->physics() + ", this build has " + own +
            " and does not simulate that one (CHANGELOG.md names the release that does): its "
            "fitnesses would mix two physics; resume it with that release or start a new run");
      sim::KeepPhysics(store->physics(), &config->scenario);
    }
    if (store->physics().empty() && !o.show_config)
      std::cerr << "ahhs-evolve: note: " << o.resume_dir
                << " does not record its physics (an older build made it); resuming with " << own
                << '\n';
    if (o.show_config) {
      std::cout << ConfigToJson(*config).dump(2) << '\n';
      return nullptr;
    }
    store->Export(true);  // the database is the truth: rebuild files missing, short or wrong
  } else {
    // The README's main job: without --config or --scenario the run is the robust damped gait
    // (configs/gait-damped-ahhs2-30-robust.toml), options given on top of it.
    const bool main_job = app.count("--config") == 0 && app.count("--scenario") == 0;
    if (main_job) {
      if (app.count("--trials") == 0) o.trials = kMainJob.trials;
      if (app.count("--post-eval") == 0) o.end.post_eval = kMainJob.post_eval;
      if (app.count("--validation") == 0) o.end.validation = kMainJob.validation;
    }
    config->scenario = o.scenario.Config();
    config->scenario.envelope = o.envelope.Resolve(main_job ? kMainJob.envelope : "none");
    config->variant = o.variant == "ahhs1" ? modules::Variant::kAhhs1 : modules::Variant::kAhhs2;
    config->hormones = o.hormones;
    config->rules = o.rules;
    config->ga.population = o.population;
    config->ga.generations = o.generations;
    config->ga.elitism = o.elitism;
    config->ga.mutation.gene_rate = o.mutation_rate;
    config->ga.mutation.max_change = o.mutation_max_change;
    config->ga.mutation.profile = modules::ParseMutationProfile(o.mutation_profile);
    config->ga.crossover_rate = o.crossover_rate;
    config->ga.trials = o.trials;
    config->ga.aggregate = ParseAggregate(o.aggregate);
    ApplyRunEndOptions(o.end, config);
    config->seed = o.seed;
    if (o.scenario.duration < 0) throw std::invalid_argument("--duration must not be negative");
    const std::string error = CheckEvolveConfig(*config);
    if (!error.empty()) throw std::invalid_argument(error);
    if (o.show_config) {
      std::cout << ConfigToJson(*config).dump(2) << '\n';
      return nullptr;
    }
    if (o.out_dir.empty()) {
      char stamp[32];
      const std::time_t t = std::time(nullptr);
      std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&t));
      o.out_dir = std::string("runs/") + stamp + "-" + o.scenario.scenario;
    }
    const std::string run_id = base::HostName() + "-" + std::to_string(getpid()) + "-" +
                               std::to_string(std::time(nullptr));
    store = RunStore::Create(o.out_dir, run_id, config->seed, ConfigToJson(*config),
                             sim::PhysicsOf(config->scenario), o.overwrite);
  }
  return store;
}

FarmOptions FarmOptionsFor(const EvolveOptions& o, const EvolveConfig& config,
                           const std::string& wire_run) {
  FarmOptions farm;
  farm.run = wire_run;
  farm.config = config.scenario;
  farm.population = config.ga.population;
  farm.trials = config.ga.trials;
  ApplyFarmOptions(o.farm, &farm);
  return farm;
}

}  // namespace ahhs::evolver
