// Built-in open-loop commands for running a scenario without controllers (`ahhs-sim --drive`):
// the physics-only baseline and a debugging aid.
#pragma once

#include <string>

#include "sim/core/scenario.h"

namespace ahhs::sim {

enum class DriveKind { kZero, kWave };

DriveKind ParseDrive(const std::string& name);  // "zero" / "wave"; throws std::invalid_argument

// Actuator values (num_actuators entries) for one compartment at the current tick.
// zero: all 0. wave, gait: a sine wave travelling along the chain,
// A_i = amplitude * sin(2 pi f t - i * phase_lag). wave, pendulum: the cart is pushed back and
// forth in a square wave at the pendulum's natural period, pumping the swing.
void DriveCommand(DriveKind drive, const Scenario& scenario, int compartment, double* values);

}  // namespace ahhs::sim
