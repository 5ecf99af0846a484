// One physics step of a chain of rigid bodies with the constraint model of ODE's dWorldStep and
// a solver that uses the chain's structure.
//
// The model is dWorldStep's, row for row (ODE 0.16 source, read, not copied): a hinge gives 3
// ball rows and 2 axis rows (world ERP and CFM) plus one limit-or-motor row; a fixed joint 3
// linear rows with its own ERP and CFM and 3 angular rows with the world's; a one-axis angular
// motor 1 row; a contact a normal row (soft ERP and CFM) and two friction rows bounded by
// mu times the normal force (dContactApprox1). The unknowns are the row forces lambda of
//   (J M^-1 J^T + CFM / h) lambda = c / h - J (v / h + M^-1 f_ext) + w,
// each lambda in [lo, hi] with w complementary to it (w = 0 inside, w >= 0 at lo, w <= 0 at
// hi); then v += h M^-1 (f_ext + J^T lambda), x += h v, and the quaternion is advanced and
// normalised. f_ext holds gravity and the implicit gyroscopic torque (Lacoursiere 2006).
//
// The solver: dWorldStep hands all rows to one dense Dantzig LCP, whose cost grows with the
// cube of the rows (about 70 for a damped chain of 5 modules, 49 of them the joints' bilateral
// rows). Here the bilateral rows U are factored as J M^-1 J^T restricted to them, which for a
// chain added in order is a band matrix (a joint's rows touch only its neighbours' rows): an
// envelope LDL^T in time linear in the chain's length. The bounded rows B (motors, limits,
// contacts, about 20) are then solved on the Schur complement
//   S = A_BB - A_BU A_UU^-1 A_UB
// by Dantzig pivoting (sim/core/box_lcp.h, friction rows after the rest as in ODE), and
// lambda_U follows by back substitution. For a positive definite A the solution is unique,
// so this gives dWorldStep's answer to rounding whenever the friction bounds do not bind.
//
// Resting replaces ODE's per-body auto-disable: the chain rests when all its bodies have moved
// slower than the thresholds for rest_steps steps in a row (velocities zeroed, bodies
// disabled), and wakes when any body is enabled again (dBodyEnable).
#pragma once

#include <ode/ode.h>

#include <cstdint>
#include <utility>
#include <vector>

#include "sim/core/box_lcp.h"

namespace ahhs::sim {

class ChainStep {
 public:
  struct Params {
    double rest_linear_speed = 0;   // m/s
    double rest_angular_speed = 0;  // rad/s
    int rest_steps = 0;             // 0: never rest
    // Start each step's bounded rows from the states the last step's ended with, when the rows
    // are as many (sim/core/box_lcp.h): the same solution in other rounding, far fewer pivots.
    bool warm_start = false;
  };
  ChainStep(dWorldID world, Params params);

  // The structure, in chain order (bodies and joints as they follow each other along the
  // chain: the factor of the joints' rows is then a band; any order gives the same answer). A joint
  // is read from ODE at every step (its parameters, the hinge angle); its anchors and relative pose
  // are taken when it is added, as ODE takes them when it is set.
  void AddBody(dBodyID body);
  void AddHinge(dJointID hinge);
  void AddFixed(dJointID fixed);         // after dJointSetFixed; second body may be the world
  void AddAngularMotor(dJointID motor);  // one axis, relative to the first body, no stops
  // This step's contacts (cleared by Step); b1 or b2 may be null (static geometry).
  void AddContact(const dContact& contact, dBodyID b1, dBodyID b2);

  // True when the chain rests and stays resting (no body was enabled since): the caller may
  // skip collision and Step.
  bool Resting() const;
  // Advances the chain by h seconds.
  void Step(double h);

  // For tests and profiling: the rows of the last step (bilateral, bounded), the pivots its
  // bounded rows took, and how many steps' pivoting did not finish (GaitScenario fails the
  // episode at the first).
  int last_bilateral_rows() const { return last_nu_; }
  int last_bounded_rows() const { return last_nb_; }
  int last_pivots() const { return last_pivots_; }
  std::int64_t lcp_failures() const { return lcp_failures_; }

 private:
  struct Body {
    dBodyID id;
    double inv_mass;
    double inv_inertia[9];  // body frame, row-major
    int idle_steps = 0;
  };
  struct Hinge {
    dJointID id;
    int b1, b2;
    double anchor1[3], anchor2[3], axis1[3], axis2[3];  // body frames
  };
  struct Fixed {
    dJointID id;
    int b1, b2;  // b2 -1: the world
    double offset[3];
    dQuaternion qrel;
  };
  struct Motor {
    dJointID id;
    int b1, b2;
    int hinge;  // the hinge whose axis it turns about, or -1
  };
  struct Contact {
    dContact c;
    int b1, b2;
  };
  // One constraint row: the Jacobian for body b1 (lin, ang) and b2 (-1: none).
  struct Row {
    int b1, b2;
    double j1[6], j2[6];
    double rhs, cfm, lo, hi;
    int findex;  // -1, or the row (in the same list) whose force bounds this one
  };

  int BodyIndex(dBodyID body) const;
  void BuildRows(double h);
  void SolveRows();
  void Integrate(double h);

  dWorldID world_;
  Params params_;
  std::vector<Body> bodies_;
  std::vector<Hinge> hinges_;
  std::vector<Fixed> fixed_;
  std::vector<Motor> motors_;
  std::vector<Contact> contacts_;
  enum class JointKind { kHinge, kFixed, kMotor };
  std::vector<std::pair<JointKind, int>> joints_;  // in the order added
  bool resting_ = false;
  // Per step, reused.
  std::vector<double> inv_inertia_w_;  // 9 per body
  std::vector<double> force_;          // 6 per body: external force and torque
  std::vector<Row> unbounded_, bounded_;
  std::vector<double> lambda_u_, lambda_b_;
  std::vector<double> jm_u_, jm_b_;  // J M^-1, 12 per row
  std::vector<double> factor_;       // nu x nu envelope LDL^T (L below, D on the diagonal)
  std::vector<int> first_;           // first column of each U row's envelope
  std::vector<double> y_;            // L^-1 A_UB, nu x nb (column-major)
  std::vector<int> y_first_;         // first non-zero of each column of y_
  std::vector<double> yd_;           // y_ times D^-1
  std::vector<double> u_, z_, inv_d_;
  std::vector<int> root_;  // per bounded row: the first row with its Jacobian
  std::vector<double> schur_, rhs_b_, lo_b_, hi_b_, work_;
  std::vector<int> findex_b_, first_u_of_body_, body_start_, body_rows_;
  BoxLcp lcp_;
  BoxLcpStart lcp_start_;
  int last_nu_ = 0, last_nb_ = 0, last_pivots_ = 0;
  std::int64_t lcp_failures_ = 0;
};

}  // namespace ahhs::sim
