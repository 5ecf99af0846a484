#include "sim/core/drive.h"

#include <cmath>
#include <stdexcept>

namespace ahhs::sim {

DriveKind ParseDrive(const std::string& name) {
  if (name == "zero") return DriveKind::kZero;
  if (name == "wave") return DriveKind::kWave;
  throw std::invalid_argument("unknown drive '" + name + "' (use zero or wave)");
}

void DriveCommand(DriveKind drive, const Scenario& scenario, int compartment, double* values) {
  for (int a = 0; a < scenario.num_actuators(); ++a) values[a] = 0.0;
  if (drive == DriveKind::kZero) return;
  const double t = scenario.sim_time();
  if (scenario.num_compartments() == 2 && scenario.num_sensors() == 10) {  // pendulum
    const double period = 1.42;  // s, 2 pi sqrt(0.5 m / 9.81 m/s^2)
    const double push = std::sin(2 * M_PI * t / period) >= 0 ? 1.0 : -1.0;
    // v_cmd = v_max (A1 - A0) / 2: the left compartment pulls, the right one pushes.
    values[compartment] = compartment == 0 ? -push : push;
    return;
  }
  const double frequency = 0.5;       // Hz
  const double amplitude = 0.8;       // of the hinge range
  const double phase_lag = M_PI / 2;  // rad between neighbouring modules
  values[0] = amplitude * std::sin(2 * M_PI * frequency * t - compartment * phase_lag);
}

}  // namespace ahhs::sim
