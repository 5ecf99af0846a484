#include "sim/core/pendulum.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ahhs::sim {

double WrapAngle(double a) {
  a = std::fmod(a + M_PI, 2 * M_PI);
  if (a <= 0) a += 2 * M_PI;
  return a - M_PI;
}

double PendulumFitness(double cost, std::int64_t ticks) {
  return ticks > 0 ? 1.0 - cost / (M_PI * static_cast<double>(ticks)) : 0.0;
}

PendulumScenario::PendulumScenario(const ScenarioConfig& config, PendulumConstants constants)
    : k_(constants), envelope_(config.envelope), choices_(config.pendulum) {
  total_ticks_ = EpisodeTicks(config.duration, k_.control_period, k_.ticks);
  Reset(0);
}

void PendulumScenario::Reset(std::uint64_t seed) {
  state_ = PendulumState{};
  const EnvelopeDraw draw = DrawEnvelope(envelope_, seed, 2);
  if (envelope_.start_angle > 0) state_.phi = WrapAngle(M_PI + draw.start_angle);
  cart_speed_scale_ = draw.cart_speed_scale;
  actuators_[0] = actuators_[1] = 0;
  noise_rng_.seed(seed);
  tick_ = 0;
  cost_ = 0;
  error_.clear();
  SampleSensors();
}

void PendulumScenario::SetState(const PendulumState& s) {
  state_ = s;
  SampleSensors();
}

void PendulumScenario::SetActuators(int compartment, const double* values) {
  // Each compartment drives only its own actuator; non-finite values never reach the physics.
  const double a = values[compartment];
  if (std::isfinite(a)) actuators_[compartment] = std::clamp(a, -1.0, 1.0);
}

namespace {

// sin and cos of (phi + d) from sin and cos of phi, for |d| <= 0.04 rad (an RK4 stage is offset
// by about omega * integration_step: 0.035 rad at 10 rad/s, faster than a turning pendulum
// goes): Taylor series of sin d to d^7 and of cos d to d^8, whose remainders (< 1e-18) are below
// double rounding of the result. One library sincos per RK4 step instead of four
// (docs/performance.md). Multiplications by constant reciprocals, not divisions, for the same
// reason.
inline void SinCosNear(double sin_phi, double cos_phi, double d, double* sin_out, double* cos_out) {
  constexpr double k6 = 1.0 / 6, k20 = 1.0 / 20, k42 = 1.0 / 42;
  constexpr double k12 = 1.0 / 12, k30 = 1.0 / 30, k56 = 1.0 / 56;
  const double d2 = d * d;
  const double sin_d = d - d * d2 * k6 * (1 - d2 * k20 * (1 - d2 * k42));
  const double cos_d = 1 - d2 * 0.5 * (1 - d2 * k12 * (1 - d2 * k30 * (1 - d2 * k56)));
  *sin_out = sin_phi * cos_d + cos_phi * sin_d;
  *cos_out = cos_phi * cos_d - sin_phi * sin_d;
}

// sin and cos of phi + d for any d: near phi from the series, otherwise from the library (a
// pendulum spun faster than about 11 rad/s). Kept out of line so the RK4 stages stay inlined.
[[gnu::noinline]] void SinCosFar(double angle, double* sin_out, double* cos_out) {
  *sin_out = std::sin(angle);
  *cos_out = std::cos(angle);
}
inline void SinCosAt(double phi, double sin_phi, double cos_phi, double angle, double* sin_out,
                     double* cos_out) {
  const double d = angle - phi;
  if (std::fabs(d) <= 0.04)
    SinCosNear(sin_phi, cos_phi, d, sin_out, cos_out);
  else
    SinCosFar(angle, sin_out, cos_out);
}

}  // namespace

void PendulumScenario::Integrate(double v_cmd) {
  const double h = k_.integration_step;
  const double phi0 = state_.phi;
  const double sin0 = std::sin(phi0), cos0 = std::cos(phi0);
  const double inv_tau = 1 / k_.motor_time_constant, inv_length = 1 / k_.length;
  // Derivatives of (x, v, phi, omega) with the cart speed following v_cmd through a first-order
  // lag. The pivot's acceleration a drives the pendulum: phi'' = (g sin phi + a cos phi) / l.
  // The first stage is at phi itself; the others are close to it.
  const bool soft = choices_.walls == PendulumWalls::kSoft;
  const double x_max = k_.wall_inner - k_.cart_half_width;
  auto deriv = [&](const double s[4], double d[4], bool at_phi) {
    double a = (v_cmd - s[1]) * inv_tau;
    if (soft && std::fabs(s[0]) > x_max) {  // in a soft wall: pushed out, never pulled in
      const double side = s[0] > 0 ? 1.0 : -1.0;
      const double depth = std::fabs(s[0]) - x_max;
      a -=
          side * std::max(0.0, k_.soft_wall_stiffness * depth + k_.soft_wall_damping * s[1] * side);
    }
    double sin_phi = sin0, cos_phi = cos0;
    if (!at_phi) SinCosAt(phi0, sin0, cos0, s[2], &sin_phi, &cos_phi);
    d[0] = s[1];
    d[1] = a;
    d[2] = s[3];
    d[3] = (k_.gravity * sin_phi + a * cos_phi) * inv_length - k_.pivot_friction * s[3];
  };
  const double s0[4] = {state_.x, state_.v, state_.phi, state_.omega};
  double k1[4], k2[4], k3[4], k4[4], s[4];
  deriv(s0, k1, true);
  for (int i = 0; i < 4; ++i) s[i] = s0[i] + 0.5 * h * k1[i];
  deriv(s, k2, false);
  for (int i = 0; i < 4; ++i) s[i] = s0[i] + 0.5 * h * k2[i];
  deriv(s, k3, false);
  for (int i = 0; i < 4; ++i) s[i] = s0[i] + h * k3[i];
  deriv(s, k4, false);
  const double h6 = h / 6.0;
  for (int i = 0; i < 4; ++i) s[i] = s0[i] + h6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
  state_ = {s[0], s[1], s[2], s[3]};

  // A rigid wall stops the cart dead; the sudden stop kicks the pendulum (integrated phi'' over
  // the impulse: delta omega = delta v cos(phi) / l).
  if (!soft && std::fabs(state_.x) >= x_max) {
    state_.x = std::copysign(x_max, state_.x);
    if (state_.v * state_.x > 0) {
      double sin_phi, cos_phi;
      SinCosAt(phi0, sin0, cos0, state_.phi, &sin_phi, &cos_phi);
      state_.omega += -state_.v * cos_phi * inv_length;
      state_.v = 0;
    }
  }
  if (std::fabs(state_.phi) > M_PI) state_.phi = WrapAngle(state_.phi);
}

StepStatus PendulumScenario::Step(const SubstepObserver& observer) {
  if (!error_.empty()) return StepStatus::kFailed;
  if (tick_ >= total_ticks_) return StepStatus::kFinished;
  const double v_cmd =
      choices_.actuator_gain == 1
          ? k_.max_speed * cart_speed_scale_ * (actuators_[1] - actuators_[0]) / 2.0
          : k_.max_speed * cart_speed_scale_ *
                std::clamp(choices_.actuator_gain * (actuators_[1] - actuators_[0]) / 2.0, -1.0,
                           1.0);
  const int substeps = static_cast<int>(std::lround(k_.control_period / k_.integration_step));
  for (int i = 0; i < substeps; ++i) {
    Integrate(v_cmd);
    if (observer) observer((static_cast<double>(tick_) + (i + 1.0) / substeps) * k_.control_period);
  }
  if (!std::isfinite(state_.x) || !std::isfinite(state_.v) || !std::isfinite(state_.phi) ||
      !std::isfinite(state_.omega)) {
    error_ = "pendulum state is not finite at tick " + std::to_string(tick_);
    return StepStatus::kFailed;
  }
  ++tick_;
  cost_ += std::fabs(state_.phi);
  SampleSensors();
  return tick_ >= total_ticks_ ? StepStatus::kFinished : StepStatus::kRunning;
}

void PendulumScenario::SampleSensors() {
  const double phi = state_.phi;
  const double half_pi = M_PI / 2;
  double s[kPendulumSensors] = {};
  // Quadrants: phi in (0, pi/2] upper left, [-pi/2, 0] upper right, (pi/2, pi] lower left,
  // (-pi, -pi/2) lower right. Upper sensors rise to 1 at the top, lower ones at the bottom.
  if (phi > 0 && phi <= half_pi) s[kUpperLeft] = 1 - phi / half_pi;
  if (phi <= 0 && phi >= -half_pi) s[kUpperRight] = 1 + phi / half_pi;
  if (phi > half_pi) s[kLowerLeft] = (phi - half_pi) / half_pi;
  if (phi < -half_pi) s[kLowerRight] = (-phi - half_pi) / half_pi;
  const double gap_left = state_.x - k_.cart_half_width + k_.wall_inner;
  const double gap_right = k_.wall_inner - state_.x - k_.cart_half_width;
  s[kWallLeft] = std::max(0.0, 1 - gap_left / k_.wall_sensor_range);
  s[kWallRight] = std::max(0.0, 1 - gap_right / k_.wall_sensor_range);
  s[kSpeedLeft] = std::max(0.0, -state_.v) / k_.max_speed;
  s[kSpeedRight] = std::max(0.0, state_.v) / k_.max_speed;
  s[kSpinPositive] = std::min(1.0, std::max(0.0, state_.omega) / k_.spin_sensor_range);
  s[kSpinNegative] = std::min(1.0, std::max(0.0, -state_.omega) / k_.spin_sensor_range);
  // Independent uniform noise on every reading, in sensor order, then clamped to [0, 1].
  for (int j = 0; j < kPendulumSensors; ++j) {
    const double u = static_cast<double>(noise_rng_() >> 11) * 0x1.0p-53;
    sensors_[j] = std::clamp(s[j] + (2 * u - 1) * k_.noise, 0.0, 1.0);
  }
}

void PendulumScenario::ReadSensors(int compartment, double* values) const {
  for (int j = 0; j < kPendulumSensors; ++j)
    values[j] = sensor_owned(compartment, j) ? sensors_[j] : 0.0;
}

void PendulumScenario::Bodies(std::vector<BodyState>* bodies) const {
  // Body 0: the cart, its centre at the pivot. Body 1: the bob. Then the two walls.
  bodies->clear();
  BodyState cart;
  cart.module = 0;
  cart.position[0] = state_.x;
  cart.size[0] = 2 * k_.cart_half_width;
  cart.size[1] = 0.1;
  cart.size[2] = 0.05;
  cart.mass = k_.cart_mass;
  bodies->push_back(cart);
  BodyState bob;
  bob.module = 1;
  bob.shape = BodyState::kSphere;
  bob.position[0] = state_.x - k_.length * std::sin(state_.phi);
  bob.position[2] = k_.length * std::cos(state_.phi);
  bob.size[0] = 0.03;
  bob.mass = k_.bob_mass;
  bodies->push_back(bob);
  for (double side : {-1.0, 1.0}) {
    BodyState wall;
    wall.position[0] = side * (k_.wall_inner + 0.025);
    wall.size[0] = 0.05;
    wall.size[1] = 0.3;
    wall.size[2] = 0.3;
    bodies->push_back(wall);
  }
}

double PendulumScenario::Fitness() const { return PendulumFitness(cost_, tick_); }

}  // namespace ahhs::sim
