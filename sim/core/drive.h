// Built-in commands for running a scenario without controllers (`ahhs-sim --drive`): the
// physics-only baselines, and designed reference controllers that show a scenario can be solved in
// our physics (docs/scenarios.md lists what each one scores).
#pragma once

#include <string>

#include "sim/core/scenario.h"

namespace ahhs::sim {

enum class DriveKind { kZero, kWave, kSwingUp, kInchworm };

// "zero" / "wave" / "swingup" / "inchworm"; throws std::invalid_argument naming the choices.
DriveKind ParseDrive(const std::string& name);
// True if the drive is defined for the scenario (swingup: pendulum only; inchworm: gait only).
bool DriveFits(DriveKind drive, const Scenario& scenario);

// Actuator values (num_actuators entries) for one compartment at the current tick; slots the
// compartment does not own are 0.
// - zero: all 0.
// - wave, gait: a sine wave travelling along the chain, A_i = 0.8 sin(2 pi 0.5 Hz t - i pi/2)
//   (caterpillar). wave, pendulum: the cart pushed back and forth in a square wave at the
//   pendulum's small-swing period (open loop; it does not swing the pendulum up).
// - inchworm, gait: every hinge bends one way only, A_i = 0.9 max(0, sin(2 pi 0.5 Hz t - i pi/4)):
//   a hump rises at the front and runs back along the chain, which inches forwards.
// - swingup, pendulum: energy pumping from the noisy sensors alone (what the two compartments'
//   controllers see together): it brings the pendulum over the top and keeps it turning.
void DriveCommand(DriveKind drive, const Scenario& scenario, int compartment, double* values);

}  // namespace ahhs::sim
