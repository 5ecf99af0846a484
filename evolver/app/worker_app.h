// ahhs-worker's command line and its two ways of running: a supervisor of one worker process
// per slot, or one worker serving farm jobs (docs/evolution.md, docs/protocol.md).
#pragma once

#include <atomic>
#include <string>

#include "base/cli.h"

namespace ahhs::evolver {

struct WorkerOptions {
  std::string url, arena = "direct", id, arena_url, run, external, arena_name;
  int slots = 1, external_timeout_s = 60;
  bool verbose = false, quiet = false, any_run = false, realtime = false;
  bool arena_url_given = false;
};

// Declares every option on `app` (`o` holds the defaults).
void AddWorkerOptions(base::cli::App& app, WorkerOptions* o);

// After parsing: "" (and --arena-url defaulted to a port of this process's own), or the usage
// error to print.
std::string CheckWorkerOptions(const base::cli::App& app, WorkerOptions* o);

// --slots N > 1: starts N worker processes and supervises them until `stop`.
int SuperviseSlots(const WorkerOptions& o, const std::atomic<bool>& stop);

// One worker: serves farm jobs until `stop`. AHHS_WORKER_FAULT=nan (tests) makes every result a
// NaN fitness. Returns the exit code.
int ServeJobs(WorkerOptions o, const std::atomic<bool>& stop);

}  // namespace ahhs::evolver
