// Held-out post-evaluation's seeds and the arenas that cannot carry an envelope yet.
#include <catch2/catch.hpp>
#include <set>

#include "evolver/arena/fused_arena.h"
#include "evolver/arena/post_eval.h"
#include "evolver/ga/ga.h"
#include "modules/core/variation.h"

using namespace ahhs;

TEST_CASE("held-out seeds never equal a run's evaluation seeds", "[post-eval]") {
  std::set<std::uint64_t> held_out;
  for (std::uint64_t k = 0; k < 1000; ++k) held_out.insert(arena::HeldOutSeed(k));
  CHECK(held_out.size() == 1000);
  CHECK(arena::HeldOutSeed(0) == arena::HeldOutSeed(0));
  // Every evaluation seed of 20 runs at the paper's scale (seeds 1-20, 200 x 30).
  for (std::uint64_t run = 1; run <= 20; ++run)
    for (int g = 0; g < 200; ++g)
      for (int i = 0; i < 30; ++i) REQUIRE(held_out.count(evolver::EvaluationSeed(run, g, i)) == 0);
}

TEST_CASE("an arena that sends RESET refuses an envelope it cannot carry, never ignores it",
          "[post-eval][envelope]") {
  arena::EpisodeSpec spec;
  spec.config = sim::MakeScenarioConfig(sim::ScenarioKind::kPendulum, sim::Joints::kDamped, 2, 1);
  spec.config.envelope = sim::EnvelopePreset("paper");
  modules::Rng rng(3);
  spec.genome = modules::RandomGenome({modules::Variant::kAhhs2, 3, 4, 10, 2}, rng);
  const arena::EpisodeResult r = arena::RunFused(spec);
  CHECK_FALSE(r.ok);
  CHECK_THAT(r.error, Catch::Contains("envelope of noise (paper)"));
}
