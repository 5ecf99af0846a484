// The inverted pendulum on a cart ("crab"), paper section 3.1: a cart between two walls, a
// point-mass pendulum free to turn 360 degrees, two compartments (left, right) with partitioned,
// relative, noisy sensors. Integrated with RK4; no ODE world (none is needed for a 1-D cart).
#pragma once

#include <random>

#include "sim/core/constants.h"
#include "sim/core/scenario.h"

namespace ahhs::sim {

// Sensor slots (even: left compartment 0, odd: right compartment 1).
enum PendulumSensor : int {
  kUpperLeft = 0,   // pendulum in the upper-left quadrant, 1 at the top
  kUpperRight = 1,  // upper-right quadrant, 1 at the top
  kLowerLeft = 2,   // lower-left quadrant, 1 at the bottom
  kLowerRight = 3,  // lower-right quadrant, 1 at the bottom
  kWallLeft = 4,    // proximity of the left wall, 1 = touching
  kWallRight = 5,
  kSpeedLeft = 6,  // cart speed to the left / max speed
  kSpeedRight = 7,
  kSpinPositive = 8,  // counter-clockwise angular speed / spin_sensor_range, at most 1
  kSpinNegative = 9,  // clockwise
  kPendulumSensors = 10,
};

// Dynamic state. phi: angle from the top, counter-clockwise positive (the bob moves to -x),
// wrapped to (-pi, pi]; hanging down is phi = pi.
struct PendulumState {
  double x = 0;       // cart centre, m
  double v = 0;       // cart speed, m/s
  double phi = M_PI;  // rad
  double omega = 0;   // rad/s
};

class PendulumScenario final : public Scenario {
 public:
  explicit PendulumScenario(const ScenarioConfig& config, PendulumConstants constants = {});

  void Reset(std::uint64_t seed) override;
  int num_compartments() const override { return 2; }
  int num_sensors() const override { return kPendulumSensors; }
  int num_actuators() const override { return 2; }
  bool sensor_owned(int compartment, int sensor) const override {
    return sensor % 2 == compartment;
  }
  bool actuator_owned(int compartment, int actuator) const override {
    return actuator == compartment;
  }
  std::vector<std::pair<int, int>> Docking() const override { return ChainDocking(2); }
  void SetActuators(int compartment, const double* values) override;
  using Scenario::Step;
  StepStatus Step(const SubstepObserver& observer) override;
  void ReadSensors(int compartment, double* values) const override;
  double HingeAngle(int) const override { return 0.0; }
  void Bodies(std::vector<BodyState>* bodies) const override;
  double Fitness() const override;
  double Cost() const override { return cost_; }
  std::int64_t tick() const override { return tick_; }
  std::int64_t total_ticks() const override { return total_ticks_; }
  double control_period() const override { return k_.control_period; }
  const std::string& error() const override { return error_; }

  const PendulumState& state() const { return state_; }
  // For tests: start from a given state.
  void SetState(const PendulumState& s);
  const PendulumConstants& constants() const { return k_; }

 private:
  void Integrate(double v_cmd);  // one RK4 step of k_.integration_step
  void SampleSensors();          // noisy readings for the current tick

  PendulumConstants k_;
  Envelope envelope_;
  PendulumChoices choices_;
  double cart_speed_scale_ = 1;  // this episode's envelope draw
  std::int64_t total_ticks_;
  PendulumState state_;
  double actuators_[2] = {0, 0};
  double sensors_[kPendulumSensors] = {};
  std::mt19937_64 noise_rng_{0};
  std::int64_t tick_ = 0;
  double cost_ = 0;
  std::string error_;
};

// Wraps an angle into (-pi, pi].
double WrapAngle(double a);

// Pendulum fitness from its accumulated cost: 1 - cost / (pi * ticks); 0 for a pendulum that
// hangs still, 1 for one always upright.
double PendulumFitness(double cost, std::int64_t ticks);

}  // namespace ahhs::sim
