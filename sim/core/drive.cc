#include "sim/core/drive.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sim/core/gait.h"
#include "sim/core/pendulum.h"

namespace ahhs::sim {

DriveKind ParseDrive(const std::string& name) {
  if (name == "zero") return DriveKind::kZero;
  if (name == "wave") return DriveKind::kWave;
  if (name == "swingup") return DriveKind::kSwingUp;
  if (name == "inchworm") return DriveKind::kInchworm;
  throw std::invalid_argument("unknown drive '" + name +
                              "' (use zero, wave, swingup (pendulum) or inchworm (gait))");
}

bool DriveFits(DriveKind drive, const Scenario& scenario) {
  const bool pendulum = dynamic_cast<const PendulumScenario*>(&scenario) != nullptr;
  if (drive == DriveKind::kSwingUp) return pendulum;
  if (drive == DriveKind::kInchworm) return !pendulum;
  return true;
}

namespace {

// The pendulum's state as the ten noisy sensors tell it (docs/scenarios.md, sensor table).
struct PendulumEstimate {
  double phi, omega, x, v;
};

PendulumEstimate EstimatePendulum(const PendulumScenario& p) {
  const PendulumConstants& k = p.constants();
  double left[kPendulumSensors], right[kPendulumSensors], s[kPendulumSensors];
  p.ReadSensors(0, left);
  p.ReadSensors(1, right);
  for (int j = 0; j < kPendulumSensors; ++j) s[j] = j % 2 == 0 ? left[j] : right[j];
  const double half_pi = M_PI / 2;
  // The angle from the quadrant sensor that reads most; near the horizontal all four read ~0.
  const double by_quadrant[4] = {(1 - s[kUpperLeft]) * half_pi, -(1 - s[kUpperRight]) * half_pi,
                                 half_pi + s[kLowerLeft] * half_pi,
                                 -(half_pi + s[kLowerRight] * half_pi)};
  int q = 0;
  for (int j = 1; j < 4; ++j)
    if (s[j] > s[q]) q = j;
  PendulumEstimate e{};
  e.phi = by_quadrant[q];
  if (s[q] < 0.05)
    e.phi = s[kUpperLeft] + s[kLowerLeft] >= s[kUpperRight] + s[kLowerRight] ? half_pi : -half_pi;
  e.omega = (s[kSpinPositive] - s[kSpinNegative]) * k.spin_sensor_range;
  const double reach = k.wall_inner - k.cart_half_width;  // the cart centre's farthest x
  if (s[kWallLeft] > 0 && s[kWallLeft] >= s[kWallRight])
    e.x = -reach + (1 - s[kWallLeft]) * k.wall_sensor_range;
  else if (s[kWallRight] > 0)
    e.x = reach - (1 - s[kWallRight]) * k.wall_sensor_range;
  e.v = (s[kSpeedRight] - s[kSpeedLeft]) * k.max_speed;
  return e;
}

// Energy pumping (per unit mass, about the pivot): E = l^2 omega^2 / 2 + g l cos phi, and
// dE/dt = l omega a cos phi for a cart acceleration a. The cart accelerates along
// sign(omega cos phi) until E reaches the energy of passing the top at kTopSpeed, so the
// pendulum keeps turning slowly over the top; a spring-damper term keeps the cart off the walls.
double SwingUpSpeed(const PendulumScenario& p) {
  constexpr double kTopSpeed = 1.5;                                     // rad/s at the top
  constexpr double kEnergyGain = 1.0, kCentring = 1.0, kDamping = 1.0;  // 1/(m s), 1/s^2, 1/s
  const PendulumConstants& k = p.constants();
  const PendulumEstimate e = EstimatePendulum(p);
  const double l = k.length;
  const double energy = 0.5 * l * l * e.omega * e.omega + k.gravity * l * std::cos(e.phi);
  const double target = k.gravity * l + 0.5 * l * l * kTopSpeed * kTopSpeed;
  const double pump = e.omega * std::cos(e.phi) > 0 ? 1.0 : -1.0;
  const double accel = kEnergyGain * (target - energy) * pump - kCentring * e.x - kDamping * e.v;
  return std::clamp((e.v + k.motor_time_constant * accel) / k.max_speed, -1.0, 1.0);
}

}  // namespace

void DriveCommand(DriveKind drive, const Scenario& scenario, int compartment, double* values) {
  for (int a = 0; a < scenario.num_actuators(); ++a) values[a] = 0.0;
  if (drive == DriveKind::kZero) return;
  const double t = scenario.sim_time();
  if (const auto* pendulum = dynamic_cast<const PendulumScenario*>(&scenario)) {
    // v_cmd = v_max (A1 - A0) / 2: a speed u (in v_max) is A0 = -u, A1 = u.
    double u = 0;
    if (drive == DriveKind::kWave) {
      const PendulumConstants& k = pendulum->constants();
      const double period = 2 * M_PI * std::sqrt(k.length / k.gravity);
      u = std::sin(2 * M_PI * t / period) >= 0 ? 1.0 : -1.0;
    } else if (drive == DriveKind::kSwingUp) {
      u = SwingUpSpeed(*pendulum);
    }
    values[compartment] = compartment == 0 ? -u : u;
    return;
  }
  if (drive == DriveKind::kWave) {
    const double frequency = 0.5;       // Hz
    const double amplitude = 0.8;       // of the hinge range
    const double phase_lag = M_PI / 2;  // rad between neighbouring modules
    values[0] = amplitude * std::sin(2 * M_PI * frequency * t - compartment * phase_lag);
  } else if (drive == DriveKind::kInchworm) {
    // Each hinge bends one way only (a half-wave), a quarter of a quarter period after the
    // module in front of it: a hump rises at the front and runs back along the chain.
    const double frequency = 0.5;       // Hz
    const double amplitude = 0.9;       // of the hinge range
    const double phase_lag = M_PI / 4;  // rad between neighbouring modules
    const double s = std::sin(2 * M_PI * frequency * t - compartment * phase_lag);
    values[0] = amplitude * std::max(0.0, s);
  }
}

}  // namespace ahhs::sim
