// ahhs-evaluate: the ask/tell evaluation service (docs/protocol.md, "Evaluation service"). Reads
// requests as JSON lines on stdin, answers each with one JSON line on stdout, and evaluates
// through the same farm as ahhs-evolve: --workers local workers, and any worker on the bus.
// Ends at the end of its input (exit 0) or on Ctrl-C (exit 130). With --out (or --resume) it
// records every request as one generation of a run directory.
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <thread>

#include "base/children.h"
#include "base/cli.h"
#include "bus/fault_bus.h"
#include "bus/lcm_bus.h"
#include "bus/wire_version.h"
#include "evolver/app/local_workers.h"
#include "evolver/farm/farm_evaluator.h"
#include "evolver/farm/farm_protocol.h"
#include "evolver/serve/eval_service.h"
#include "evolver/serve/service_run.h"
#include "modules/core/genome_vector.h"
#include "modules/core/random.h"
#include "sim/core/constants.h"
#include "sim/node/envelope_options.h"
#include "sim/node/scenario_options.h"

namespace cli = ahhs::base::cli;

namespace ev = ahhs::evolver;

namespace {
std::atomic<int> g_interrupts{0};
void OnSignal(int) {
  if (++g_interrupts >= 3) std::_Exit(130);
}
}  // namespace

int main(int argc, char** argv) {
  cli::App app{
      "ahhs-evaluate: evaluates batches of genomes for any optimizer (JSON lines on "
      "stdin and stdout, docs/protocol.md)"};
  ahhs::sim::ScenarioOptions scenario;
  scenario.Add(app, "", "episode length in simulated seconds (default: the scenario's)");
  ahhs::sim::EnvelopeOptions envelope;
  envelope.Add(app, "envelope of noise of every episode: none, paper or wide (docs/scenarios.md)");
  std::string variant = "ahhs2", aggregate = "mean", url = ahhs::bus::kDefaultLcmUrl,
              arena = "direct";
  ev::ServiceSettings settings;
  settings.shape.hormones = 5;
  settings.shape.rules = 30;
  int workers = -1;
  double job_deadline = 300, worker_wait = 60;
  std::string out_dir, resume_dir, optimizer = "external";
  ev::ServiceRun run;
  bool overwrite = false;
  app.add_option("--variant", variant, "the shape of vector genomes: ahhs1 or ahhs2")
      ->check(cli::IsMember({"ahhs1", "ahhs2"}))
      ->capture_default_str();
  app.add_option("--hormones", settings.shape.hormones, "hormones of vector genomes")
      ->check(cli::Range(1, ahhs::modules::Ranges::kMaxHormones))
      ->capture_default_str();
  app.add_option("--rules", settings.shape.rules, "rules of vector genomes")
      ->check(cli::Range(0, ahhs::modules::Ranges::kMaxRules))
      ->capture_default_str();
  app.add_option("--trials", settings.trials, "episodes per genome, each with its own seed")
      ->check(cli::Range(1, ev::kMaxTrials))
      ->capture_default_str();
  app.add_option("--aggregate", aggregate, "a genome's fitness from its trials: mean, median, min")
      ->check(cli::IsMember({"mean", "median", "min"}))
      ->capture_default_str();
  app.add_option("--seed", settings.seed, "seed of the requests that bring none")
      ->check(ahhs::modules::SeedTextError)
      ->capture_default_str();
  app.add_option("--workers", workers, "local workers (default: one per core; 0: only external)")
      ->check(cli::Range(0, 256));
  app.add_option("--arena-kind", arena, "how local workers evaluate: direct, fused or processes")
      ->check(cli::IsMember({"direct", "fused", "processes"}))
      ->capture_default_str();
  app.add_option("--lcm-url", url, "LCM URL of the farm (ttl=1 to use LAN workers)")
      ->capture_default_str();
  app.add_option("--job-deadline", job_deadline, "seconds before an evaluation is re-issued")
      ->check(cli::PositiveNumber)
      ->capture_default_str();
  app.add_option("--worker-wait", worker_wait, "seconds without any worker before a request fails")
      ->check(cli::PositiveNumber)
      ->capture_default_str();
  app.add_option(
      "--out", out_dir,
      "record the run in this directory: each request one generation (docs/protocol.md)");
  app.add_option("--resume", resume_dir, "go on recording the run in this directory");
  app.add_option("--population", run.population, "--out: genomes per generation (per request)")
      ->check(cli::Range(1, ev::kMaxServiceBatch));
  app.add_option("--generations", run.generations, "--out: generations of the run")
      ->check(cli::Range(1, 10000000));
  app.add_option("--optimizer", optimizer, "--out: the optimizer's name, stored with the run")
      ->capture_default_str();
  app.add_flag("--overwrite", overwrite, "--out: replace a run already in the directory");
  ahhs::base::SetVersion(app, {ahhs::bus::WireVersionLine(), ahhs::evolver::FarmVersionLine(),
                               ahhs::evolver::ServiceVersionLine(), ahhs::sim::PhysicsVersionLine(),
                               ahhs::modules::GenomeVectorLine()});
  if (const int code = ahhs::base::Parse(app, argc, argv); code >= 0) return code;

  ev::FarmOptions farm_options;
  std::unique_ptr<ev::RunStore> store;
  try {
    if (!out_dir.empty() && !resume_dir.empty())
      throw std::invalid_argument("give --out or --resume, not both");
    if (!resume_dir.empty())
      for (const char* name : {"--scenario", "--docking", "--joints", "--modules", "--duration",
                               "--variant", "--hormones", "--rules", "--trials", "--aggregate",
                               "--seed", "--population", "--generations", "--optimizer",
                               "--overwrite", "--pendulum.actuator-gain", "--pendulum.walls"})
        if (app.count(name))
          throw std::invalid_argument(std::string(name) +
                                      " cannot be given with --resume: the run keeps its own");
    if (!resume_dir.empty() && envelope.given())
      throw std::invalid_argument(
          "--envelope cannot be given with --resume: the run keeps its own");
    if (!out_dir.empty() && (run.population == 0 || run.generations == 0))
      throw std::invalid_argument("--out needs --population and --generations");
    if (out_dir.empty() && resume_dir.empty() &&
        (app.count("--population") || app.count("--generations") || app.count("--overwrite")))
      throw std::invalid_argument("--population, --generations and --overwrite go with --out");
    settings.scenario = scenario.Config();
    settings.scenario.envelope = envelope.Resolve();
    const std::string error = ahhs::sim::CheckConfig(settings.scenario);
    if (!error.empty()) throw std::invalid_argument(error);
    auto probe = ahhs::sim::MakeScenario(settings.scenario);
    settings.shape.variant =
        variant == "ahhs1" ? ahhs::modules::Variant::kAhhs1 : ahhs::modules::Variant::kAhhs2;
    settings.shape.sensors = probe->num_sensors();
    settings.shape.actuators = probe->num_actuators();
    settings.aggregate = ev::ParseAggregate(aggregate);
    farm_options.run = ahhs::base::HostName() + "-" + std::to_string(getpid()) + "-evaluate";
    if (!out_dir.empty() || !resume_dir.empty()) {
      ev::EvolveConfig config;
      config.scenario = settings.scenario;
      config.variant = settings.shape.variant;
      config.hormones = settings.shape.hormones;
      config.rules = settings.shape.rules;
      config.ga.population = run.population;
      config.ga.generations = run.generations;
      config.ga.trials = settings.trials;
      config.ga.aggregate = settings.aggregate;
      config.seed = settings.seed;
      config.optimizer = optimizer;
      store = ev::OpenServiceRun(resume_dir.empty() ? out_dir : resume_dir, !resume_dir.empty(),
                                 overwrite, farm_options.run, &config);
      settings.scenario = config.scenario;
      settings.shape = config.shape();
      settings.trials = config.ga.trials;
      settings.aggregate = config.ga.aggregate;
      settings.seed = config.seed;
      run.store = store.get();
      run.optimizer = config.optimizer;
      run.population = config.ga.population;
      run.generations = config.ga.generations;
      std::string command_line;
      for (int a = 0; a < argc; ++a) command_line += (a ? " " : "") + std::string(argv[a]);
      run.session = store->BeginSession(command_line);
      run.seconds = [] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
            .count();
      };
    }
    farm_options.config = settings.scenario;  // (a resumed run's own)
    farm_options.population = ev::kMaxServiceBatch;
    farm_options.trials = settings.trials;
    farm_options.lease.job_deadline =
        std::chrono::milliseconds(static_cast<std::int64_t>(job_deadline * 1000));
    farm_options.no_worker_timeout =
        std::chrono::milliseconds(static_cast<std::int64_t>(worker_wait * 1000));
  } catch (const std::exception& e) {
    std::cerr << "ahhs-evaluate: " << e.what() << '\n';
    return ahhs::base::kExitUsage;
  }

  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  if (workers < 0) workers = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  ahhs::base::ChildProcesses local;
  int exit_code = ahhs::base::kExitOk;
  try {
    ev::StartLocalWorkers(&local, workers, url, arena, farm_options.run);
    auto bus = ahhs::bus::OpenBusWithFaultInjection(url);
    ev::FarmEvaluator::Hooks hooks;
    hooks.interrupted = [] { return g_interrupts > 0; };
    hooks.report = [](const std::string& text) { std::cerr << "ahhs-evaluate: " << text << '\n'; };
    ev::FarmEvaluator farm(bus.get(), farm_options, hooks);
    ev::EvalService service(settings, farm, run.store ? &run : nullptr);
    std::cout << service.Hello().dump() << std::endl;
    std::string line;
    while (g_interrupts == 0 && std::getline(std::cin, line)) {
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      std::cout << service.Handle(line).dump() << std::endl;
    }
    if (g_interrupts > 0) exit_code = ahhs::base::kExitInterrupted;
  } catch (const std::exception& e) {
    std::cerr << "ahhs-evaluate: " << e.what() << '\n';
    exit_code = ahhs::base::kExitFailure;
  }
  local.StopAll(std::chrono::seconds(5));
  return exit_code;
}
