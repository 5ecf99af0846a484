// Is a fitness robust, or a knife-edge that deterministic chaos happened to favour? The same
// genome and evaluation seed replayed in slightly perturbed physics (docs/scenarios.md,
// "Deterministic chaos"). Evolution keeps the best of many chaotic evaluations, so its best is
// often far above what the same controller scores when friction changes by 1 %.
#pragma once

#include <string>
#include <vector>

#include "episode/arena/episode.h"

namespace ahhs::episode {

// The q-quantile of sorted values, linear between order statistics (numpy's default).
double Quantile(const std::vector<double>& sorted, double q);

// Median, quartiles and range of some values; all NaN when there are none.
struct Spread {
  double median, lower_quartile, upper_quartile, min, max;
};
Spread SpreadOf(std::vector<double> values);

// Friction scales of a robustness check with n replays, from 1 - spread to 1 + spread in
// even steps on both sides of 1, never 1 itself.
inline constexpr double kRobustnessSpread = 0.025;
std::vector<double> RobustnessScales(int n);

struct Robustness {
  std::vector<double> scales;     // friction scale of each replay
  std::vector<double> fitnesses;  // of each replay; NaN where the episode failed
  std::vector<std::string> errors;
  int failed = 0;
  // Over the replays that did not fail; NaN when all failed.
  double median = 0, lower_quartile = 0, upper_quartile = 0, min = 0, max = 0;
  // One line: the spread, and where `fitness` (the unperturbed replay's) lies in it.
  std::string Describe(double fitness) const;
};

// Replays `spec` (its friction_scale taken as 1) with each of RobustnessScales(n).
Robustness MeasureRobustness(const EpisodeSpec& spec, int n);

}  // namespace ahhs::episode
