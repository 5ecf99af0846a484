// The fitness monitor's node: an episode that saw no valid state fails loudly; it never scores 0.
#include "episode/fitness/fitness_node.h"

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
  episode::FitnessNode node(&bus, "T");
  const bus::ArenaChannels ch("T");
  std::vector<fitness_t> heard;
  auto sub = bus::SubscribeTyped<fitness_t>(
      bus, ch.Fitness(), [&](const std::string&, const fitness_t& f) { heard.push_back(f); });
  sim_control_t reset{};
  reset.command = sim_control_t::RESET;
  reset.episode = 7;
  sim::ScenarioToWire(
      sim::MakeScenarioConfig(sim::ScenarioKind::kPendulum, sim::DockingKind::kDamped, 2, 1.0),
      &reset);
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

namespace {

// A gait episode of `ticks` ticks on arena T, and what the monitor says on FITNESS.
struct GaitEpisode {
  bus::LcmBus bus{"memq://"};
  const bus::ArenaChannels ch{"T"};
  std::vector<fitness_t> heard;
  bus::Subscription sub;
  double period = 0;
  explicit GaitEpisode(std::int64_t episode) {
    sub = bus::SubscribeTyped<fitness_t>(
        bus, ch.Fitness(), [&](const std::string&, const fitness_t& f) { heard.push_back(f); });
    sim_control_t reset{};
    reset.command = sim_control_t::RESET;
    reset.episode = episode;
    const auto config =
        sim::MakeScenarioConfig(sim::ScenarioKind::kGait, sim::DockingKind::kFixed, 3,
                                0.5);  // 10 ticks
    period = sim::ShapeOf(config).control_period;
    sim::ScenarioToWire(config, &reset);
    bus::PublishTyped(bus, ch.SimControl(), reset);
  }
  // A tracker's state of tick k: every module's body 1 cm further along x per tick.
  void State(std::int64_t episode, std::int64_t k) {
    sim_state_t s{};
    s.episode = episode;
    s.tick = k;
    s.sim_time = static_cast<double>(k) * period;
    s.num_bodies = 3;
    for (int b = 0; b < 3; ++b) {
      s.module.push_back(b);
      s.shape.push_back(sim_state_t::SHAPE_BOX);
      s.px.push_back(0.01 * static_cast<double>(k) + 0.1 * b);
      s.py.push_back(0);
      s.pz.push_back(0.05);
      s.qw.push_back(1);
      s.qx.push_back(0);
      s.qy.push_back(0);
      s.qz.push_back(0);
      s.sx.push_back(0.1);
      s.sy.push_back(0.1);
      s.sz.push_back(0.1);
      s.mass.push_back(0.2);
    }
    bus::PublishTyped(bus, ch.SimState(), s);
  }
  void Clock(std::int64_t episode, std::int64_t k, std::int8_t state) {
    sim_clock_t c{};
    c.episode = episode;
    c.tick = k;
    c.sim_time = static_cast<double>(k) * period;
    c.run_state = state;
    bus::PublishTyped(bus, ch.SimClock(), c);
  }
  std::optional<fitness_t> Final() const {
    for (const auto& f : heard)
      if (f.is_final) return f;
    return std::nullopt;
  }
};

}  // namespace

TEST_CASE("a tracker's state of the final tick, sent after FINISHED, is counted",
          "[fitness][tracker]") {
  GaitEpisode e(3);
  episode::FitnessNode node(&e.bus, "T", std::chrono::milliseconds(60000));
  node.Poll(std::chrono::milliseconds(0));
  // A tracker answers each clock with that tick's state: ticks 0-9 running, then FINISHED at 10.
  for (std::int64_t k = 0; k < 10; ++k) {
    e.Clock(3, k, sim_clock_t::RUNNING);
    e.State(3, k);
    node.Poll(std::chrono::milliseconds(0));
  }
  e.Clock(3, 10, sim_clock_t::FINISHED);
  node.Poll(std::chrono::milliseconds(0));
  e.bus.Handle(std::chrono::milliseconds(0));
  CHECK_FALSE(e.Final());  // waiting for tick 10's state
  e.State(3, 10);
  node.Poll(std::chrono::milliseconds(0));
  e.bus.Handle(std::chrono::milliseconds(0));
  const auto f = e.Final();
  REQUIRE(f);
  CHECK(f->status == fitness_t::OK);
  CHECK(f->states_missed == 0);
  CHECK(f->states_seen == 11);
  CHECK(f->sim_time == Approx(10 * e.period));
  // All 10 ticks of 1 cm count: 0.1 m over 1 m / 0.7.
  CHECK(f->fitness == Approx(0.07).epsilon(1e-9));
}

TEST_CASE("without the final tick's state the monitor ends after its wait, saying one is missed",
          "[fitness][tracker]") {
  GaitEpisode e(4);
  episode::FitnessNode node(&e.bus, "T", std::chrono::milliseconds(0));
  node.Poll(std::chrono::milliseconds(0));
  for (std::int64_t k = 0; k < 10; ++k) {
    e.Clock(4, k, sim_clock_t::RUNNING);
    e.State(4, k);
    node.Poll(std::chrono::milliseconds(0));
  }
  e.Clock(4, 10, sim_clock_t::FINISHED);
  node.Poll(std::chrono::milliseconds(0));  // handles FINISHED; the wait of 0 ms is over at once
  node.Maintain();
  e.bus.Handle(std::chrono::milliseconds(0));
  const auto f = e.Final();
  REQUIRE(f);
  CHECK(f->status == fitness_t::OK);
  CHECK(f->states_missed == 1);
  CHECK(f->fitness == Approx(0.063).epsilon(1e-9));  // 9 cm: ticks 1-9
}

TEST_CASE("a simulated episode's final state comes before FINISHED: no wait", "[fitness]") {
  GaitEpisode e(5);
  episode::FitnessNode node(&e.bus, "T", std::chrono::milliseconds(60000));
  node.Poll(std::chrono::milliseconds(0));
  for (std::int64_t k = 1; k <= 10; ++k) e.State(5, k);
  e.Clock(5, 10, sim_clock_t::FINISHED);
  node.Poll(std::chrono::milliseconds(0));
  e.bus.Handle(std::chrono::milliseconds(0));
  const auto f = e.Final();
  REQUIRE(f);
  CHECK(f->states_missed == 0);
}
