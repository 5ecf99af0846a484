// Held-out post-evaluation: does a genome keep its fitness on episodes evolution never saw? It
// is replayed on N episodes whose seeds come from a stream no run draws its evaluation seeds
// from, each perturbed by an envelope of noise (sim/core/envelope.h), and summarised by median,
// quartiles, minimum and the share of episodes that succeed at the scenario: the gait over the wall
// (fitness > 1), the pendulum with the bob above the pivot in at least 20 % of ticks
// (docs/evolution.md, "Held-out post-evaluation"). For the gait also the share that ends with
// every module half beyond the wall's outer face, which a chain that has just crossed does
// at a fitness of 0.9-1 (docs/scenarios.md, "Against the paper's scale").
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "episode/arena/episode.h"
#include "sim/core/envelope.h"

namespace ahhs::episode {

// The k-th held-out seed (k = 0, 1, ...): the same for every genome, so two genomes are compared
// on the same episodes.
std::uint64_t HeldOutSeed(std::uint64_t k);

// The pendulum succeeds when the bob is above the pivot in at least this share of ticks.
inline constexpr double kPendulumSuccessShare = 0.2;

struct PostEvaluation {
  sim::ScenarioKind kind = sim::ScenarioKind::kGait;
  sim::Envelope envelope;
  std::vector<std::uint64_t> seeds;
  std::vector<double> fitnesses;  // NaN where the episode failed
  std::vector<bool> succeeded;
  std::vector<int> halves_over_wall;  // gait: module halves beyond the wall at the end; -1 failed
  std::vector<std::string> errors;
  int failed = 0;
  // Over the episodes that did not fail; NaN when all failed.
  double median = 0, lower_quartile = 0, upper_quartile = 0, min = 0;
  double success_share = 0;      // of all episodes (a failed one does not succeed)
  double beyond_wall_share = 0;  // gait, of all episodes: every module half beyond the wall
  // One line: "post-evaluation on 50 held-out episodes (envelope paper): median ..., ...".
  std::string Describe() const;
  // Every figure and episode (seed, fitness or null, success; the gait's halves beyond the
  // wall), the envelope's half-widths.
  nlohmann::json ToJson() const;
};

// Replays `spec`'s genome (its seed and envelope are replaced) on HeldOutSeed(0..n-1) under
// `envelope`, in the direct arena.
PostEvaluation PostEvaluate(const EpisodeSpec& spec, const sim::Envelope& envelope, int n);

}  // namespace ahhs::episode
