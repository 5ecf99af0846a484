// Plays the launcher (episode::RunEpisode) for separately started ahhs-sim, ahhs-module and
// ahhs-fitness processes; prints the monitor's fitness ("monitor fitness X") and, in lockstep,
// the in-process reference fitness of the same genome and seed ("fitness X"), which
// tests/episode/multiprocess_arena.sh compares with what the sim process reports.
//   arena_driver --lcm-url URL --scenario S --modules N --duration D --seed S --variant ahhs1|ahhs2
#include <ahhs/module_status_t.hpp>
#include <ahhs/sim_clock_t.hpp>
#include <ahhs/sim_control_t.hpp>
#include <chrono>
#include <cstdio>
#include <set>

#include "base/cli.h"
#include "bus/channels.h"
#include "bus/fault_bus.h"
#include "bus/lcm_bus.h"
#include "bus/typed.h"
#include "episode/arena/episode.h"
#include "episode/arena/launcher_role.h"
#include "modules/core/variation.h"
#include "modules/node/genome_codec.h"
#include "tests/episode/direct_loop.h"

namespace cli = ahhs::base::cli;

using namespace ahhs;
using Clock = std::chrono::steady_clock;

int main(int argc, char** argv) {
  cli::App app{"launcher stand-in for the multi-process arena test"};
  std::string url, variant = "ahhs2";
  testing::Episode e{"pendulum", 2, 10.0, 1};
  app.add_option("--lcm-url", url)->required();
  app.add_option("--scenario", e.scenario);
  app.add_option("--modules", e.modules);
  app.add_option("--duration", e.duration);
  app.add_option("--seed", e.seed);
  app.add_option("--variant", variant);
  bool realtime = false;
  app.add_flag("--realtime", realtime);
  std::string arena = "AHHS";
  app.add_option("--arena", arena);
  if (const int code = ahhs::base::Parse(app, argc, argv); code >= 0) return code;

  auto probe = sim::MakeScenario(testing::ConfigOf(e));
  modules::Rng rng(static_cast<std::uint64_t>(e.seed));
  const auto genome = modules::RandomGenome(
      {variant == "ahhs1" ? modules::Variant::kAhhs1 : modules::Variant::kAhhs2, 5,
       variant == "ahhs1" ? 40 : 15, probe->num_sensors(), probe->num_actuators()},
      rng);
  auto bus_ptr = bus::OpenBusWithFaultInjection(url);  // honours AHHS_FAULT_DROP like every process
  bus::Bus& bus = *bus_ptr;
  episode::EpisodeSpec spec;
  spec.config = testing::ConfigOf(e);
  spec.genome = genome;
  spec.seed = e.seed;
  spec.episode = 777;
  spec.realtime = realtime;
  spec.arena = arena;
  const auto result = episode::RunEpisode(
      bus, spec, [&](std::chrono::microseconds w) { bus.Handle(w); },
      [](std::string*) { return true; });
  if (!result.ok) {
    std::fprintf(stderr, "arena_driver: %s\n", result.error.c_str());
    return 1;
  }
  std::printf("monitor fitness %.17g\n", result.fitness);
  if (realtime) return 0;  // real time has no reference run: the physics sees wall-clock timing
  std::printf("fitness %.17g\n", testing::DirectFitness(e, genome));
  return 0;
}
