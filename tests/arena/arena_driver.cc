// Plays the launcher for separate ahhs-sim and ahhs-module processes: RESET + GENOME until every
// module reports READY, START, wait for the end; then prints the in-process reference fitness
// of the same genome and seed ("fitness X"), which tests/arena/multiprocess_arena.sh compares
// with the fitness the sim process reports.
//   arena_driver --lcm-url URL --scenario S --modules N --duration D --seed S --variant ahhs1|ahhs2
#include <CLI/CLI.hpp>
#include <ahhs/module_status_t.hpp>
#include <ahhs/sim_clock_t.hpp>
#include <ahhs/sim_control_t.hpp>
#include <chrono>
#include <cstdio>
#include <set>

#include "bus/channels.h"
#include "bus/lcm_bus.h"
#include "bus/typed.h"
#include "modules/core/variation.h"
#include "modules/node/genome_codec.h"
#include "tests/arena/direct_loop.h"

using namespace ahhs;
using Clock = std::chrono::steady_clock;

int main(int argc, char** argv) {
  CLI::App app{"launcher stand-in for the multi-process arena test"};
  std::string url, variant = "ahhs2";
  testing::Episode e{"pendulum", 2, 10.0, 1};
  app.add_option("--lcm-url", url)->required();
  app.add_option("--scenario", e.scenario);
  app.add_option("--modules", e.modules);
  app.add_option("--duration", e.duration);
  app.add_option("--seed", e.seed);
  app.add_option("--variant", variant);
  CLI11_PARSE(app, argc, argv);

  auto probe = sim::MakeScenario(testing::ConfigOf(e));
  const int modules = probe->num_compartments();
  modules::Rng rng(static_cast<std::uint64_t>(e.seed));
  const auto genome = modules::RandomGenome(
      {variant == "ahhs1" ? modules::Variant::kAhhs1 : modules::Variant::kAhhs2, 5,
       variant == "ahhs1" ? 40 : 15, probe->num_sensors(), probe->num_actuators()},
      rng);
  bus::LcmBus bus(url);
  bus::ArenaChannels ch;
  const std::int64_t episode = 777;
  std::set<int> ready;
  std::int8_t run_state = -1;
  bus::SubscribeTyped<module_status_t>(
      bus, ch.AnyStatus(), [&](const std::string&, const module_status_t& s) {
        if (s.episode == episode && s.state == module_status_t::READY) ready.insert(s.module);
      });
  bus::SubscribeTyped<sim_clock_t>(bus, ch.SimClock(),
                                   [&](const std::string&, const sim_clock_t& c) {
                                     if (c.episode == episode) run_state = c.run_state;
                                   });
  sim_control_t c{};
  c.episode = episode;
  c.seed = e.seed;
  c.scenario = e.scenario;
  c.num_modules = e.modules;
  c.duration = e.duration;
  const auto give_up = Clock::now() + std::chrono::seconds(15);
  while ((static_cast<int>(ready.size()) < modules || run_state != sim_clock_t::RESET) &&
         Clock::now() < give_up) {
    c.command = sim_control_t::RESET;
    bus::PublishTyped(bus, ch.SimControl(), c);
    bus::PublishTyped(bus, ch.Genome(), modules::GenomeMessage(genome, episode));
    bus.Handle(std::chrono::milliseconds(200));
  }
  if (static_cast<int>(ready.size()) < modules) {
    std::fprintf(stderr, "arena_driver: only %zu of %d modules reported READY\n", ready.size(),
                 modules);
    return 1;
  }
  c.command = sim_control_t::START;
  bus::PublishTyped(bus, ch.SimControl(), c);
  const auto deadline = Clock::now() + std::chrono::seconds(120);
  while (run_state != sim_clock_t::FINISHED && run_state != sim_clock_t::FAILED &&
         Clock::now() < deadline)
    bus.Handle(std::chrono::milliseconds(100));
  if (run_state != sim_clock_t::FINISHED) {
    std::fprintf(stderr, "arena_driver: the episode did not finish\n");
    return 1;
  }
  std::printf("fitness %.17g\n", testing::DirectFitness(e, genome));
  return 0;
}
