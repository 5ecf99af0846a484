#include "episode/arena/post_eval.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "episode/arena/direct_arena.h"
#include "episode/arena/robustness.h"
#include "modules/core/random.h"
#include "sim/core/behaviour.h"
#include "sim/core/envelope.h"

namespace ahhs::episode {

namespace {
constexpr std::uint64_t kHeldOutStream = 0x686f6c642d6f7574;  // "hold-out"
}

std::uint64_t HeldOutSeed(std::uint64_t k) { return modules::DeriveSeed(kHeldOutStream, {k}); }

PostEvaluation PostEvaluate(const EpisodeSpec& spec, const sim::Envelope& envelope, int n) {
  PostEvaluation r;
  r.kind = spec.config.kind;
  r.envelope = envelope;
  std::vector<double> ok;
  std::vector<double> commands;
  for (int k = 0; k < n; ++k) {
    EpisodeSpec e = spec;
    e.seed = HeldOutSeed(static_cast<std::uint64_t>(k));
    e.config.envelope = envelope;
    sim::BehaviourSummary behaviour;
    const EpisodeResult result = RunDirectEpisode(e, [&](const DirectTick& t) {
      commands.clear();
      for (int c = 0; c < t.organism->size(); ++c) {
        const auto& a = t.organism->state(c).actuators;
        commands.insert(commands.end(), a.data(), a.data() + a.size());
      }
      behaviour.Observe(*t.scenario, commands);
    });
    r.seeds.push_back(e.seed);
    if (!result.ok) {
      r.fitnesses.push_back(std::numeric_limits<double>::quiet_NaN());
      r.succeeded.push_back(false);
      r.halves_over_wall.push_back(-1);
      r.errors.push_back(result.error);
      ++r.failed;
      continue;
    }
    r.fitnesses.push_back(result.fitness);
    ok.push_back(result.fitness);
    const bool success =
        e.config.kind == sim::ScenarioKind::kGait
            ? result.fitness > 1.0
            : behaviour.ticks() > 0 &&
                  static_cast<double>(behaviour.ticks_above_pivot()) >=
                      kPendulumSuccessShare * static_cast<double>(behaviour.ticks());
    r.succeeded.push_back(success);
    r.halves_over_wall.push_back(behaviour.halves_over_wall());
    if (behaviour.halves() > 0 && behaviour.halves_over_wall() == behaviour.halves())
      r.beyond_wall_share += 1;
  }
  r.success_share =
      n > 0 ? static_cast<double>(std::count(r.succeeded.begin(), r.succeeded.end(), true)) / n
            : 0.0;
  r.beyond_wall_share = n > 0 ? r.beyond_wall_share / n : 0.0;
  const Spread s = SpreadOf(std::move(ok));
  r.median = s.median;
  r.lower_quartile = s.lower_quartile;
  r.upper_quartile = s.upper_quartile;
  r.min = s.min;
  return r;
}

nlohmann::json PostEvaluation::ToJson() const {
  using nlohmann::json;
  const auto number = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json envelope_doc = json::object();
  for (const auto& k : sim::EnvelopeKeys())
    if (k.Written(envelope)) envelope_doc[k.name] = envelope.*k.field;
  const bool gait = kind == sim::ScenarioKind::kGait;
  json episodes = json::array();
  for (std::size_t k = 0; k < seeds.size(); ++k) {
    json e = {{"seed", seeds[k]},
              {"fitness", number(fitnesses[k])},
              {"succeeded", static_cast<bool>(succeeded[k])}};
    if (gait)
      e["halves_over_wall"] = halves_over_wall[k] >= 0 ? json(halves_over_wall[k]) : json(nullptr);
    episodes.push_back(std::move(e));
  }
  json doc = {{"episodes", static_cast<int>(seeds.size())},
              {"envelope", sim::EnvelopeName(envelope)},
              {"envelope_half_widths", envelope_doc},
              {"failed", failed},
              {"median", number(median)},
              {"lower_quartile", number(lower_quartile)},
              {"upper_quartile", number(upper_quartile)},
              {"min", number(min)},
              {"success_share", success_share},
              {"per_episode", episodes}};
  if (gait) doc["beyond_wall_share"] = beyond_wall_share;
  return doc;
}

std::string PostEvaluation::Describe() const {
  char buf[400];
  const int n = static_cast<int>(seeds.size());
  const std::string env = sim::EnvelopeName(envelope);
  if (failed == n) {
    std::snprintf(buf, sizeof buf,
                  "post-evaluation: all %d held-out episodes (envelope %s) failed (%s)", n,
                  env.c_str(), errors.empty() ? "none run" : errors.front().c_str());
    return buf;
  }
  const bool gait = kind == sim::ScenarioKind::kGait;
  char beyond[64] = "";
  if (gait)
    std::snprintf(beyond, sizeof beyond, ", wholly beyond it at the end in %.0f %%",
                  100 * beyond_wall_share);
  std::snprintf(buf, sizeof buf,
                "post-evaluation on %d held-out episodes (envelope %s): median %.4g, quartiles "
                "%.4g / %.4g, min %.4g; %s in %.0f %%%s%s",
                n, env.c_str(), median, lower_quartile, upper_quartile, min,
                gait ? "over the wall (fitness > 1)" : "bob above the pivot in >= 20 % of ticks",
                100 * success_share, beyond,
                failed > 0 ? (" (" + std::to_string(failed) + " failed)").c_str() : "");
  return buf;
}

}  // namespace ahhs::episode
