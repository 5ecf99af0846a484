// ahhs-evaluate: the ask/tell evaluation service (docs/protocol.md, "Evaluation service"). Reads
// requests as JSON lines on stdin, answers each with one JSON line on stdout, and evaluates
// through the same farm as ahhs-evolve: --workers local workers, and any worker on the bus.
// Ends at the end of its input (exit 0) or on Ctrl-C (exit 130). With --out (or --resume) it
// records every request as one generation of a run directory.
#include <atomic>
#include <csignal>
#include <iostream>
#include <thread>

#include "base/children.h"
#include "base/cli.h"
#include "bus/fault_bus.h"
#include "bus/wire_version.h"
#include "evolver/app/evaluate_app.h"
#include "evolver/app/local_workers.h"
#include "evolver/farm/farm_protocol.h"
#include "modules/core/genome_vector.h"
#include "sim/core/constants.h"

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
  ev::EvaluateOptions options;
  ev::AddEvaluateOptions(app, &options);
  ahhs::base::SetVersion(app, {ahhs::bus::WireVersionLine(), ahhs::evolver::FarmVersionLine(),
                               ahhs::evolver::ServiceVersionLine(), ahhs::sim::PhysicsVersionLine(),
                               ahhs::modules::GenomeVectorLine()});
  if (const int code = ahhs::base::Parse(app, argc, argv); code >= 0) return code;

  std::string command_line;
  for (int a = 0; a < argc; ++a) command_line += (a ? " " : "") + std::string(argv[a]);
  ev::EvaluateSetup setup;
  try {
    setup = ev::SetUpEvaluate(app, options, command_line);
  } catch (const std::exception& e) {
    std::cerr << "ahhs-evaluate: " << e.what() << '\n';
    return ahhs::base::kExitUsage;
  }

  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  int workers = options.farm.workers;
  if (workers < 0) workers = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  ahhs::base::ChildProcesses local;
  int exit_code = ahhs::base::kExitOk;
  try {
    ev::StartLocalWorkers(&local, workers, options.farm.url, options.farm.arena, setup.farm.run);
    auto bus = ahhs::bus::OpenBusWithFaultInjection(options.farm.url);
    ev::FarmEvaluator::Hooks hooks;
    hooks.interrupted = [] { return g_interrupts > 0; };
    hooks.report = [](const std::string& text) { std::cerr << "ahhs-evaluate: " << text << '\n'; };
    ahhs::base::CpuStarvation starvation;
    hooks.workers_starved = [&] { return starvation.Starved(); };
    ev::FarmEvaluator farm(bus.get(), setup.farm, hooks);
    const std::string ready = ev::WaitForFarmWorkers(options.farm, &farm);
    if (!ready.empty()) std::cerr << "ahhs-evaluate: " << ready << '\n';
    ev::EvalService service(setup.settings, farm, setup.store ? &setup.run : nullptr);
    std::cout << service.Hello().dump() << std::endl;
    std::string line;
    while (g_interrupts == 0 && std::getline(std::cin, line)) {
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      std::cout << service.Handle(line).dump() << std::endl;
    }
    // The end of the input: a recorded run whose last generation is in is validated and
    // post-evaluated now (stderr: stdout is the protocol's).
    if (g_interrupts > 0)
      exit_code = ahhs::base::kExitInterrupted;
    else
      ev::FinishRun(setup, farm, stderr);
  } catch (const ev::FarmInterrupted&) {
    exit_code = ahhs::base::kExitInterrupted;
  } catch (const std::exception& e) {
    std::cerr << "ahhs-evaluate: " << e.what() << '\n';
    exit_code = ahhs::base::kExitFailure;
  }
  local.StopAll(std::chrono::seconds(5));
  return exit_code;
}
