// ahhs-launch: runs one episode of a genome in an arena made of separate processes (ahhs-sim,
// one ahhs-module per compartment, ahhs-fitness), or with --fused in this process over memq://.
// Prints "fitness: <value>" as its last line. Every child is stopped on success, on error and on
// Ctrl-C; children also die with the launcher (PR_SET_PDEATHSIG).
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <thread>

#include "bus/fault_bus.h"
#include "bus/lcm_bus.h"
#include "modules/core/genome_json.h"
#include "tools/launch/episode_runner.h"

namespace al = ahhs::launch;

namespace {

std::atomic<bool> g_interrupted{false};
void OnSignal(int) { g_interrupted = true; }

struct Child {
  std::string name;
  pid_t pid = -1;
};

pid_t Spawn(const std::vector<std::string>& argv, bool quiet) {
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    prctl(PR_SET_PDEATHSIG, SIGTERM);  // never outlive the launcher
    if (getppid() != parent) _exit(1);
    std::signal(SIGINT, SIG_IGN);  // Ctrl-C goes to the launcher, which stops us in order
    if (quiet) {
      FILE* devnull = std::fopen("/dev/null", "w");
      if (devnull) dup2(fileno(devnull), STDOUT_FILENO);
    }
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    std::fprintf(stderr, "ahhs-launch: cannot run %s\n", args[0]);
    _exit(127);
  }
  return pid;
}

void StopAll(std::vector<Child>& children, int signal = SIGTERM) {
  for (auto& c : children)
    if (c.pid > 0) kill(c.pid, signal);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(3);
  for (auto& c : children) {
    while (c.pid > 0) {
      if (waitpid(c.pid, nullptr, WNOHANG) != 0) {
        c.pid = -1;
      } else if (std::chrono::steady_clock::now() > deadline) {
        kill(c.pid, SIGKILL);
        waitpid(c.pid, nullptr, 0);
        c.pid = -1;
      } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
    }
  }
}

// False (with a message) when a child has ended before the episode did. The children serve
// until stopped, so any exit during the episode is a failure.
bool ChildrenAlive(std::vector<Child>& children, std::string* why) {
  for (auto& c : children) {
    if (c.pid <= 0) continue;
    int status = 0;
    if (waitpid(c.pid, &status, WNOHANG) == c.pid) {
      c.pid = -1;
      *why = c.name + " ended during the episode (" +
             (WIFSIGNALED(status) ? "killed by signal " + std::to_string(WTERMSIG(status))
                                  : "exit status " + std::to_string(WEXITSTATUS(status))) +
             ")";
      return false;
    }
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "ahhs-launch: one episode of a genome in an arena of separate processes (or --fused)"};
  std::string scenario = "gait", joints = "damped", genome_file, url, arena, log_file;
  int modules = 5;
  double duration = 0;
  std::int64_t seed = 1;
  bool fused = false, realtime = false, verbose = false;
  int timeout_s = 3600;
  int lockstep_timeout_ms = 2000;
  app.add_option("--scenario", scenario, "gait or pendulum")->capture_default_str();
  app.add_option("--genome", genome_file, "genome file (docs/genome.md)")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--seed", seed, "episode seed")->capture_default_str();
  app.add_option("--joints", joints, "gait docking: damped or fixed")->capture_default_str();
  app.add_option("--modules", modules, "gait: modules in the chain (>= 2)")->capture_default_str();
  app.add_option("--duration", duration, "episode length, simulated seconds (default: the task's)");
  app.add_flag("--fused", fused, "run every node in this process over memq://");
  app.add_flag("--realtime", realtime,
               "the sim keeps wall-clock pace; modules act on the latest messages");
  app.add_option("--log", log_file, "record the whole episode with lcm-logger into this file");
  app.add_option("--lcm-url", url, "LCM URL for the processes (default: host-only multicast)");
  app.add_option("--arena", arena, "arena name (default: unique per launch)");
  app.add_option("--timeout", timeout_s, "give up after this many seconds")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--lockstep-timeout-ms", lockstep_timeout_ms,
                 "longest wait of the sim for a module's command (modules wait a quarter of it for "
                 "their neighbours' packets, so that after a loss they still answer in time)")
      ->check(CLI::Range(1, 600000))
      ->capture_default_str();
  app.add_flag("-v,--verbose", verbose, "show the children's output");
  CLI11_PARSE(app, argc, argv);

  al::EpisodeSpec spec;
  try {
    spec.config.kind = ahhs::sim::ParseScenarioKind(scenario);
    spec.config.joints = ahhs::sim::ParseJoints(joints);
    spec.config.num_modules = spec.config.kind == ahhs::sim::ScenarioKind::kPendulum ? 2 : modules;
    if (app.count("--duration") && !(duration > 0))
      throw std::invalid_argument("--duration must be positive");
    spec.config.duration = duration;
    const std::string config_error = ahhs::sim::CheckConfig(spec.config);
    if (!config_error.empty()) throw std::invalid_argument(config_error);
    spec.genome = ahhs::modules::LoadGenomeFile(genome_file);
    const std::string fit = al::CheckGenomeFits(spec.genome, spec.config);
    if (!fit.empty()) throw std::invalid_argument(genome_file + ": " + fit);
    if (fused && !log_file.empty())
      throw std::invalid_argument(
          "--log records bus traffic; it needs the process arena, not --fused");
  } catch (const std::exception& e) {
    std::cerr << "ahhs-launch: " << e.what() << '\n';
    return 1;
  }
  spec.seed = seed;
  spec.realtime = realtime;
  spec.episode = static_cast<std::int64_t>(getpid()) * 1000 + 1;
  spec.arena = arena.empty() ? "AHHS" + std::to_string(getpid()) : arena;
  spec.episode_timeout = std::chrono::seconds(timeout_s);
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);

  al::EpisodeResult result;
  if (fused) {
    result = al::RunFused(spec);
  } else {
    if (url.empty()) url = ahhs::bus::kDefaultLcmUrl;
    std::vector<Child> children;
    try {
      const std::string dir = al::ExecutableDir();
      const bool quiet = !verbose;
      if (!log_file.empty()) {
        children.push_back({"lcm-logger", Spawn({"/usr/bin/lcm-logger", "--lcm-url=" + url,
                                                 "--quiet", "--force", log_file},
                                                quiet)});
        for (int k = 0; k < 200; ++k) {  // wait until the logger has opened its file
          struct stat st;
          if (stat(log_file.c_str(), &st) == 0) break;
          std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      }
      std::vector<std::string> sim_args{dir + "/ahhs-sim",
                                        "--lcm-url",
                                        url,
                                        "--arena",
                                        spec.arena,
                                        "--lockstep-timeout-ms",
                                        std::to_string(lockstep_timeout_ms)};
      if (verbose) sim_args.push_back("--verbose");
      // lcm-logger is a passive listener: pace the lockstep so it keeps up on a busy machine.
      if (!log_file.empty()) sim_args.insert(sim_args.end(), {"--min-tick-us", "3000"});
      children.push_back({"ahhs-sim", Spawn(sim_args, quiet)});
      children.push_back(
          {"ahhs-fitness",
           Spawn({dir + "/ahhs-fitness", "--lcm-url", url, "--arena", spec.arena}, quiet)});
      for (int m = 0; m < spec.config.num_modules; ++m)
        children.push_back({"ahhs-module " + std::to_string(m),
                            Spawn({dir + "/ahhs-module", "--id", std::to_string(m), "--lcm-url",
                                   url, "--arena", spec.arena, "--hormone-timeout-ms",
                                   std::to_string(std::max(1, lockstep_timeout_ms / 4))},
                                  quiet)});
      // The launcher's own bus is opened after the children are forked, so that no child
      // inherits its sockets.
      auto bus_ptr = ahhs::bus::MakeBus(url);
      ahhs::bus::Bus& bus = *bus_ptr;
      auto alive = [&](std::string* why) {
        if (g_interrupted) {
          *why = "interrupted";
          return false;
        }
        return ChildrenAlive(children, why);
      };
      result = al::RunEpisode(
          bus, spec, [&](std::chrono::microseconds w) { bus.Handle(w); }, alive);
      if (result.ok && !log_file.empty()) {
        // Let the logger write the last messages, then stop it with SIGINT (it flushes on exit).
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
        kill(children[0].pid, SIGINT);
        for (int k = 0; k < 300 && waitpid(children[0].pid, nullptr, WNOHANG) == 0; ++k)
          std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
    } catch (const std::exception& e) {
      result.ok = false;
      result.error = e.what();
    }
    StopAll(children);
  }
  if (!result.ok) {
    std::cerr << "ahhs-launch: episode failed: " << result.error << '\n';
    return g_interrupted ? 130 : 2;
  }
  std::printf(
      "scenario %s, seed %lld, %s arena%s; ticks without a state at the fitness monitor: %d\n",
      ahhs::sim::ScenarioName(spec.config.kind), static_cast<long long>(seed),
      fused ? "fused" : "process", realtime ? ", real time" : "", result.states_missed);
  std::printf("fitness: %.17g\n", result.fitness);
  return 0;
}
