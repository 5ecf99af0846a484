// ahhs-evolve: the paper's GA over the evaluation farm, stored in a run directory
// (docs/evolution.md). Starts --workers local ahhs-worker processes itself (default: one per
// core) and uses any other worker heard on the bus. Ctrl-C stops cleanly; --resume DIR
// continues a stopped or killed run and ends with exactly the uninterrupted run's results.
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <thread>

#include "base/atomic_file.h"
#include "base/children.h"
#include "base/cli.h"
#include "base/cli_toml.h"
#include "base/format.h"
#include "bus/fault_bus.h"
#include "bus/lcm_bus.h"
#include "episode/arena/post_eval.h"
#include "episode/arena/process_arena.h"
#include "evolver/evolve/evolution.h"
#include "evolver/farm/arena_evaluator.h"
#include "evolver/farm/farm_evaluator.h"
#include "evolver/run/progress.h"
#include "evolver/run/run_end.h"
#include "evolver/store/run_store.h"
#include "modules/core/random.h"
#include "sim/node/envelope_options.h"
#include "sim/node/scenario_options.h"

namespace ev = ahhs::evolver;
using Clock = std::chrono::steady_clock;

namespace {

std::atomic<int> g_interrupts{0};
void OnSignal(int) {
  if (++g_interrupts >= 3) std::_Exit(130);  // the third Ctrl-C does not wait for anything
}

// The command line.
struct Options {
  ahhs::sim::ScenarioOptions task;
  std::string variant = "ahhs2", out_dir, resume_dir, arena = "direct",
              url = ahhs::bus::kDefaultLcmUrl, mutation_profile = "paper";
  int hormones = 5, rules = 30, population = 20, generations = 200, elitism = 1, workers = -1,
      trials = 1, post_eval = 0;
  std::string aggregate = "mean", post_eval_envelope;
  ahhs::sim::EnvelopeOptions envelope;
  double mutation_rate = 0.15, mutation_max_change = 0.1, crossover_rate = 0.05;
  std::uint64_t seed = 1;
  double job_deadline = 300, worker_wait = 60;
  bool overwrite = false, show_config = false;
};

void AddOptions(CLI::App& app, Options* o) {
  ahhs::cli::AddStrictTomlConfig(app, "preset file (TOML, e.g. configs/gait-damped-ahhs2-30.toml)");
  o->task.Add(app, "", "episode length, simulated seconds (0: the task's, 60 s gait / 3000 ticks)");
  app.add_option("--variant", o->variant, "controller: ahhs1 or ahhs2")
      ->check(CLI::IsMember({"ahhs1", "ahhs2"}))
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
      ->check(CLI::IsMember({"paper", "fine-doses"}))
      ->capture_default_str();
  app.add_option("--crossover-rate", o->crossover_rate, "two-point crossover rate")
      ->capture_default_str();
  app.add_option("--trials", o->trials,
                 "episodes per individual and generation, each with a fresh seed (robust "
                 "evolution; the paper: 1)")
      ->check(CLI::Range(1, ev::kMaxTrials))
      ->capture_default_str();
  app.add_option("--aggregate", o->aggregate, "an individual's fitness from its trials")
      ->check(CLI::IsMember({"mean", "median", "min"}))
      ->capture_default_str();
  app.add_option("--post-eval", o->post_eval,
                 "when the run ends, replay its best on N held-out episodes: median, quartiles, "
                 "min and the share that succeeds, also in RUN/post-eval.json")
      ->check(CLI::Range(0, ev::kMaxPostEval))
      ->capture_default_str();
  app.add_option("--post-eval-envelope", o->post_eval_envelope,
                 "envelope of the held-out episodes (default: the run's, or paper for a run "
                 "without one)")
      ->check(CLI::IsMember({"none", "paper", "wide"}));
  o->envelope.Add(app,
                  "envelope of noise every episode is perturbed with: none (the paper), paper or "
                  "wide (docs/scenarios.md)");
  app.add_option("--seed", o->seed, "run seed (every random draw of the run derives from it)")
      ->check(ahhs::modules::SeedTextError)
      ->capture_default_str();
  auto* out_opt =
      app.add_option("--out", o->out_dir, "run directory (default: runs/<time>-<task>)");
  auto* resume_opt =
      app.add_option("--resume", o->resume_dir, "continue the run stored in this directory");
  out_opt->excludes(resume_opt);
  app.add_flag("--overwrite", o->overwrite, "replace an existing run directory given with --out");
  app.add_flag("--show-config", o->show_config,
               "print the run's configuration as JSON and exit (nothing is created or run)");
  app.add_option("--workers", o->workers,
                 "local worker processes to start (default: one per core; 0: only external)")
      ->check(CLI::Range(0, 256));
  app.add_option("--arena-kind", o->arena, "how local workers evaluate: direct, fused or processes")
      ->check(CLI::IsMember({"direct", "fused", "processes"}))
      ->capture_default_str();
  app.add_option("--lcm-url", o->url, "LCM URL of the evaluation farm (ttl=1 to use LAN workers)")
      ->capture_default_str();
  app.add_option("--job-deadline", o->job_deadline, "seconds before an evaluation is re-issued")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--worker-wait", o->worker_wait,
                 "seconds to wait for any worker before giving up (the run stays resumable)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
}

// The run: a new one from the options, or the stored one (--resume). Returns nullptr after
// --show-config printed the configuration. Throws with a message for the user.
std::unique_ptr<ev::RunStore> OpenRun(const CLI::App& app, Options& o, ev::EvolveConfig* config) {
  std::unique_ptr<ev::RunStore> store;
  if (!o.resume_dir.empty()) {
    for (const char* name :
         {"--scenario",         "--joints",         "--modules",       "--duration",
          "--variant",          "--hormones",       "--rules",         "--population",
          "--generations",      "--elitism",        "--mutation-rate", "--mutation-max-change",
          "--mutation-profile", "--crossover-rate", "--seed",          "--overwrite",
          "--trials",           "--aggregate",      "--post-eval",     "--post-eval-envelope"})
      if (app.count(name))
        throw std::invalid_argument(std::string(name) +
                                    " cannot be given with --resume: a resumed run keeps "
                                    "its stored configuration");
    if (o.envelope.given())
      throw std::invalid_argument(
          "--envelope cannot be given with --resume: a resumed run keeps its stored "
          "configuration");
    store = ev::RunStore::Open(o.resume_dir,
                               o.show_config ? ev::StoreAccess::kRead : ev::StoreAccess::kWrite);
    *config = ev::ConfigFromJson(store->config());
    const std::string physics =
        ahhs::sim::PhysicsVersion(config->scenario.kind, config->scenario.joints);
    if (!store->physics().empty() && store->physics() != physics)
      throw std::invalid_argument(o.resume_dir + " was made with the " +
                                  ahhs::sim::ScenarioName(config->scenario.kind) + " physics of " +
                                  store->physics() + ", this build has " + physics +
                                  " (CHANGELOG.md): its fitnesses would mix two physics; start a "
                                  "new run");
    if (store->physics().empty() && !o.show_config)
      std::cerr << "ahhs-evolve: note: " << o.resume_dir
                << " does not record its physics (made before 2026-12-01); resuming with "
                << physics << '\n';
    if (o.show_config) {
      std::cout << ev::ConfigToJson(*config).dump(2) << '\n';
      return nullptr;
    }
    store->Export(true);  // the database is the truth: rebuild files missing, short or wrong
  } else {
    config->scenario = o.task.Config();
    config->scenario.envelope = o.envelope.Resolve();
    config->variant =
        o.variant == "ahhs1" ? ahhs::modules::Variant::kAhhs1 : ahhs::modules::Variant::kAhhs2;
    config->hormones = o.hormones;
    config->rules = o.rules;
    config->ga.population = o.population;
    config->ga.generations = o.generations;
    config->ga.elitism = o.elitism;
    config->ga.mutation.gene_rate = o.mutation_rate;
    config->ga.mutation.max_change = o.mutation_max_change;
    config->ga.mutation.profile = ahhs::modules::ParseMutationProfile(o.mutation_profile);
    config->ga.crossover_rate = o.crossover_rate;
    config->ga.trials = o.trials;
    config->ga.aggregate = ev::ParseAggregate(o.aggregate);
    config->post_eval = o.post_eval;
    config->post_eval_envelope =
        !o.post_eval_envelope.empty()      ? ahhs::sim::EnvelopePreset(o.post_eval_envelope)
        : config->scenario.envelope.none() ? ahhs::sim::EnvelopePreset("paper")
                                           : config->scenario.envelope;
    config->seed = o.seed;
    if (o.task.duration < 0) throw std::invalid_argument("--duration must not be negative");
    const std::string error = ev::CheckEvolveConfig(*config);
    if (!error.empty()) throw std::invalid_argument(error);
    if (o.show_config) {
      std::cout << ev::ConfigToJson(*config).dump(2) << '\n';
      return nullptr;
    }
    if (o.out_dir.empty()) {
      char stamp[32];
      const std::time_t t = std::time(nullptr);
      std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&t));
      o.out_dir = std::string("runs/") + stamp + "-" + o.task.scenario;
    }
    const std::string run_id = ahhs::base::HostName() + "-" + std::to_string(getpid()) + "-" +
                               std::to_string(std::time(nullptr));
    store = ev::RunStore::Create(
        o.out_dir, run_id, config->seed, ev::ConfigToJson(*config),
        ahhs::sim::PhysicsVersion(config->scenario.kind, config->scenario.joints), o.overwrite);
  }
  return store;
}

ev::FarmOptions FarmOptionsFor(const Options& o, const ev::EvolveConfig& config,
                               const std::string& wire_run) {
  ev::FarmOptions farm;
  farm.run = wire_run;
  farm.config = config.scenario;
  farm.population = config.ga.population;
  farm.trials = config.ga.trials;
  farm.lease.job_deadline =
      std::chrono::milliseconds(static_cast<std::int64_t>(o.job_deadline * 1000));
  farm.no_worker_timeout =
      std::chrono::milliseconds(static_cast<std::int64_t>(o.worker_wait * 1000));
  return farm;
}

// A local worker that dies is started again, this many times per session at most.
constexpr int kMaxWorkerRestarts = 20;

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"ahhs-evolve: evolves hormone controllers (the paper's GA) on evaluation workers"};
  Options options;
  AddOptions(app, &options);
  if (const int code = ahhs::cli::Parse(app, argc, argv); code >= 0) return code;

  std::string command_line;
  for (int i = 0; i < argc; ++i) command_line += (i ? " " : "") + std::string(argv[i]);
  ev::EvolveConfig config;
  std::unique_ptr<ev::RunStore> store;
  int session = 0, first = 0;
  try {
    store = OpenRun(app, options, &config);
    if (!store) return 0;  // --show-config
    session = store->BeginSession(command_line);
    first = store->LastGeneration() + 1;
  } catch (const std::exception& e) {
    std::cerr << "ahhs-evolve: " << e.what() << '\n';
    return ahhs::cli::kExitFailure;
  }
  const std::string dir = store->dir();
  const std::string wire_run = store->run_id() + "/s" + std::to_string(session);
  // The last stored generation for a message, when even reading it fails (a full disk).
  const auto stored_up_to = [&]() -> std::string {
    try {
      return std::to_string(store->LastGeneration());
    } catch (const std::exception&) {
      return "?";
    }
  };
  if (first >= config.ga.generations) {
    std::cout << "the run in " << dir << " is already complete (" << config.ga.generations
              << " generations)\n";
  }

  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  // Follow-up commands are printed so that they run as printed (full paths).
  const std::string self = ahhs::base::ExecutableDir() + "/ahhs-evolve";

  // Local workers, started before our own bus exists.
  if (options.workers < 0)
    options.workers = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  ahhs::base::ChildProcesses local;
  int restarts = 0;
  const std::string worker_bin = ahhs::base::ExecutableDir() + "/ahhs-worker";
  for (int k = 0; k < options.workers && first < config.ga.generations; ++k)
    local.Start(
        "local worker " + std::to_string(k),
        {worker_bin, "--quiet", "--lcm-url", options.url, "--arena-kind", options.arena, "--run",
         store->run_id(), "--id",
         ahhs::base::HostName() + ":" + std::to_string(getpid()) + "/w" + std::to_string(k)},
        true);

  ev::Progress progress(first, config.ga.generations);
  std::printf("run directory: %s\n", dir.c_str());
  std::string robust;
  if (config.ga.trials > 1 || !config.scenario.envelope.none())
    robust =
        ", " + std::to_string(config.ga.trials) + " trial" +
        (config.ga.trials > 1 ? std::string("s (") + ev::AggregateName(config.ga.aggregate) + ")"
                              : std::string()) +
        ", envelope " + ahhs::sim::EnvelopeName(config.scenario.envelope);
  std::printf(
      "%s %s, %s %d hormones x %d rules, population %d, "
      "generations %d%s, seed %llu%s\n",
      ahhs::sim::ScenarioName(config.scenario.kind),
      config.scenario.kind == ahhs::sim::ScenarioKind::kGait
          ? (std::string(ahhs::sim::JointsName(config.scenario.joints)) + " docking, " +
             std::to_string(config.scenario.num_modules) + " modules")
                .c_str()
          : "cart and pole",
      ahhs::modules::VariantName(config.variant), config.hormones, config.rules,
      config.ga.population, config.ga.generations, robust.c_str(),
      static_cast<unsigned long long>(config.seed),
      first > 0 ? (", resuming at generation " + std::to_string(first)).c_str() : "");
  std::printf("workers: %d local (%s arena)%s; more: %s/ahhs-worker --lcm-url '%s' --run %s\n",
              static_cast<int>(local.size()), options.arena.c_str(),
              options.workers == 0 ? ", waiting for external ones" : "",
              ahhs::base::ExecutableDir().c_str(), options.url.c_str(), store->run_id().c_str());
  std::fflush(stdout);

  int exit_code = 0;
  try {
    auto bus = ahhs::bus::OpenBusWithFaultInjection(options.url);
    int current_generation = first;
    ev::FarmEvaluator::Hooks hooks;
    hooks.interrupted = [&] { return g_interrupts > 0; };
    hooks.poll = [&] {
      // Keep the local workers alive: one that died is started again.
      for (const auto& ended : local.Reap()) {
        if (g_interrupts > 0) continue;
        if (restarts >= kMaxWorkerRestarts) {
          progress.Say(ended.name + " ended; not restarted (" + std::to_string(restarts) +
                       " restarts already)");
          continue;
        }
        progress.Say(ended.name + " ended (" + ahhs::base::DescribeExit(ended.status) +
                     "); its jobs go to other workers; starting it again");
        ++restarts;
        local.Restart(ended.index);
      }
    };
    hooks.progress = [&](std::size_t done, std::size_t total) {
      progress.Evaluated(current_generation, done, total);
    };
    hooks.report = [&](const std::string& text) { progress.Say(text); };
    ev::FarmEvaluator farm(bus.get(), FarmOptionsFor(options, config, wire_run), hooks);

    ev::EvolutionHooks evolution_hooks;
    evolution_hooks.on_generation = [&](const ev::GenerationRecord& r) {
      progress.Generation(r);
      current_generation = r.generation + 1;
    };
    evolution_hooks.stop = [&] { return g_interrupts > 0; };
    const bool finished = ev::RunEvolution(*store, config, farm, session, evolution_hooks);
    progress.Clear();
    if (!finished) throw ev::FarmInterrupted();
    const auto& c = farm.counters();
    if (c.reissued || c.invalid_results || c.results.dropped || c.statuses.dropped)
      std::printf(
          "farm: %lld jobs re-issued, %lld invalid results, %llu undecodable messages dropped\n",
          static_cast<long long>(c.reissued), static_cast<long long>(c.invalid_results),
          static_cast<unsigned long long>(c.results.dropped + c.statuses.dropped));
  } catch (const ev::FarmInterrupted&) {
    progress.Clear();
    std::printf("interrupted: generations 0-%s are stored in %s\ncontinue with: %s --resume %s\n",
                stored_up_to().c_str(), dir.c_str(), self.c_str(), dir.c_str());
    exit_code = 130;
  } catch (const std::exception& e) {
    progress.Clear();
    std::cerr << "ahhs-evolve: " << e.what() << "\nthe run is stored up to generation "
              << stored_up_to() << "; continue with: " << self << " --resume " << dir << '\n';
    exit_code = ahhs::cli::kExitFailure;
  }
  local.StopAll(std::chrono::seconds(5));
  if (exit_code != 0) return exit_code;

  try {
    ev::PrintRunSummary(*store, config);
    if (config.post_eval > 0) ev::PostEvaluateBest(*store, config);
  } catch (const std::exception& e) {
    std::cerr << "ahhs-evolve: " << e.what() << '\n';
    return ahhs::cli::kExitFailure;
  }
  return 0;
}
