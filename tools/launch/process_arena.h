// An arena of separate processes: ahhs-sim, ahhs-fitness and one ahhs-module per compartment,
// started once and serving episode after episode on one bus (docs/protocol.md). Used by
// ahhs-launch for one episode and by ahhs-worker --arena processes for many. Children die with
// this process (PR_SET_PDEATHSIG) and are stopped (SIGTERM, then SIGKILL) by the destructor.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bus/bus.h"
#include "tools/launch/episode_runner.h"

namespace ahhs::launch {

struct ProcessArenaOptions {
  std::string url;      // LCM URL of the arena's traffic
  std::string arena;    // channel prefix, unique on the bus
  int num_modules = 5;  // module processes (2 for the pendulum)
  int lockstep_timeout_ms = 2000;
  bool verbose = false;  // show the children's output
  std::string log_file;  // when set, `logger` records everything into it
  // "ahhs-logger" (ours, next to this program; keeps every message) or "lcm-logger" (Debian's
  // /usr/bin/lcm-logger, whose 30-message queue can lose lockstep bursts).
  std::string logger = "ahhs-logger";
  std::string bin_dir;  // where ahhs-sim and the others are (default: next to this program)
};

// Starts `argv` (argv[0] a path) as a child that dies with this process and ignores Ctrl-C (its
// owner stops it in order). With `quiet` its stdout goes to /dev/null; with an `output_file` its
// stdout and stderr are appended to that file. No descriptor beyond stdin/stdout/stderr is
// inherited. Throws std::runtime_error when fork fails or the output file cannot be opened.
pid_t SpawnChild(const std::vector<std::string>& argv, bool quiet,
                 const std::string& output_file = "");

// Sends SIGTERM to every child (pid > 0), waits up to `grace`, then SIGKILLs the rest. Sets
// every pid to -1.
void StopChildren(std::vector<pid_t>* pids, std::chrono::milliseconds grace);

class ProcessArena {
 public:
  // Starts the children. Throws std::runtime_error when a program cannot be started.
  explicit ProcessArena(ProcessArenaOptions options);
  ~ProcessArena();
  ProcessArena(const ProcessArena&) = delete;
  ProcessArena& operator=(const ProcessArena&) = delete;

  // Runs one episode (spec.arena is set to the arena's name). `keep_going(why)` is asked every
  // loop besides the children's health; returning false aborts with its message.
  EpisodeResult Run(EpisodeSpec spec, const std::function<bool(std::string*)>& keep_going);

  // Stops the logger gently so that it writes what it has and closes its file (call after the
  // last episode).
  void FinishLog();

  const ProcessArenaOptions& options() const { return options_; }
  bool healthy() const { return healthy_; }

 private:
  struct Child {
    std::string name;
    pid_t pid = -1;
  };
  bool ChildrenAlive(std::string* why);
  void StopAll();

  ProcessArenaOptions options_;
  std::vector<Child> children_;
  std::unique_ptr<bus::Bus> bus_;
  bool healthy_ = true;
};

}  // namespace ahhs::launch
