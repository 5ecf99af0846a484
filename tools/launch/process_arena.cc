#include "tools/launch/process_arena.h"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <stdexcept>
#include <thread>

#include "bus/fault_bus.h"

namespace ahhs::launch {

pid_t SpawnChild(const std::vector<std::string>& argv, bool quiet, const std::string& output_file) {
  int out_fd = -1;
  if (!output_file.empty()) {
    out_fd = open(output_file.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (out_fd < 0) throw std::runtime_error("cannot write " + output_file);
  }
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) {
    if (out_fd >= 0) close(out_fd);
    throw std::runtime_error("fork failed");
  }
  if (pid > 0) {
    if (out_fd >= 0) close(out_fd);
    return pid;
  }
  // The child.
  prctl(PR_SET_PDEATHSIG, SIGTERM);  // never outlive the owner
  if (getppid() != parent) _exit(1);
  std::signal(SIGINT, SIG_IGN);  // Ctrl-C goes to the owner, which stops us in order
  if (out_fd >= 0) {
    dup2(out_fd, STDOUT_FILENO);
    dup2(out_fd, STDERR_FILENO);
  } else if (quiet) {
    FILE* devnull = std::fopen("/dev/null", "w");
    if (devnull) dup2(fileno(devnull), STDOUT_FILENO);
  }
  // The owner's sockets (e.g. its LCM bus) stay with the owner.
  for (int fd = 3; fd < 1024; ++fd) close(fd);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  execv(args[0], args.data());
  std::fprintf(stderr, "cannot run %s\n", args[0]);
  _exit(127);
}

void StopChildren(std::vector<pid_t>* pids, std::chrono::milliseconds grace) {
  for (pid_t pid : *pids)
    if (pid > 0) kill(pid, SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + grace;
  for (pid_t& pid : *pids) {
    while (pid > 0) {
      if (waitpid(pid, nullptr, WNOHANG) != 0) {
        pid = -1;
      } else if (std::chrono::steady_clock::now() > deadline) {
        kill(pid, SIGKILL);
        waitpid(pid, nullptr, 0);
        pid = -1;
      } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
    }
  }
}

ProcessArena::ProcessArena(ProcessArenaOptions options) : options_(std::move(options)) {
  const std::string dir = options_.bin_dir.empty() ? ExecutableDir() : options_.bin_dir;
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
      children_.push_back({options_.logger, SpawnChild(logger_args, quiet)});
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
    // A logger is a passive listener: pace the lockstep so that it keeps up on a busy machine
    // (lcm-logger queues only 30 messages; ahhs-logger's queue is unbounded, but the socket's
    // receive buffer is not).
    if (!options_.log_file.empty()) sim_args.insert(sim_args.end(), {"--min-tick-us", "3000"});
    children_.push_back({"ahhs-sim", SpawnChild(sim_args, quiet)});
    children_.push_back(
        {"ahhs-fitness",
         SpawnChild({dir + "/ahhs-fitness", "--lcm-url", url, "--arena", options_.arena}, quiet)});
    for (int m = 0; m < options_.num_modules; ++m)
      children_.push_back(
          {"ahhs-module " + std::to_string(m),
           SpawnChild({dir + "/ahhs-module", "--id", std::to_string(m), "--lcm-url", url, "--arena",
                       options_.arena, "--hormone-timeout-ms",
                       std::to_string(std::max(1, options_.lockstep_timeout_ms / 4))},
                      quiet)});
    // Our own bus is opened after the children are forked, so that no child inherits its
    // sockets.
    bus_ = bus::MakeBus(url);
  } catch (...) {
    StopAll();
    throw;
  }
}

ProcessArena::~ProcessArena() { StopAll(); }

bool ProcessArena::ChildrenAlive(std::string* why) {
  for (auto& c : children_) {
    if (c.pid <= 0) continue;
    int status = 0;
    if (waitpid(c.pid, &status, WNOHANG) == c.pid) {
      c.pid = -1;
      healthy_ = false;
      *why = c.name + " ended during the episode (" +
             (WIFSIGNALED(status) ? "killed by signal " + std::to_string(WTERMSIG(status))
                                  : "exit status " + std::to_string(WEXITSTATUS(status))) +
             ")";
      return false;
    }
  }
  return true;
}

EpisodeResult ProcessArena::Run(EpisodeSpec spec,
                                const std::function<bool(std::string*)>& keep_going) {
  spec.arena = options_.arena;
  auto alive = [&](std::string* why) { return keep_going(why) && ChildrenAlive(why); };
  EpisodeResult result = RunEpisode(
      *bus_, spec, [&](std::chrono::microseconds w) { bus_->Handle(w); }, alive);
  if (!result.ok && !result.episode_failed) healthy_ = false;
  return result;
}

void ProcessArena::FinishLog() {
  if (options_.log_file.empty() || children_.empty() || children_[0].pid <= 0) return;
  // Let the logger write the last messages, then stop it with SIGINT (it flushes on exit).
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  kill(children_[0].pid, SIGINT);
  for (int k = 0; k < 300; ++k) {
    if (waitpid(children_[0].pid, nullptr, WNOHANG) == children_[0].pid) {
      children_[0].pid = -1;
      return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

void ProcessArena::StopAll() {
  std::vector<pid_t> pids;
  for (const auto& c : children_) pids.push_back(c.pid);
  StopChildren(&pids, std::chrono::seconds(3));
  for (auto& c : children_) c.pid = -1;
}

}  // namespace ahhs::launch
