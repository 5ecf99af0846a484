// Every physical constant of both scenarios, in one place, with its unit. docs/scenarios.md lists
// them with the reasons for each choice; change both together.
#pragma once

#include <cmath>
#include <string>

namespace ahhs::sim {

// The physics a fitness was measured with, per scenario (sim::PhysicsVersion picks one). Bump one
// with every change that changes a fitness of that scenario (constants, solver, sensors): a study
// takes an exported run only when it was made with the same physics (tools/study), since the
// run store cannot tell otherwise. CHANGELOG.md says what each change was.
inline constexpr const char* kPendulumPhysicsVersion = "2026-12-01";
inline constexpr const char* kGaitFixedPhysicsVersion = "2026-12-05";
inline constexpr const char* kGaitDampedPhysicsVersion = "2026-12-05";
// Earlier gait physics this build still replays (sim::ReplayablePhysics), all the same model:
// the chain solver without its warm start (both dockings), and ODE's dWorldStep instead of the
// chain solver (the first study was made with those).
inline constexpr const char* kGaitChainColdPhysicsVersion = "2026-12-04";
inline constexpr const char* kGaitFixedDantzigPhysicsVersion = "2026-12-01";
inline constexpr const char* kGaitDampedDantzigPhysicsVersion = "2026-12-01.2";

// The physics versions for --version.
inline std::string PhysicsVersionLine() {
  return std::string("physics: pendulum ") + kPendulumPhysicsVersion + ", gait fixed " +
         kGaitFixedPhysicsVersion + ", gait damped " + kGaitDampedPhysicsVersion +
         " (replays gait " + kGaitChainColdPhysicsVersion + ", gait fixed " +
         kGaitFixedDantzigPhysicsVersion + ", gait damped " + kGaitDampedDantzigPhysicsVersion +
         ")";
}

struct PendulumConstants {
  // s per controller tick. The paper's slow sampling: a pendulum that keeps turning passes the
  // bottom at 2 sqrt(g / l) = 8.86 rad/s or a little faster, about 9 degrees per tick
  // (docs/scenarios.md). Not a speed limit: nothing caps the angular speed.
  double control_period = 0.0175;
  int ticks = 3000;                  // ticks per episode (52.5 s)
  double integration_step = 0.0035;  // s, RK4 (5 substeps per tick)
  double gravity = 9.81;             // m/s^2
  double length = 0.5;               // m, pivot to point mass (massless rod)
  double pivot_friction = 0.05;      // 1/s, viscous: d(omega)/dt -= friction * omega
  // rad/s: the angular-speed sensors read 1 at this speed (9 degrees per tick) and saturate above.
  double spin_sensor_range = 0.05 * M_PI / 0.0175;
  double wall_inner = 1.0;           // m, inner faces of the walls at x = +-wall_inner
  double cart_half_width = 0.1;      // m
  double max_speed = 1.0;            // m/s, v_cmd = max_speed * (A1 - A0) / 2
  double motor_time_constant = 0.1;  // s, first-order lag from v_cmd to cart speed
  double wall_sensor_range = 1.0;    // m, proximity 1 at contact, 0 at this gap or more
  double noise = 0.023;              // uniform noise +-noise (fraction of the [0, 1] range)
  double cart_mass = 1.0;            // kg (reported in SIM/STATE only; the cart is driven)
  double bob_mass = 0.1;             // kg (reported only)
  // Soft walls (pendulum.walls = soft): a spring-damper stop pushing the cart out of a wall,
  // acceleration = stiffness x depth + damping x inward speed (never pulling): 44.7 rad/s, 0.7
  // of critical damping; a cart at top speed stops within about 1.5 cm, one pushed by the
  // motor rests 5 mm deep.
  double soft_wall_stiffness = 2000;  // 1/s^2
  double soft_wall_damping = 62.6;    // 1/s
};

enum class GaitSolver { kChain, kDantzig, kQuickStep };

struct GaitConstants {
  double control_period = 0.05;  // s per controller tick (20 Hz)
  // s per physics step. Fixed docking: 4 steps per control tick. Damped docking: 8, because
  // its docking springs ring at about 20-30 Hz, which 4 steps per tick do not resolve: evolved
  // damped gaits then behaved differently at finer steps (docs/scenarios.md, "Physics step").
  double physics_step_fixed = 0.0125;
  double physics_step_damped = 0.00625;
  // The solver. The model is ODE's exact (Dantzig LCP) dWorldStep: with the iterative
  // dWorldQuickStep the under-converged contact and servo forces made a chain under constant
  // commands chatter and creep (up to 0.9 m in 55 s); docs/scenarios.md has the measurements.
  // kChain solves that model with the chain's structure (sim/core/chain_step.h), about twice as
  // fast for a moving chain with the same distributions (docs/performance.md); kDantzig is
  // dWorldStep itself (the physics of 2026-12-01); kQuickStep, with the settings below, is kept
  // to compare against.
  GaitSolver solver = GaitSolver::kChain;
  // kChain: start each step's bounded rows from where the last step's ended (ChainStep::Params).
  bool chain_warm_start = true;
  int solver_iterations = 16;  // dWorldSetQuickStepNumIterations
  // Successive over-relaxation of the quick-step solver (dWorldSetQuickStepW).
  double solver_relaxation_fixed = 1.3;
  double solver_relaxation_damped = 1.5;
  // Resting: an organism whose every body moves slower than these for rest_time
  // is put to rest (ODE's auto-disable) until a hinge target changes. A resting chain cannot
  // creep by contact micro-events (docs/scenarios.md). 0 s: never rest.
  double rest_linear_speed = 0.01;   // m/s
  double rest_angular_speed = 0.01;  // rad/s
  double rest_time = 0.125;          // s (10 physics steps of fixed docking)
  double duration = 60.0;            // s per episode
  double gravity = 9.81;             // m/s^2
  double module_size = 0.1;          // m, a module is a cube of this edge, two halves along x
  double module_mass = 0.5;          // kg (0.25 kg per half)
  double hinge_range = M_PI / 2;     // rad, main hinge limits +-90 degrees; target = range * A
  double servo_gain = 10.0;          // 1/s, commanded hinge speed = gain * angle error
  double servo_max_speed = 3.0;      // rad/s
  // N m. Holding the module's own half plus two modules straight out needs 1.53 N m, plus three
  // modules 3.0 N m: 2.2 N m lifts two neighbours, not three.
  double servo_max_torque = 2.2;
  // N m, Coulomb friction in the servo's gearbox: back-driving a hinge takes at least this much.
  // Without it a servo stalled short of its target (held back by gravity and contact) kept its
  // chain rocking in place (docs/scenarios.md).
  double servo_gear_friction = 0.1;
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
