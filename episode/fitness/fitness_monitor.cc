#include "episode/fitness/fitness_monitor.h"

#include <cmath>

#include "sim/core/gait.h"
#include "sim/core/pendulum.h"

namespace ahhs::episode {

FitnessMonitor::FitnessMonitor(sim::ScenarioKind kind, double control_period,
                               std::int64_t total_ticks)
    : kind_(kind), period_(control_period), total_ticks_(total_ticks) {}

namespace {
struct BodyAt {
  double x, y, z;
  int module;
};
}  // namespace

bool FitnessMonitor::Add(const sim_state_t& s) {
  return AddState(s.sim_time, static_cast<std::size_t>(s.num_bodies), [&](std::size_t b) {
    return BodyAt{s.px[b], s.py[b], s.pz[b], s.module[b]};
  });
}

bool FitnessMonitor::Add(double sim_time, const std::vector<sim::BodyState>& bodies) {
  // The moving bodies in order, as SIM/STATE lists them (sim::KeepMovingBodies).
  moving_.clear();
  for (std::size_t b = 0; b < bodies.size(); ++b)
    if (bodies[b].mass > 0) moving_.push_back(b);
  return AddState(sim_time, moving_.size(), [&](std::size_t i) {
    const sim::BodyState& body = bodies[moving_[i]];
    return BodyAt{body.position[0], body.position[1], body.position[2], body.module};
  });
}

template <class Pos>
bool FitnessMonitor::AddState(double sim_time, std::size_t n, const Pos& pos) {
  if (!std::isfinite(sim_time) || sim_time < last_time_) return false;  // out of order
  for (std::size_t b = 0; b < n; ++b) {
    const BodyAt p = pos(b);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
  }
  if (kind_ == sim::ScenarioKind::kPendulum) {
    if (n < 2) return false;
    const BodyAt cart = pos(0), bob = pos(1);
    const double k = sim_time / period_;
    const double tick = std::round(k);
    if (std::fabs(k - tick) < 1e-9 && tick >= 1 && tick > static_cast<double>(ticks_)) {
      // phi from the bob's position relative to the pivot (the cart's centre): the bob sits at
      // (-l sin phi, l cos phi).
      const double phi = std::atan2(cart.x - bob.x, bob.z - cart.z);
      cost_ += std::fabs(phi);
      if (std::fabs(phi) < M_PI / 2) ++ticks_above_;
      const sim::PendulumConstants pendulum;
      if (pendulum.wall_inner - std::fabs(cart.x) - pendulum.cart_half_width < kNearWall)
        ++ticks_near_wall_;
      ticks_ = static_cast<std::int64_t>(tick);
      ++ticks_with_state_;
    }
  } else {
    // Centroid of the module bodies, in message order (the sim lists them module by module).
    double c[2] = {0, 0};
    int count = 0;
    for (std::size_t b = 0; b < n; ++b) {
      const BodyAt p = pos(b);
      if (p.module < 0) continue;
      c[0] += p.x;
      c[1] += p.y;
      ++count;
    }
    if (count == 0) return false;
    c[0] /= count;
    c[1] /= count;
    if (!have_start_) {
      start_[0] = c[0];
      start_[1] = c[1];
      have_start_ = true;
    }
    now_[0] = c[0];
    now_[1] = c[1];
    ticks_ = static_cast<std::int64_t>(std::llround(sim_time / period_));
  }
  last_time_ = sim_time;
  ++states_;
  return true;
}

double FitnessMonitor::cost() const {
  if (kind_ == sim::ScenarioKind::kPendulum) return cost_;
  return std::hypot(now_[0] - start_[0], now_[1] - start_[1]);
}

double FitnessMonitor::fitness() const {
  // Mean over the ticks whose state arrived: a lost state leaves the estimate unbiased.
  if (kind_ == sim::ScenarioKind::kPendulum) return sim::PendulumFitness(cost_, ticks_with_state_);
  return sim::GaitFitness(cost(), sim::GaitConstants{});
}

std::vector<double> FitnessMonitor::descriptor() const {
  if (kind_ == sim::ScenarioKind::kPendulum) {
    const double n = static_cast<double>(ticks_with_state_);
    if (ticks_with_state_ == 0) return {0, 0};
    return {static_cast<double>(ticks_above_) / n, static_cast<double>(ticks_near_wall_) / n};
  }
  return {now_[0] - start_[0], now_[1] - start_[1]};
}

std::vector<std::string> FitnessMonitor::DescriptorNames(sim::ScenarioKind kind) {
  if (kind == sim::ScenarioKind::kPendulum) return {"above_pivot", "at_wall"};
  return {"end_x", "end_y"};
}

}  // namespace ahhs::episode
