// Every physical constant of both tasks, in one place, with its unit. docs/scenarios.md lists
// them with the reasons for each choice; change both together.
#pragma once

#include <cmath>

namespace ahhs::sim {

struct PendulumConstants {
  double control_period = 0.05;                   // s per controller tick
  int ticks = 3000;                               // ticks per episode (150 s)
  double integration_step = 0.01;                 // s, RK4 (5 substeps per tick)
  double gravity = 9.81;                          // m/s^2
  double length = 0.5;                            // m, pivot to point mass (massless rod)
  double pivot_friction = 0.05;                   // 1/s, viscous: d(omega)/dt -= friction * omega
  double max_angular_speed = 0.05 * M_PI / 0.05;  // rad/s: at most 9 degrees per tick
  double wall_inner = 1.0;                        // m, inner faces of the walls at x = +-wall_inner
  double cart_half_width = 0.1;                   // m
  double max_speed = 1.0;                         // m/s, v_cmd = max_speed * (A1 - A0) / 2
  double motor_time_constant = 0.1;               // s, first-order lag from v_cmd to cart speed
  double wall_sensor_range = 1.0;  // m, proximity 1 at contact, 0 at this gap or more
  double noise = 0.023;            // uniform noise +-noise (fraction of the [0, 1] range)
  double cart_mass = 1.0;          // kg (reported in SIM/STATE only; the cart is driven)
  double bob_mass = 0.1;           // kg (reported only)
};

struct GaitConstants {
  double control_period = 0.05;  // s per controller tick (20 Hz)
  double physics_step = 0.0125;  // s, dWorldQuickStep: 4 steps per control tick
  int solver_iterations = 16;    // dWorldSetQuickStepNumIterations (docs/scenarios.md)
  // Successive over-relaxation of the quick-step solver (dWorldSetQuickStepW; ODE's default is
  // 1.3). The damped chain (10 bodies, 4 soft docks) needs 1.5 for the servo to hold two
  // modules within 16 iterations; the fixed chain (6 bodies) is closest to a converged solver
  // at 1.3. Measured, see docs/scenarios.md.
  double solver_relaxation_fixed = 1.3;
  double solver_relaxation_damped = 1.5;
  double duration = 60.0;         // s per episode
  double gravity = 9.81;          // m/s^2
  double module_size = 0.1;       // m, a module is a cube of this edge, two halves along x
  double module_mass = 0.5;       // kg (0.25 kg per half)
  double hinge_range = M_PI / 2;  // rad, main hinge limits +-90 degrees; target = range * A
  double servo_gain = 10.0;       // 1/s, commanded hinge speed = gain * angle error
  double servo_max_speed = 3.0;   // rad/s
  // N m. Holding the module's own half plus two modules straight out needs 1.53 N m, plus three
  // modules 3.0 N m: 2.2 N m lifts two neighbours, not three.
  double servo_max_torque = 2.2;
  double friction = 0.8;  // Coulomb friction coefficient, every contact
  double contact_erp = 0.2, contact_cfm = 1e-5;
  double world_erp = 0.2, world_cfm = 1e-9;  // rigid ("fixed") docking uses these
  // "Damped" docking: a stiff spring-damper per constraint direction, N/m and N s/m, turned
  // into ERP/CFM for the docking joints (ODE manual, "soft constraint").
  double dock_stiffness = 4000.0;
  double dock_damping = 40.0;
  double sensor_range = 0.2;     // m, proximity rays; value 1 - distance / range
  double wall_inner = 1.0;       // m, inner face of the square wall from the start centre
  double wall_height = 0.05;     // m
  double wall_thickness = 0.05;  // m
  double cube_size = 0.1;        // m, static cubes outside the wall
  // Fitness: displacement / (wall_inner / 0.7), so the centroid at the wall's face scores 0.7.
  double fitness_wall_score = 0.7;
};

}  // namespace ahhs::sim
