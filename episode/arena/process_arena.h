// An arena of separate processes: ahhs-sim, ahhs-fitness and one ahhs-module per compartment,
// started once and serving episode after episode on one bus (docs/protocol.md), except the
// roles named external, which others play (docs/hardware.md). Used by
// ahhs-launch for one episode and by ahhs-worker --arena-kind processes for many. Children die with
// this process (PR_SET_PDEATHSIG) and are stopped (SIGTERM, then SIGKILL) by the destructor.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "base/children.h"
#include "bus/bus.h"
#include "episode/arena/episode.h"
#include "episode/arena/external_roles.h"

namespace ahhs::episode {

struct ProcessArenaOptions {
  std::string url;      // LCM URL of the arena's traffic
  std::string arena;    // channel prefix, unique on the bus
  int num_modules = 5;  // module processes (2 for the pendulum)
  // 0 (the default): exact lockstep. The sim waits for every command and each module for every
  // hormone packet, and a lockstep episode whose fitness monitor missed a state fails; an
  // episode without progress for `stall_timeout` (a lost datagram) fails. The result is then
  // the fused arena's to the bit, or an error: never a result changed by a loss or a stall.
  // Above 0: the sim goes on after this long without a module's command, modules after a
  // quarter of it without a neighbour's packet (docs/protocol.md), and the result can differ.
  int lockstep_timeout_ms = 0;
  std::chrono::seconds stall_timeout{10};
  bool verbose = false;  // show the children's output
  std::string log_file;  // when set, `logger` records everything into it
  // "ahhs-logger" (ours, next to this program; keeps every message) or "lcm-logger" (Debian's
  // /usr/bin/lcm-logger, whose 30-message queue can lose lockstep bursts).
  std::string logger = "ahhs-logger";
  std::string bin_dir;  // where ahhs-sim and the others are (default: next to this program)
  // Roles not started here: every episode waits up to `external_timeout` for them.
  ExternalRoles external;
  std::chrono::seconds external_timeout{60};
  // ahhs-sim --hardware-modules: modules whose bodies are hardware ("" = none).
  std::string hardware_modules;
};

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
  bool ChildrenAlive(std::string* why);

  ProcessArenaOptions options_;
  base::ChildProcesses children_;  // the logger (when logging) first
  std::unique_ptr<bus::Bus> bus_;
  bool healthy_ = true;
};

}  // namespace ahhs::episode
