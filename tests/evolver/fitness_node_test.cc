// The fitness monitor's node: an episode that saw no valid state fails loudly; it never scores 0.
#include "evolver/fitness/fitness_node.h"

#include <ahhs/fitness_t.hpp>
#include <ahhs/sim_clock_t.hpp>
#include <ahhs/sim_control_t.hpp>
#include <catch2/catch.hpp>

#include "bus/channels.h"
#include "bus/lcm_bus.h"
#include "bus/typed.h"
#include "sim/node/sim_codec.h"

using namespace ahhs;

TEST_CASE("an episode whose monitor received no valid state ends in an error, not fitness 0") {
  bus::LcmBus bus("memq://");
  evolver::FitnessNode node(&bus, "T");
  const bus::ArenaChannels ch("T");
  std::vector<fitness_t> heard;
  auto sub = bus::SubscribeTyped<fitness_t>(
      bus, ch.Fitness(), [&](const std::string&, const fitness_t& f) { heard.push_back(f); });
  sim_control_t reset{};
  reset.command = sim_control_t::RESET;
  reset.episode = 7;
  sim::ScenarioToWire(
      sim::MakeScenarioConfig(sim::ScenarioKind::kPendulum, sim::Joints::kDamped, 2, 1.0), &reset);
  bus::PublishTyped(bus, ch.SimControl(), reset);
  node.Poll(std::chrono::milliseconds(10));
  // States of another episode (a tracker that does not copy the episode) are not valid.
  sim_clock_t clock{};
  clock.episode = 7;
  clock.tick = 50;
  clock.run_state = sim_clock_t::FINISHED;
  bus::PublishTyped(bus, ch.SimClock(), clock);
  node.Poll(std::chrono::milliseconds(10));
  bus.Handle(std::chrono::milliseconds(0));
  REQUIRE_FALSE(heard.empty());
  const fitness_t& last = heard.back();
  CHECK(last.is_final);
  CHECK(last.status == fitness_t::ERROR);
  CHECK(last.states_seen == 0);
  CHECK_THAT(last.message, Catch::Contains("no valid SIM/STATE arrived for episode 7"));
}
