// ahhs-fitness: the fitness monitor as its own process. Follows SIM/STATE (from the sim, a
// tracker, or lcm-logplayer) and publishes FITNESS; prints "fitness: <value>" for every episode
// that ends, and exits after --episodes of them.
#include <atomic>
#include <csignal>
#include <cstdio>
#include <iostream>

#include "base/cli.h"
#include "bus/fault_bus.h"
#include "bus/lcm_bus.h"
#include "bus/wire_version.h"
#include "episode/fitness/fitness_node.h"

namespace cli = ahhs::base::cli;

namespace {
std::atomic<bool> g_stop{false};
void OnSignal(int) { g_stop = true; }
}  // namespace

int main(int argc, char** argv) {
  cli::App app{"ahhs-fitness: the scenario's fitness from the organism's state (SIM/STATE)"};
  std::string url = ahhs::bus::kDefaultLcmUrl, arena = ahhs::bus::kDefaultArena;
  int episodes = 0;
  double timeout = 0;
  app.add_option("--lcm-url", url, "LCM URL")->capture_default_str();
  app.add_option("--arena", arena, "arena name: channel prefix")->capture_default_str();
  app.add_option("--episodes", episodes, "exit after this many episodes (0 = run until killed)")
      ->check(cli::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--timeout", timeout,
                 "give up after this many seconds without a final result (0 = never)")
      ->check(cli::NonNegativeNumber);
  ahhs::base::SetVersion(app, {ahhs::bus::WireVersionLine()});
  if (const int code = ahhs::base::Parse(app, argc, argv); code >= 0) return code;
  try {
    auto bus = ahhs::bus::OpenBusWithFaultInjection(url);
    ahhs::episode::FitnessNode node(bus.get(), arena);
    std::signal(SIGINT, OnSignal);
    std::signal(SIGTERM, OnSignal);
    const auto start = std::chrono::steady_clock::now();
    int done = 0;
    std::int64_t reported = -1;
    while (!g_stop) {
      node.Poll(std::chrono::milliseconds(100));
      const auto& f = node.final_result();
      if (f && f->episode != reported) {
        reported = f->episode;
        if (f->status != ahhs::fitness_t::OK) {
          std::fprintf(stderr, "ahhs-fitness: episode %lld failed: %s\n",
                       static_cast<long long>(f->episode), f->message.c_str());
          return ahhs::base::kExitFailure;
        }
        std::printf("episode %lld: %d states, %d ticks missed%s%s\nfitness: %.17g\n",
                    static_cast<long long>(f->episode), f->states_seen, f->states_missed,
                    f->message.empty() ? "" : "; ", f->message.c_str(), f->fitness);
        std::fflush(stdout);
        if (episodes > 0 && ++done >= episodes) return 0;
      }
      if (timeout > 0 &&
          std::chrono::steady_clock::now() - start > std::chrono::duration<double>(timeout)) {
        std::fprintf(stderr, "ahhs-fitness: no final fitness within %.0f s\n", timeout);
        return ahhs::base::kExitFailure;
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "ahhs-fitness: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
