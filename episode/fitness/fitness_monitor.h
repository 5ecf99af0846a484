// Scenario fitness computed from the organism's state alone (SIM/STATE), so that a tracking system
// can replace the simulator. Pure core: feed it states in order, read the fitness.
#pragma once

#include <ahhs/sim_state_t.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/core/scenario.h"

namespace ahhs::episode {

class FitnessMonitor {
 public:
  // control_period: seconds per controller tick; total_ticks: ticks of a full episode.
  FitnessMonitor(sim::ScenarioKind kind, double control_period, std::int64_t total_ticks);

  // Uses one state. Pendulum: every state at a tick boundary (sim_time = k * period, k >= 1)
  // adds |phi| (from cart = body 0 and bob = body 1) to the cost. Gait: the first state is the
  // start, the latest one the end; fitness = centroid displacement / (1 m / 0.7).
  // Returns false (and ignores the state) when it is malformed.
  bool Add(const sim_state_t& state);
  // The same for a state given as the scenario's bodies (scenery, module -1, is skipped as the
  // sim leaves it out of SIM/STATE): the direct arena's, without a message copy per tick.
  bool Add(double sim_time, const std::vector<sim::BodyState>& bodies);

  double fitness() const;
  double cost() const;
  // The behaviour descriptor (docs/scenarios.md, "Behaviour descriptors"). Pendulum: the shares
  // of the ticks seen with the bob above the pivot and with the cart within kNearWall of a wall;
  // gait: the centroid's displacement from the first state to the latest, x and y, m.
  static constexpr double kNearWall = 0.01;  // m, gap between the cart's side and a wall
  std::vector<double> descriptor() const;
  // What descriptor() holds, value by value: "above_pivot", "at_wall"; "end_x", "end_y".
  static std::vector<std::string> DescriptorNames(sim::ScenarioKind kind);
  std::int64_t ticks_seen() const { return ticks_; }
  std::int64_t states_seen() const { return states_; }
  // Whether the episode's last state has arrived (gait) / every tick's state (pendulum).
  bool complete() const {
    return kind_ == sim::ScenarioKind::kGait
               ? last_time_ >= static_cast<double>(total_ticks_) * period_ - 1e-9
               : ticks_with_state_ >= total_ticks_;
  }
  // Ticks of the episode for which the state needed did not arrive.
  std::int64_t ticks_missed() const {
    if (kind_ == sim::ScenarioKind::kPendulum) return total_ticks_ - ticks_with_state_;
    return complete() ? 0 : total_ticks_ - ticks_;
  }

 private:
  // One state: `pos(i)` is the i-th body's {x, y, z, module}, in message order.
  template <class Pos>
  bool AddState(double sim_time, std::size_t n, const Pos& pos);

  sim::ScenarioKind kind_;
  double period_;
  std::int64_t total_ticks_;
  std::int64_t ticks_ = 0;             // last tick seen
  std::int64_t ticks_with_state_ = 0;  // pendulum: tick-boundary states used
  std::int64_t states_ = 0;
  double cost_ = 0;
  std::int64_t ticks_above_ = 0, ticks_near_wall_ = 0;  // pendulum
  std::vector<std::size_t> moving_;                     // Add(bodies)'s scratch
  bool have_start_ = false;
  double start_[2] = {0, 0}, now_[2] = {0, 0};
  double last_time_ = -1;
};

}  // namespace ahhs::episode
