// ahhs-evolve: the paper's GA over the evaluation farm, stored in a run directory
// (docs/evolution.md). Starts --workers local ahhs-worker processes itself (default: one per
// core) and uses any other worker heard on the bus. Ctrl-C stops cleanly; --resume DIR
// continues a stopped or killed run and ends with exactly the uninterrupted run's results.
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <thread>

#include "base/children.h"
#include "base/cli.h"
#include "base/format.h"
#include "bus/fault_bus.h"
#include "bus/lcm_bus.h"
#include "bus/wire_version.h"
#include "evolver/app/local_workers.h"
#include "evolver/evolve/evolution.h"
#include "evolver/farm/arena_evaluator.h"
#include "evolver/farm/farm_evaluator.h"
#include "evolver/farm/farm_protocol.h"
#include "evolver/run/evolve_options.h"
#include "evolver/run/progress.h"
#include "evolver/run/run_end.h"
#include "evolver/store/run_store.h"
#include "modules/core/genome_json.h"
#include "modules/core/random.h"
#include "sim/core/constants.h"
#include "sim/node/envelope_options.h"
#include "sim/node/scenario_options.h"

namespace cli = ahhs::base::cli;

namespace ev = ahhs::evolver;
using Clock = std::chrono::steady_clock;

namespace {

std::atomic<int> g_interrupts{0};
void OnSignal(int) {
  if (++g_interrupts >= 3) std::_Exit(130);  // the third Ctrl-C does not wait for anything
}

// A local worker that dies is started again, this many times per session at most.
constexpr int kMaxWorkerRestarts = 20;

}  // namespace

int main(int argc, char** argv) {
  cli::App app{"ahhs-evolve: evolves hormone controllers (the paper's GA) on evaluation workers"};
  ev::EvolveOptions options;
  ev::AddEvolveOptions(app, &options);
  ahhs::base::SetVersion(app, {ahhs::bus::WireVersionLine(), ahhs::evolver::FarmVersionLine(),
                               ahhs::evolver::RunStore::FormatVersionLine(),
                               ahhs::sim::PhysicsVersionLine(), ahhs::modules::GenomeFormatLine()});
  if (const int code = ahhs::base::Parse(app, argc, argv); code >= 0) return code;

  std::string command_line;
  for (int i = 0; i < argc; ++i) command_line += (i ? " " : "") + std::string(argv[i]);
  ev::EvolveConfig config;
  std::unique_ptr<ev::RunStore> store;
  int session = 0, first = 0;
  try {
    store = ev::OpenRun(app, options, &config);
    if (!store) return 0;  // --show-config
    session = store->BeginSession(command_line);
    first = store->LastGeneration() + 1;
  } catch (const std::exception& e) {
    std::cerr << "ahhs-evolve: " << e.what() << '\n';
    return ahhs::base::kExitFailure;
  }
  const std::string dir = store->dir();
  const std::string wire_run = store->run_id() + "/s" + std::to_string(session);
  // What an interrupted or failed run has stored, for the line that says how to go on (also
  // when reading it fails: a full disk).
  const auto stored = [&]() -> std::string {
    try {
      const int last = store->LastGeneration();
      if (last < 0) return "no generation is stored yet";
      return last == 0 ? "generation 0 is stored"
                       : "generations 0-" + std::to_string(last) + " are stored";
    } catch (const std::exception&) {
      return "the stored generations could not be read";
    }
  };
  // Evaluations left: generations, or the validation of a finished run.
  const bool to_evaluate =
      first < config.ga.generations || (config.validation > 0 && store->LoadValidation().empty());
  if (first >= config.ga.generations) {
    std::cout << "the run in " << dir << " is already complete (" << config.ga.generations
              << " generations)\n";
  }

  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  // Follow-up commands are printed so that they run as printed (full paths, this session's farm).
  const std::string resume = ahhs::base::ShellWord(ahhs::base::ExecutableDir() + "/ahhs-evolve") +
                             " --resume " + ahhs::base::ShellWord(dir) + ev::FarmArgs(options.farm);

  // Local workers, started before our own bus exists.
  if (options.farm.workers < 0)
    options.farm.workers = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  ahhs::base::ChildProcesses local;
  int restarts = 0;
  if (to_evaluate)
    ev::StartLocalWorkers(&local, options.farm.workers, options.farm.url, options.farm.arena,
                          store->run_id());

  ev::Progress progress(first, config.ga.generations);
  std::printf("run directory: %s\n", dir.c_str());
  std::printf("%s\n", ev::DescribeRun(config, first).c_str());
  std::printf("workers: %d local (%s arena)%s; more: %s --lcm-url %s --run %s\n",
              static_cast<int>(local.size()), options.farm.arena.c_str(),
              options.farm.workers == 0 ? ", waiting for external ones" : "",
              ahhs::base::ShellWord(ahhs::base::ExecutableDir() + "/ahhs-worker").c_str(),
              ahhs::base::ShellWord(options.farm.url).c_str(), store->run_id().c_str());
  std::fflush(stdout);

  int exit_code = 0;
  try {
    auto bus = ahhs::bus::OpenBusWithFaultInjection(options.farm.url);
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
    ahhs::base::CpuStarvation starvation;
    hooks.workers_starved = [&] { return starvation.Starved(); };
    ev::FarmEvaluator farm(bus.get(), ev::FarmOptionsFor(options, config, wire_run), hooks);
    if (to_evaluate) {
      const std::string ready = ev::WaitForFarmWorkers(options.farm, &farm);
      if (!ready.empty()) progress.Say(ready);
    }

    ev::EvolutionHooks evolution_hooks;
    evolution_hooks.on_generation = [&](const ev::GenerationRecord& r) {
      progress.Generation(r);
      current_generation = r.generation + 1;
    };
    evolution_hooks.stop = [&] { return g_interrupts > 0; };
    const bool finished = ev::RunEvolution(*store, config, farm, session, evolution_hooks);
    progress.Clear();
    if (!finished) throw ev::FarmInterrupted();
    if (ev::ValidateRun(*store, config, farm)) progress.Clear();
    const auto& c = farm.counters();
    if (c.reissued || c.invalid_results || c.results.dropped || c.statuses.dropped)
      std::printf(
          "farm: %lld jobs re-issued, %lld invalid results, %llu undecodable messages dropped\n",
          static_cast<long long>(c.reissued), static_cast<long long>(c.invalid_results),
          static_cast<unsigned long long>(c.results.dropped + c.statuses.dropped));
  } catch (const ev::FarmInterrupted&) {
    progress.Clear();
    std::printf("interrupted: %s in %s\ncontinue with: %s\n", stored().c_str(), dir.c_str(),
                resume.c_str());
    exit_code = 130;
  } catch (const std::exception& e) {
    progress.Clear();
    std::cerr << "ahhs-evolve: " << e.what() << '\n'
              << stored() << " in " << dir << "; continue with: " << resume << '\n';
    exit_code = ahhs::base::kExitFailure;
  }
  local.StopAll(std::chrono::seconds(5));
  if (exit_code != 0) return exit_code;

  try {
    ev::PrintRunSummary(*store, config);
    if (config.post_eval > 0) ev::PostEvaluateBest(*store, config);
  } catch (const std::exception& e) {
    std::cerr << "ahhs-evolve: " << e.what() << '\n';
    return ahhs::base::kExitFailure;
  }
  return 0;
}
