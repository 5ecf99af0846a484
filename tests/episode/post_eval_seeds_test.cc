// Held-out post-evaluation's seeds and the arenas that cannot carry an envelope yet.
#include <catch2/catch.hpp>
#include <set>

#include "episode/arena/direct_arena.h"
#include "episode/arena/fused_arena.h"
#include "episode/arena/post_eval.h"
#include "evolver/ga/ga.h"
#include "modules/core/variation.h"

using namespace ahhs;

TEST_CASE("held-out seeds never equal a run's evaluation seeds, of any trial", "[post-eval]") {
  std::set<std::uint64_t> held_out;
  for (std::uint64_t k = 0; k < 1000; ++k) held_out.insert(episode::HeldOutSeed(k));
  CHECK(held_out.size() == 1000);
  CHECK(episode::HeldOutSeed(0) == episode::HeldOutSeed(0));
  // Every evaluation seed of 20 runs at the paper's scale (seeds 1-20, 200 x 30), with up to 5
  // trials per individual.
  for (std::uint64_t run = 1; run <= 20; ++run)
    for (int g = 0; g < 200; ++g)
      for (int i = 0; i < 30; ++i)
        for (int t = 0; t < 5; ++t) REQUIRE(held_out.count(evolver::TrialSeed(run, g, i, t)) == 0);
}

TEST_CASE("an envelope travels in RESET: the fused arena equals the direct one, bit for bit",
          "[post-eval][envelope]") {
  for (auto kind : {sim::ScenarioKind::kPendulum, sim::ScenarioKind::kGait}) {
    episode::EpisodeSpec spec;
    spec.config = sim::MakeScenarioConfig(kind, sim::DockingKind::kDamped, 3, 5);
    spec.config.envelope = sim::EnvelopePreset("wide");
    spec.seed = 21;
    modules::Rng rng(3);
    const auto shape = sim::ShapeOf(spec.config);
    spec.genome = modules::RandomGenome(
        {modules::Variant::kAhhs2, 3, 8, shape.sensors, shape.actuators}, rng);
    const episode::EpisodeResult direct = episode::RunDirectEpisode(spec);
    const episode::EpisodeResult fused = episode::RunFused(spec);
    REQUIRE(direct.ok);
    REQUIRE(fused.ok);
    CHECK(fused.fitness == direct.fitness);
    episode::EpisodeSpec plain = spec;
    plain.config.envelope = {};
    CHECK(episode::RunDirectEpisode(plain).fitness != direct.fitness);
  }
}
