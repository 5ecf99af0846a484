#include "sim/core/behaviour.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sim/core/gait.h"
#include "sim/core/pendulum.h"

namespace ahhs::sim {

void BehaviourSummary::Observe(const Scenario& scenario, const std::vector<double>& commands) {
  ++ticks_;
  const double time = scenario.sim_time();
  if (!prev_commands_.empty() && time > kSettleTime && commands != prev_commands_)
    last_change_ = time;
  prev_commands_ = commands;
  if (time > kSettleTime) {
    if (low_.empty()) low_ = high_ = commands;
    for (std::size_t i = 0; i < commands.size() && i < low_.size(); ++i) {
      low_[i] = std::min(low_[i], commands[i]);
      high_[i] = std::max(high_[i], commands[i]);
    }
  }

  if (const auto* p = dynamic_cast<const PendulumScenario*>(&scenario)) {
    pendulum_ = true;
    const double phi = p->state().phi;
    if (std::fabs(phi) < M_PI / 2) ++above_;
    if (have_prev_) {
      widest_ = std::max(widest_, std::fabs(WrapAngle(phi - prev_phi_)));
      // Over the top: the angle changes sign near 0 (near pi it is a pass through the bottom).
      if ((phi > 0) != (prev_phi_ > 0) && std::fabs(phi) < M_PI / 2 &&
          std::fabs(prev_phi_) < M_PI / 2)
        ++passes_;
    }
    prev_phi_ = phi;
    have_prev_ = true;
    return;
  }
  if (const auto* g = dynamic_cast<const GaitScenario*>(&scenario)) {
    const GaitConstants& k = g->constants();
    const auto c = g->Centroid();
    if (!have_start_) {
      start_[0] = c[0];
      start_[1] = c[1];
      have_start_ = true;
    }
    moved_[0] = c[0] - start_[0];
    moved_[1] = c[1] - start_[1];
    g->Bodies(&bodies_);
    halves_ = halves_over_ = halves_near_ = 0;
    for (const BodyState& b : bodies_) {
      if (b.module < 0) continue;
      ++halves_;
      const double out = std::max(std::fabs(b.position[0]), std::fabs(b.position[1]));
      if (out > k.wall_inner + k.wall_thickness) ++halves_over_;
      if (out > k.wall_inner - k.module_size) ++halves_near_;
    }
  }
}

double BehaviourSummary::command_swing() const {
  double swing = 0;
  for (std::size_t i = 0; i < low_.size(); ++i) swing = std::max(swing, high_[i] - low_[i]);
  return swing;
}

std::string BehaviourSummary::WallClass() const {
  if (halves_ == 0) return "";
  if (halves_over_ == halves_) return "over";
  if (2 * halves_over_ >= halves_) return "half over";
  if (halves_near_ > 0) return "at the wall";
  return "inside";
}

std::string BehaviourSummary::Describe() const {
  char line[256];
  if (pendulum_) {
    std::snprintf(
        line, sizeof line,
        "bob above the pivot in %.1f %% of ticks, %d passes over the top, at most %.2f "
        "degrees per tick",
        ticks_ > 0 ? 100.0 * static_cast<double>(above_) / static_cast<double>(ticks_) : 0.0,
        passes_, widest_ * 180 / M_PI);
    return line;
  }
  if (halves_ == 0) return "";
  char moved[96];
  std::snprintf(moved, sizeof moved, "; moved %.2f m (x %+.2f, y %+.2f)",
                std::hypot(moved_[0], moved_[1]), moved_[0], moved_[1]);
  if (last_change_ < 0)
    std::snprintf(line, sizeof line,
                  "commands constant after %.0f s; %s (%d of %d module halves beyond the wall)",
                  kSettleTime, WallClass().c_str(), halves_over_, halves_);
  else
    std::snprintf(line, sizeof line,
                  "commands still changing (last change at %.2f s, a command spans up to %.3g "
                  "after %.0f s); %s (%d of %d module halves beyond the wall)",
                  last_change_, command_swing(), kSettleTime, WallClass().c_str(), halves_over_,
                  halves_);
  return line + std::string(moved);
}

}  // namespace ahhs::sim
