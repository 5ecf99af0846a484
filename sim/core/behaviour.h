// What an episode did, in the terms the paper describes behaviours in: for the pendulum, how
// much of the time the bob was above the pivot and how often it went over the top; for the
// gait, whether the controllers' commands still changed after the start and where the organism
// ended up relative to the wall. Fed once per tick; used by ahhs-replay and ahhs-sim.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sim/core/scenario.h"

namespace ahhs::sim {

class BehaviourSummary {
 public:
  // Command changes before this simulated time do not count (a controller's start-up).
  static constexpr double kSettleTime = 5.0;  // s

  // After each completed tick: the scenario's state and the actuator values every compartment
  // commanded for that tick (any layout; compared with the previous tick's, value by value).
  void Observe(const Scenario& scenario, const std::vector<double>& commands);

  std::int64_t ticks() const { return ticks_; }
  // Pendulum.
  std::int64_t ticks_above_pivot() const { return above_; }
  int passes_over_top() const { return passes_; }
  double widest_turn() const { return widest_; }  // rad in one tick
  // Gait. Simulated time of the last tick after kSettleTime whose commands differed from the
  // tick before; -1 if they never changed after kSettleTime (a constant command).
  double last_command_change() const { return last_change_; }
  // Largest range (max - min) of any one command value over the ticks after kSettleTime.
  double command_swing() const;
  // Module halves beyond the wall's outer face at the end, and all halves.
  int halves_over_wall() const { return halves_over_; }
  int halves() const { return halves_; }
  // Centroid displacement from the first observed tick to the last, x and y, m.
  double moved_x() const { return moved_[0]; }
  double moved_y() const { return moved_[1]; }
  // "inside", "at the wall", "half over", "over" (all halves beyond the wall).
  std::string WallClass() const;

  // One line, e.g. "bob above the pivot in 73.1 % of ticks, 28 passes over the top, at most
  // 8.95 degrees per tick".
  std::string Describe() const;

 private:
  bool pendulum_ = false;
  std::int64_t ticks_ = 0, above_ = 0;
  int passes_ = 0;
  double widest_ = 0, prev_phi_ = 0;
  bool have_prev_ = false;
  std::vector<double> prev_commands_;
  double last_change_ = -1;
  std::vector<double> low_, high_;  // per command value, after kSettleTime
  int halves_over_ = 0, halves_ = 0, halves_near_ = 0;
  bool have_start_ = false;
  double start_[2] = {0, 0}, moved_[2] = {0, 0};
  std::vector<BodyState> bodies_;
};

}  // namespace ahhs::sim
