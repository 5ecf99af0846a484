// The fitness monitor's behaviour descriptor against hand-computed values (docs/scenarios.md,
// "Behaviour descriptors"), and the same bits from every arena kind.
#include "episode/fitness/fitness_monitor.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "episode/arena/direct_arena.h"
#include "episode/arena/fused_arena.h"
#include "modules/core/random.h"
#include "modules/core/variation.h"

using namespace ahhs;

namespace {

// A state of `n` bodies at `sim_time`; body b at (x[b], y[b], z[b]), a module body.
sim_state_t State(double sim_time, std::vector<double> x, std::vector<double> y,
                  std::vector<double> z) {
  sim_state_t s{};
  s.sim_time = sim_time;
  s.num_bodies = static_cast<std::int16_t>(x.size());
  s.px = x;
  s.py = y;
  s.pz = z;
  s.module.assign(x.size(), 0);
  return s;
}

}  // namespace

TEST_CASE("pendulum descriptor: the shares of ticks above the pivot and within 1 cm of a wall") {
  const double period = 0.0175;
  episode::FitnessMonitor m(sim::ScenarioKind::kPendulum, period, 4);
  // The state at RESET (t = 0) is no tick of the episode.
  REQUIRE(m.Add(State(0, {0, 0}, {0, 0}, {0, 0.5})));
  // Tick 1: upright, the cart in the middle. Tick 2: the bob below the pivot (phi = 120 deg),
  // the cart 5 mm from the right wall (its side at 0.995 m). Tick 3: bob horizontal-ish above
  // (phi = -80 deg), the cart 2 cm from the left wall. Tick 4: below, touching the left wall.
  const double l = 0.5, a = 120 * M_PI / 180, b = -80 * M_PI / 180;
  REQUIRE(m.Add(State(1 * period, {0, 0}, {0, 0}, {0, l})));
  REQUIRE(m.Add(State(2 * period, {0.895, 0.895 - l * std::sin(a)}, {0, 0}, {0, l * std::cos(a)})));
  REQUIRE(m.Add(State(3 * period, {-0.88, -0.88 - l * std::sin(b)}, {0, 0}, {0, l * std::cos(b)})));
  REQUIRE(m.Add(State(4 * period, {-0.9, -0.9}, {0, 0}, {0, -l})));
  const std::vector<double> d = m.descriptor();
  REQUIRE(d.size() == 2);
  CHECK(d[0] == 0.5);  // ticks 1 and 3 above the pivot
  CHECK(d[1] == 0.5);  // ticks 2 (5 mm) and 4 (0 mm) at a wall; tick 3's 2 cm is not
  CHECK(episode::FitnessMonitor::DescriptorNames(sim::ScenarioKind::kPendulum) ==
        std::vector<std::string>{"above_pivot", "at_wall"});
}

TEST_CASE("gait descriptor: the centroid's displacement from the first state to the last") {
  episode::FitnessMonitor m(sim::ScenarioKind::kGait, 0.05, 2);
  REQUIRE(m.Add(State(0, {0, 1}, {0, 0}, {0, 0})));           // centroid (0.5, 0)
  REQUIRE(m.Add(State(0.05, {3, 3}, {3, 3}, {1, 1})));        // ignored: only the latest counts
  REQUIRE(m.Add(State(0.1, {0.25, 0.75}, {-1, 0}, {0, 0})));  // centroid (0.5, -0.5)
  CHECK(m.descriptor() == std::vector<double>{0.0, -0.5});
  CHECK(m.cost() == 0.5);
  CHECK(episode::FitnessMonitor::DescriptorNames(sim::ScenarioKind::kGait) ==
        std::vector<std::string>{"end_x", "end_y"});
}

TEST_CASE(
    "the direct and fused arenas give the same descriptor to the bit, any scenario settings") {
  for (const auto kind : {sim::ScenarioKind::kPendulum, sim::ScenarioKind::kGait}) {
    for (const auto docking : {sim::DockingKind::kFixed, sim::DockingKind::kDamped}) {
      // (The pendulum twice: with the scenario's choices (kDamped, which it ignores) and others.)
      sim::ScenarioConfig config = sim::MakeScenarioConfig(kind, docking, 5, 3);
      if (kind == sim::ScenarioKind::kPendulum && docking == sim::DockingKind::kFixed) {
        // The pendulum's choices travel in RESET too (the fused arena's sim learns it there).
        config.pendulum.actuator_gain = 10;
        config.pendulum.walls = sim::PendulumWalls::kSoft;
      }
      const sim::ScenarioShape shape = sim::ShapeOf(config);
      modules::Rng rng(17);
      episode::EpisodeSpec spec;
      spec.config = config;
      spec.seed = 5;
      spec.genome = modules::RandomGenome(
          {modules::Variant::kAhhs2, 3, 8, shape.sensors, shape.actuators}, rng);
      const episode::EpisodeResult direct = episode::RunDirectEpisode(spec);
      const episode::EpisodeResult viabus = episode::RunFused(spec);
      REQUIRE(direct.ok);
      REQUIRE(viabus.ok);
      CHECK(direct.fitness == viabus.fitness);
      REQUIRE(direct.descriptor.size() == 2);
      CHECK(direct.descriptor == viabus.descriptor);
    }
  }
}
