#include "episode/arena/robustness.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "episode/arena/direct_arena.h"

namespace ahhs::episode {

double Quantile(const std::vector<double>& sorted, double q) {
  const double pos = q * static_cast<double>(sorted.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (pos - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

Spread SpreadOf(std::vector<double> values) {
  if (values.empty()) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan, nan, nan};
  }
  std::sort(values.begin(), values.end());
  return {Quantile(values, 0.5), Quantile(values, 0.25), Quantile(values, 0.75), values.front(),
          values.back()};
}

std::vector<double> RobustnessScales(int n) {
  // 1 -+ spread * j / m for j = 1..m, m = ceil(n / 2): never 1 itself (that is the replay).
  const int m = (n + 1) / 2;
  std::vector<double> scales;
  for (int j = 1; j <= m; ++j) {
    scales.push_back(1 - kRobustnessSpread * j / m);
    if (static_cast<int>(scales.size()) < n) scales.push_back(1 + kRobustnessSpread * j / m);
  }
  std::sort(scales.begin(), scales.end());
  return scales;
}

Robustness MeasureRobustness(const EpisodeSpec& spec, int n) {
  Robustness r;
  r.scales = RobustnessScales(n);
  std::vector<double> ok;
  for (double scale : r.scales) {
    EpisodeSpec perturbed = spec;
    perturbed.config.friction_scale = scale;
    const EpisodeResult result = RunDirectEpisode(perturbed);
    if (result.ok) {
      r.fitnesses.push_back(result.fitness);
      ok.push_back(result.fitness);
    } else {
      r.fitnesses.push_back(std::numeric_limits<double>::quiet_NaN());
      r.errors.push_back(result.error);
      ++r.failed;
    }
  }
  const Spread s = SpreadOf(std::move(ok));
  r.median = s.median;
  r.lower_quartile = s.lower_quartile;
  r.upper_quartile = s.upper_quartile;
  r.min = s.min;
  r.max = s.max;
  return r;
}

std::string Robustness::Describe(double fitness) const {
  char buf[400];
  const int n = static_cast<int>(scales.size());
  if (failed == n) {
    std::snprintf(buf, sizeof buf, "robustness: all %d perturbed replays failed (%s)", n,
                  errors.front().c_str());
    return buf;
  }
  const char* verdict = fitness > max              ? "above every perturbed replay: a knife-edge"
                        : fitness > upper_quartile ? "above the upper quartile"
                        : fitness < lower_quartile ? "below the lower quartile"
                                                   : "within the quartiles: robust";
  std::snprintf(buf, sizeof buf,
                "robustness: %d replays with friction x%.3f to x%.3f: median %.4g, quartiles "
                "%.4g / %.4g, range %.4g / %.4g%s; this fitness %.4g is %s",
                n, scales.front(), scales.back(), median, lower_quartile, upper_quartile, min, max,
                failed > 0 ? (" (" + std::to_string(failed) + " failed)").c_str() : "", fitness,
                verdict);
  return buf;
}

}  // namespace ahhs::episode
