// ahhs-worker: serves evaluation jobs of any ahhs-evolve on the bus (docs/evolution.md,
// docs/protocol.md "Evaluation farm"). One evaluation at a time per process; --slots N starts N
// worker processes on this host. Runs until SIGTERM or Ctrl-C. Options and the two ways of
// running: evolver/app/worker_app.h.
//
// Fault injection for tests (docs/development.md): AHHS_WORKER_FAULT=nan makes every result a
// NaN fitness.
#include <atomic>
#include <csignal>
#include <iostream>

#include "base/cli.h"
#include "bus/lcm_bus.h"
#include "bus/wire_version.h"
#include "evolver/app/worker_app.h"
#include "evolver/farm/farm_protocol.h"
#include "sim/core/constants.h"

namespace cli = ahhs::base::cli;

namespace {

std::atomic<bool> g_stop{false};
void OnSignal(int) { g_stop = true; }

}  // namespace

int main(int argc, char** argv) {
  cli::App app{"ahhs-worker: evaluates genomes for ahhs-evolve runs on this bus"};
  ahhs::evolver::WorkerOptions o;
  o.url = o.arena_url = ahhs::bus::kDefaultLcmUrl;
  ahhs::evolver::AddWorkerOptions(app, &o);
  ahhs::base::SetVersion(app, {ahhs::bus::WireVersionLine(), ahhs::evolver::FarmVersionLine(),
                               ahhs::sim::PhysicsVersionLine()});
  if (const int code = ahhs::base::Parse(app, argc, argv); code >= 0) return code;
  if (const std::string error = ahhs::evolver::CheckWorkerOptions(app, &o); !error.empty()) {
    std::cerr << "ahhs-worker: " << error << '\n';
    return ahhs::base::kExitUsage;
  }
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  return o.slots > 1 ? ahhs::evolver::SuperviseSlots(o, g_stop)
                     : ahhs::evolver::ServeJobs(o, g_stop);
}
