#include "episode/arena/process_arena.h"

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <stdexcept>
#include <thread>

#include "bus/fault_bus.h"
#include "episode/arena/launcher_role.h"

namespace ahhs::episode {

namespace {
// The modules' --hormone-timeout-ms for a sim's lockstep timeout: a quarter of it, 0 for 0.
int HormoneTimeoutMs(int lockstep_timeout_ms) {
  return lockstep_timeout_ms == 0 ? 0 : std::max(1, lockstep_timeout_ms / 4);
}
}  // namespace

ProcessArena::ProcessArena(ProcessArenaOptions options) : options_(std::move(options)) {
  const std::string dir = options_.bin_dir.empty() ? base::ExecutableDir() : options_.bin_dir;
  const std::string& url = options_.url;
  const bool quiet = !options_.verbose;
  try {
    if (!options_.log_file.empty()) {
      std::vector<std::string> logger_args;
      if (options_.logger == "ahhs-logger")
        logger_args = {dir + "/ahhs-logger", "--lcm-url", url, "--force", options_.log_file};
      else if (options_.logger == "lcm-logger")
        logger_args = {"/usr/bin/lcm-logger", "--lcm-url=" + url, "--quiet", "--force",
                       options_.log_file};
      else
        throw std::runtime_error("unknown logger '" + options_.logger +
                                 "' (ahhs-logger or lcm-logger)");
      children_.Start(options_.logger, logger_args, quiet);
      // Both loggers create the file once they are subscribed.
      for (int k = 0; k < 200; ++k) {
        struct stat st;
        if (stat(options_.log_file.c_str(), &st) == 0) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    std::vector<std::string> sim_args{dir + "/ahhs-sim",
                                      "--lcm-url",
                                      url,
                                      "--arena",
                                      options_.arena,
                                      "--lockstep-timeout-ms",
                                      std::to_string(options_.lockstep_timeout_ms)};
    if (options_.verbose) sim_args.push_back("--verbose");
    if (!options_.hardware_modules.empty())
      sim_args.insert(sim_args.end(), {"--hardware-modules", options_.hardware_modules});
    // A logger is a passive listener: pace the lockstep so that it keeps up on a busy machine
    // (lcm-logger queues only 30 messages; ahhs-logger's queue is unbounded, but the socket's
    // receive buffer is not).
    if (!options_.log_file.empty()) sim_args.insert(sim_args.end(), {"--min-tick-us", "3000"});
    const ExternalRoles& external = options_.external;
    if (!external.sim) children_.Start("ahhs-sim", sim_args, quiet);
    if (!external.fitness)
      children_.Start("ahhs-fitness",
                      {dir + "/ahhs-fitness", "--lcm-url", url, "--arena", options_.arena}, quiet);
    for (int m = 0; m < options_.num_modules; ++m)
      if (!external.has_module(m))
        children_.Start("ahhs-module " + std::to_string(m),
                        {dir + "/ahhs-module", "--id", std::to_string(m), "--lcm-url", url,
                         "--arena", options_.arena, "--hormone-timeout-ms",
                         std::to_string(HormoneTimeoutMs(options_.lockstep_timeout_ms))},
                        quiet);
    // Our own bus is opened after the children are forked, so that no child inherits its
    // sockets.
    bus_ = bus::OpenBusWithFaultInjection(url);
  } catch (...) {
    children_.StopAll(std::chrono::seconds(3));
    throw;
  }
}

ProcessArena::~ProcessArena() = default;

bool ProcessArena::ChildrenAlive(std::string* why) {
  const auto ended = children_.Reap();
  if (ended.empty()) return true;
  healthy_ = false;
  *why = ended.front().name + " ended during the episode (" +
         base::DescribeExit(ended.front().status) + ")";
  return false;
}

EpisodeResult ProcessArena::Run(EpisodeSpec spec,
                                const std::function<bool(std::string*)>& keep_going) {
  spec.arena = options_.arena;
  spec.external = options_.external;
  spec.external_timeout = options_.external_timeout;
  const bool exact = options_.lockstep_timeout_ms == 0 && !spec.realtime;
  if (exact) spec.stall_timeout = options_.stall_timeout;
  auto alive = [&](std::string* why) { return keep_going(why) && ChildrenAlive(why); };
  EpisodeResult result = RunEpisode(
      *bus_, spec, [&](std::chrono::microseconds w) { bus_->Handle(w); }, alive);
  if (exact && result.ok && result.states_missed > 0) {
    result.ok = false;
    result.error = "the fitness monitor missed " + std::to_string(result.states_missed) +
                   " of the episode's states (lost datagrams): its fitness would not be exact";
  }
  if (!result.ok && !result.episode_failed) healthy_ = false;
  return result;
}

void ProcessArena::FinishLog() {
  if (options_.log_file.empty() || children_.size() == 0 || !children_.alive(0)) return;
  // Let the logger write the last messages, then stop it with SIGINT (it flushes on exit).
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  children_.Signal(0, SIGINT);
  for (int k = 0; k < 300 && children_.alive(0); ++k) {
    children_.Reap();
    if (children_.alive(0)) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

}  // namespace ahhs::episode
