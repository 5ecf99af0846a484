#include "sim/core/chain_step.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace ahhs::sim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// ODE's rotation matrices are row-major 3x4; ours are 3x3.
void RotationOf(dBodyID b, double r[9]) {
  const dReal* m = dBodyGetRotation(b);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r[3 * i + j] = m[4 * i + j];
}
void Mul(const double m[9], const double v[3], double out[3]) {
  for (int i = 0; i < 3; ++i) out[i] = m[3 * i] * v[0] + m[3 * i + 1] * v[1] + m[3 * i + 2] * v[2];
}
void MulT(const double m[9], const double v[3], double out[3]) {
  for (int i = 0; i < 3; ++i) out[i] = m[i] * v[0] + m[3 + i] * v[1] + m[6 + i] * v[2];
}
void MatMul(const double a[9], const double b[9], double out[9]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      out[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
}
// R M R^T.
void ToWorld(const double r[9], const double m[9], double out[9]) {
  double rm[9], rt[9];
  MatMul(r, m, rm);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) rt[3 * i + j] = r[3 * j + i];
  MatMul(rm, rt, out);
}
bool Invert3(const double m[9], double out[9]) {
  const double c0 = m[4] * m[8] - m[5] * m[7], c1 = m[5] * m[6] - m[3] * m[8],
               c2 = m[3] * m[7] - m[4] * m[6];
  const double det = m[0] * c0 + m[1] * c1 + m[2] * c2;
  if (det == 0) return false;
  const double inv = 1 / det;
  out[0] = c0 * inv;
  out[1] = (m[2] * m[7] - m[1] * m[8]) * inv;
  out[2] = (m[1] * m[5] - m[2] * m[4]) * inv;
  out[3] = c1 * inv;
  out[4] = (m[0] * m[8] - m[2] * m[6]) * inv;
  out[5] = (m[2] * m[3] - m[0] * m[5]) * inv;
  out[6] = c2 * inv;
  out[7] = (m[1] * m[6] - m[0] * m[7]) * inv;
  out[8] = (m[0] * m[4] - m[1] * m[3]) * inv;
  return true;
}
void Cross(const double a[3], const double b[3], double out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}
double Dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
double Dot6(const double a[6], const double b[6]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3] + a[4] * b[4] + a[5] * b[5];
}

}  // namespace

ChainStep::ChainStep(dWorldID world, Params params) : world_(world), params_(params) {}

int ChainStep::BodyIndex(dBodyID body) const {
  if (body == nullptr) return -1;
  for (std::size_t i = 0; i < bodies_.size(); ++i)
    if (bodies_[i].id == body) return static_cast<int>(i);
  throw std::invalid_argument("ChainStep: a joint's body was not added");
}

void ChainStep::AddBody(dBodyID body) {
  dMass m;
  dBodyGetMass(body, &m);
  Body b{body, 1 / m.mass, {}, 0};
  double inertia[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) inertia[3 * i + j] = m.I[4 * i + j];
  if (!Invert3(inertia, b.inv_inertia)) throw std::invalid_argument("ChainStep: singular inertia");
  bodies_.push_back(b);
}

void ChainStep::AddHinge(dJointID hinge) {
  Hinge h{hinge, BodyIndex(dJointGetBody(hinge, 0)), BodyIndex(dJointGetBody(hinge, 1)), {}, {}, {},
          {}};
  if (h.b1 < 0 || h.b2 < 0) throw std::invalid_argument("ChainStep: a hinge needs two bodies");
  if (dJointGetHingeParam(hinge, dParamBounce) > 0)
    throw std::invalid_argument("ChainStep: hinge stops with bounce are not modelled");
  dVector3 a1, a2, axis;
  dJointGetHingeAnchor(hinge, a1);
  dJointGetHingeAnchor2(hinge, a2);
  dJointGetHingeAxis(hinge, axis);
  double r1[9], r2[9];
  RotationOf(bodies_[static_cast<std::size_t>(h.b1)].id, r1);
  RotationOf(bodies_[static_cast<std::size_t>(h.b2)].id, r2);
  const dReal* p1 = dBodyGetPosition(bodies_[static_cast<std::size_t>(h.b1)].id);
  const dReal* p2 = dBodyGetPosition(bodies_[static_cast<std::size_t>(h.b2)].id);
  const double d1[3] = {a1[0] - p1[0], a1[1] - p1[1], a1[2] - p1[2]};
  const double d2[3] = {a2[0] - p2[0], a2[1] - p2[1], a2[2] - p2[2]};
  const double ax[3] = {axis[0], axis[1], axis[2]};
  MulT(r1, d1, h.anchor1);
  MulT(r2, d2, h.anchor2);
  MulT(r1, ax, h.axis1);
  MulT(r2, ax, h.axis2);
  joints_.emplace_back(JointKind::kHinge, static_cast<int>(hinges_.size()));
  hinges_.push_back(h);
}

void ChainStep::AddFixed(dJointID fixed) {
  Fixed f{fixed, BodyIndex(dJointGetBody(fixed, 0)), BodyIndex(dJointGetBody(fixed, 1)), {}, {}};
  if (f.b1 < 0) throw std::invalid_argument("ChainStep: a fixed joint's first body is missing");
  const dBodyID id1 = bodies_[static_cast<std::size_t>(f.b1)].id;
  const dReal* p1 = dBodyGetPosition(id1);
  const dReal* q1 = dBodyGetQuaternion(id1);
  if (f.b2 >= 0) {
    const dBodyID id2 = bodies_[static_cast<std::size_t>(f.b2)].id;
    const dReal* p2 = dBodyGetPosition(id2);
    double r1[9];
    RotationOf(id1, r1);
    const double d[3] = {p1[0] - p2[0], p1[1] - p2[1], p1[2] - p2[2]};
    MulT(r1, d, f.offset);
    dQMultiply1(f.qrel, q1, dBodyGetQuaternion(id2));
  } else {
    for (int k = 0; k < 3; ++k) f.offset[k] = p1[k];
    f.qrel[0] = q1[0];
    for (int k = 1; k < 4; ++k) f.qrel[k] = -q1[k];
  }
  joints_.emplace_back(JointKind::kFixed, static_cast<int>(fixed_.size()));
  fixed_.push_back(f);
}

void ChainStep::AddAngularMotor(dJointID motor) {
  Motor m{motor, BodyIndex(dJointGetBody(motor, 0)), BodyIndex(dJointGetBody(motor, 1)), -1};
  if (dJointGetAMotorMode(motor) != dAMotorUser || dJointGetAMotorNumAxes(motor) != 1 ||
      dJointGetAMotorAxisRel(motor, 0) != 1 || m.b1 < 0 || m.b2 < 0)
    throw std::invalid_argument("ChainStep: only a one-axis user motor relative to body 1");
  if (dJointGetAMotorParam(motor, dParamLoStop) > -kInf ||
      dJointGetAMotorParam(motor, dParamHiStop) < kInf)
    throw std::invalid_argument("ChainStep: angular motor stops are not modelled");
  // A motor about a hinge's axis (the gear friction) uses the hinge's axis.
  dVector3 ax;
  dJointGetAMotorAxis(motor, 0, ax);
  for (std::size_t h = 0; h < hinges_.size(); ++h) {
    if (hinges_[h].b1 != m.b1 || hinges_[h].b2 != m.b2) continue;
    dVector3 hx;
    dJointGetHingeAxis(hinges_[h].id, hx);
    const double a[3] = {ax[0], ax[1], ax[2]}, b[3] = {hx[0], hx[1], hx[2]};
    double c[3];
    Cross(a, b, c);
    if (Dot3(c, c) < 1e-24 && Dot3(a, b) > 0) m.hinge = static_cast<int>(h);
  }
  joints_.emplace_back(JointKind::kMotor, static_cast<int>(motors_.size()));
  motors_.push_back(m);
}

void ChainStep::AddContact(const dContact& contact, dBodyID b1, dBodyID b2) {
  constexpr int kModelled = dContactApprox1 | dContactSoftERP | dContactSoftCFM | dContactMu2;
  if ((contact.surface.mode & ~kModelled) != 0)
    throw std::invalid_argument("ChainStep: contact mode " + std::to_string(contact.surface.mode) +
                                " is not modelled");
  Contact c{contact, BodyIndex(b1), BodyIndex(b2)};
  if (c.b1 < 0) {  // as dJointAttach: the body goes first, the normal turns round
    std::swap(c.b1, c.b2);
    for (int k = 0; k < 3; ++k) c.c.geom.normal[k] = -c.c.geom.normal[k];
  }
  if (c.b1 < 0) return;  // static against static: no row
  contacts_.push_back(c);
}

bool ChainStep::Resting() const {
  if (!resting_) return false;
  for (const Body& b : bodies_)
    if (dBodyIsEnabled(b.id)) return false;
  return true;
}

void ChainStep::Step(double h) {
  if (bodies_.empty()) return;
  if (resting_) {
    if (Resting()) {
      contacts_.clear();
      return;
    }
    resting_ = false;  // a body was enabled: the whole chain wakes
    for (Body& b : bodies_) {
      dBodyEnable(b.id);
      b.idle_steps = 0;
    }
  }
  BuildRows(h);
  SolveRows();
  Integrate(h);
  contacts_.clear();
  if (params_.rest_steps <= 0) return;
  const double lin2 = params_.rest_linear_speed * params_.rest_linear_speed;
  const double ang2 = params_.rest_angular_speed * params_.rest_angular_speed;
  bool all_idle = true;
  for (Body& b : bodies_) {
    const dReal* v = dBodyGetLinearVel(b.id);
    const dReal* w = dBodyGetAngularVel(b.id);
    const bool idle = v[0] * v[0] + v[1] * v[1] + v[2] * v[2] <= lin2 &&
                      w[0] * w[0] + w[1] * w[1] + w[2] * w[2] <= ang2;
    b.idle_steps = idle ? b.idle_steps + 1 : 0;
    all_idle = all_idle && b.idle_steps >= params_.rest_steps;
  }
  if (!all_idle) return;
  resting_ = true;
  for (Body& b : bodies_) {
    dBodySetLinearVel(b.id, 0, 0, 0);
    dBodySetAngularVel(b.id, 0, 0, 0);
    dBodyDisable(b.id);
  }
}

void ChainStep::BuildRows(double h) {
  const double fps = 1 / h;
  const double world_erp = dWorldGetERP(world_), world_cfm = dWorldGetCFM(world_);
  dVector3 gravity;
  dWorldGetGravity(world_, gravity);
  const std::size_t nbody = bodies_.size();
  inv_inertia_w_.resize(9 * nbody);
  force_.resize(6 * nbody);
  for (std::size_t i = 0; i < nbody; ++i) {
    const Body& b = bodies_[i];
    double r[9];
    RotationOf(b.id, r);
    double* inv_iw = &inv_inertia_w_[9 * i];
    ToWorld(r, b.inv_inertia, inv_iw);
    double* f = &force_[6 * i];
    const dReal* fa = dBodyGetForce(b.id);
    const dReal* ta = dBodyGetTorque(b.id);
    const bool grav = dBodyGetGravityMode(b.id) != 0;
    for (int k = 0; k < 3; ++k) {
      f[k] = fa[k] + (grav ? gravity[k] / b.inv_mass : 0);
      f[3 + k] = ta[k];
    }
    if (dBodyGetGyroscopicMode(b.id)) {
      // Implicit gyroscopic torque: tau = (I (I + h [-L x])^-1 - 1) L / h, L = I w.
      dMass m;
      dBodyGetMass(b.id, &m);
      double ib[9], iw[9];
      for (int p = 0; p < 3; ++p)
        for (int q = 0; q < 3; ++q) ib[3 * p + q] = m.I[4 * p + q];
      ToWorld(r, ib, iw);
      const dReal* w = dBodyGetAngularVel(b.id);
      const double wv[3] = {w[0], w[1], w[2]};
      double l[3];
      Mul(iw, wv, l);
      const double itilde[9] = {iw[0], iw[1] + h * l[2], iw[2] - h * l[1], iw[3] - h * l[2],
                                iw[4], iw[5] + h * l[0], iw[6] + h * l[1], iw[7] - h * l[0],
                                iw[8]};
      double inv[9];
      if (Invert3(itilde, inv)) {
        double k[9];
        MatMul(iw, inv, k);
        k[0] -= 1;
        k[4] -= 1;
        k[8] -= 1;
        const double lh[3] = {l[0] * fps, l[1] * fps, l[2] * fps};
        double tau[3];
        Mul(k, lh, tau);
        for (int p = 0; p < 3; ++p) f[3 + p] += tau[p];
      }
    }
  }

  unbounded_.clear();
  bounded_.clear();
  auto add = [&](int b1, int b2, double cfm, bool bounded) -> Row& {
    std::vector<Row>& list = bounded ? bounded_ : unbounded_;
    list.emplace_back();
    Row& r = list.back();
    r.b1 = b1;
    r.b2 = b2;
    r.cfm = cfm;
    r.lo = -kInf;
    r.hi = kInf;
    r.findex = -1;
    return r;
  };
  auto pos = [&](int b) { return dBodyGetPosition(bodies_[static_cast<std::size_t>(b)].id); };
  auto rot = [&](int b, double r[9]) { RotationOf(bodies_[static_cast<std::size_t>(b)].id, r); };

  // Each joint's rows: bilateral ones to unbounded_, the rest to bounded_.
  auto hinge_rows = [&](const Hinge& hj) {
    double r1[9], r2[9], a1[3], a2[3], ax1[3], ax2[3];
    rot(hj.b1, r1);
    rot(hj.b2, r2);
    Mul(r1, hj.anchor1, a1);
    Mul(r2, hj.anchor2, a2);
    const dReal* p1 = pos(hj.b1);
    const dReal* p2 = pos(hj.b2);
    const double k = fps * world_erp;
    for (int d = 0; d < 3; ++d) {  // ball rows
      Row& r = add(hj.b1, hj.b2, world_cfm, false);
      r.j1[d] = 1;
      r.j2[d] = -1;
      // angular parts: row d of -[a1]x for body 1 and of +[a2]x for body 2
      const int e = (d + 1) % 3, g = (d + 2) % 3;
      r.j1[3 + e] = a1[g];
      r.j1[3 + g] = -a1[e];
      r.j2[3 + e] = -a2[g];
      r.j2[3 + g] = a2[e];
      r.rhs = k * (a2[d] + p2[d] - a1[d] - p1[d]);
    }
    Mul(r1, hj.axis1, ax1);
    Mul(r2, hj.axis2, ax2);
    dVector3 n{ax1[0], ax1[1], ax1[2], 0}, p, q;
    dPlaneSpace(n, p, q);
    double b[3];
    Cross(ax1, ax2, b);
    for (const dReal* u : {p, q}) {  // axis rows
      Row& r = add(hj.b1, hj.b2, world_cfm, false);
      for (int d = 0; d < 3; ++d) {
        r.j1[3 + d] = u[d];
        r.j2[3 + d] = -u[d];
      }
      const double uv[3] = {u[0], u[1], u[2]};
      r.rhs = k * Dot3(b, uv);
    }
    // The limit-or-motor row.
    const double lo = dJointGetHingeParam(hj.id, dParamLoStop);
    const double hi = dJointGetHingeParam(hj.id, dParamHiStop);
    const double fmax = dJointGetHingeParam(hj.id, dParamFMax);
    const double vel = dJointGetHingeParam(hj.id, dParamVel);
    int limit = 0;
    double limit_err = 0;
    if ((lo >= -M_PI || hi <= M_PI) && lo <= hi) {
      const double angle = dJointGetHingeAngle(hj.id);
      if (angle <= lo) {
        limit = 1;
        limit_err = angle - lo;
      } else if (angle >= hi) {
        limit = 2;
        limit_err = angle - hi;
      }
    }
    bool powered = fmax > 0;
    if (!powered && limit == 0) return;
    if (limit && lo == hi) powered = false;
    Row& r = add(hj.b1, hj.b2, world_cfm, !(limit && lo == hi));
    for (int d = 0; d < 3; ++d) {
      r.j1[3 + d] = ax1[d];
      r.j2[3 + d] = -ax1[d];
    }
    if (powered) {
      r.cfm = dJointGetHingeParam(hj.id, dParamCFM);
      if (!limit) {
        r.rhs = vel;
        r.lo = -fmax;
        r.hi = fmax;
      } else {
        // Powered at a stop: the motor's torque is applied directly (ODE's approximation).
        double fm = fmax;
        if (vel > 0 || (vel == 0 && limit == 2)) fm = -fm;
        if ((limit == 1 && vel > 0) || (limit == 2 && vel < 0))
          fm *= dJointGetHingeParam(hj.id, dParamFudgeFactor);
        for (int d = 0; d < 3; ++d) {
          force_[6 * static_cast<std::size_t>(hj.b2) + 3 + static_cast<std::size_t>(d)] +=
              fm * ax1[d];
          force_[6 * static_cast<std::size_t>(hj.b1) + 3 + static_cast<std::size_t>(d)] -=
              fm * ax1[d];
        }
      }
    }
    if (limit) {
      r.rhs = -fps * dJointGetHingeParam(hj.id, dParamStopERP) * limit_err;
      r.cfm = dJointGetHingeParam(hj.id, dParamStopCFM);
      if (lo == hi) {
        r.lo = -kInf;
        r.hi = kInf;
      } else if (limit == 1) {
        r.lo = 0;
        r.hi = kInf;
      } else {
        r.lo = -kInf;
        r.hi = 0;
      }
    }
  };
  auto fixed_rows = [&](const Fixed& fj) {
    double r1[9], ofs[3];
    rot(fj.b1, r1);
    Mul(r1, fj.offset, ofs);
    const dReal* p1 = pos(fj.b1);
    const double erp = dJointGetFixedParam(fj.id, dParamERP);
    const double cfm = dJointGetFixedParam(fj.id, dParamCFM);
    for (int d = 0; d < 3; ++d) {  // linear rows, the joint's own softness
      Row& r = add(fj.b1, fj.b2, cfm, false);
      r.j1[d] = 1;
      if (fj.b2 >= 0) {
        // row d of +[ofs]x
        const int e = (d + 1) % 3, g = (d + 2) % 3;
        r.j1[3 + e] = -ofs[g];
        r.j1[3 + g] = ofs[e];
        r.j2[d] = -1;
        r.rhs = fps * erp * (pos(fj.b2)[d] - p1[d] + ofs[d]);
      } else {
        r.rhs = fps * erp * (fj.offset[d] - p1[d]);
      }
    }
    dQuaternion qerr;
    const dReal* q1 = dBodyGetQuaternion(bodies_[static_cast<std::size_t>(fj.b1)].id);
    if (fj.b2 >= 0) {
      dQuaternion qq;
      dQMultiply1(qq, q1, dBodyGetQuaternion(bodies_[static_cast<std::size_t>(fj.b2)].id));
      dQMultiply2(qerr, qq, fj.qrel);
    } else {
      dQMultiply3(qerr, q1, fj.qrel);
    }
    if (qerr[0] < 0)
      for (int d = 1; d < 4; ++d) qerr[d] = -qerr[d];
    const double v[3] = {qerr[1], qerr[2], qerr[3]};
    double e[3];
    Mul(r1, v, e);
    for (int d = 0; d < 3; ++d) {  // angular rows, the world's softness
      Row& r = add(fj.b1, fj.b2, world_cfm, false);
      r.j1[3 + d] = 1;
      if (fj.b2 >= 0) r.j2[3 + d] = -1;
      r.rhs = fps * world_erp * 2 * e[d];
    }
  };
  auto motor_rows = [&](const Motor& mj) {
    const double fmax = dJointGetAMotorParam(mj.id, dParamFMax);
    if (!(fmax > 0)) return;
    dVector3 ax;
    if (mj.hinge >= 0) {  // the hinge's own axis, to the bit: the two rows are then one column
      double r1[9];
      rot(mj.b1, r1);
      Mul(r1, hinges_[static_cast<std::size_t>(mj.hinge)].axis1, ax);
    } else {
      dJointGetAMotorAxis(mj.id, 0, ax);
    }
    Row& r = add(mj.b1, mj.b2, dJointGetAMotorParam(mj.id, dParamCFM), true);
    for (int d = 0; d < 3; ++d) {
      r.j1[3 + d] = ax[d];
      r.j2[3 + d] = -ax[d];
    }
    r.rhs = dJointGetAMotorParam(mj.id, dParamVel);
    r.lo = -fmax;
    r.hi = fmax;
  };
  for (const auto& [kind, index] : joints_) {
    const auto i = static_cast<std::size_t>(index);
    if (kind == JointKind::kHinge) hinge_rows(hinges_[i]);
    if (kind == JointKind::kFixed) fixed_rows(fixed_[i]);
    if (kind == JointKind::kMotor) motor_rows(motors_[i]);
  }
  const double min_depth = dWorldGetContactSurfaceLayer(world_);
  const double max_vel = dWorldGetContactMaxCorrectingVel(world_);
  for (const Contact& ct : contacts_) {
    const dContact& c = ct.c;
    const int mode = c.surface.mode;
    const double erp = (mode & dContactSoftERP) ? c.surface.soft_erp : world_erp;
    const double depth = std::max(0.0, static_cast<double>(c.geom.depth) - min_depth);
    const double n[3] = {c.geom.normal[0], c.geom.normal[1], c.geom.normal[2]};
    const dReal* p1 = pos(ct.b1);
    const double c1[3] = {c.geom.pos[0] - p1[0], c.geom.pos[1] - p1[1], c.geom.pos[2] - p1[2]};
    double c2[3] = {0, 0, 0};
    if (ct.b2 >= 0) {
      const dReal* p2 = pos(ct.b2);
      for (int d = 0; d < 3; ++d) c2[d] = c.geom.pos[d] - p2[d];
    }
    auto fill = [&](Row& r, const double u[3]) {
      double t[3];
      Cross(c1, u, t);
      for (int d = 0; d < 3; ++d) {
        r.j1[d] = u[d];
        r.j1[3 + d] = t[d];
      }
      if (ct.b2 >= 0) {
        Cross(u, c2, t);
        for (int d = 0; d < 3; ++d) {
          r.j2[d] = -u[d];
          r.j2[3 + d] = t[d];
        }
      }
    };
    const std::size_t normal_row = bounded_.size();
    {
      Row& r = add(ct.b1, ct.b2, (mode & dContactSoftCFM) ? c.surface.soft_cfm : world_cfm, true);
      fill(r, n);
      r.rhs = std::min(fps * erp * depth, max_vel);
      r.lo = 0;
      r.hi = kInf;
    }
    if (c.surface.mu > 0) {
      dVector3 nn{n[0], n[1], n[2], 0}, t1, t2;
      dPlaneSpace(nn, t1, t2);
      const double mu2 = (mode & dContactMu2) ? c.surface.mu2 : c.surface.mu;
      const double mus[2] = {c.surface.mu, mu2};
      const int approx[2] = {dContactApprox1_1, dContactApprox1_2};
      const dReal* ts[2] = {t1, t2};
      for (int s = 0; s < 2; ++s) {
        if (!(mus[s] > 0)) continue;
        Row& r = add(ct.b1, ct.b2, world_cfm, true);
        const double u[3] = {ts[s][0], ts[s][1], ts[s][2]};
        fill(r, u);
        r.lo = -mus[s];
        r.hi = mus[s];
        if (mode & approx[s]) r.findex = static_cast<int>(normal_row);
      }
    }
  }

  // Scale rhs and cfm by 1/h and subtract J (v / h + M^-1 f).
  std::vector<double>& tmp = work_;
  tmp.assign(6 * nbody, 0);
  for (std::size_t i = 0; i < nbody; ++i) {
    const dReal* v = dBodyGetLinearVel(bodies_[i].id);
    const dReal* w = dBodyGetAngularVel(bodies_[i].id);
    const double* f = &force_[6 * i];
    double iwt[3];
    Mul(&inv_inertia_w_[9 * i], f + 3, iwt);
    for (int k = 0; k < 3; ++k) {
      tmp[6 * i + static_cast<std::size_t>(k)] = f[k] * bodies_[i].inv_mass + v[k] * fps;
      tmp[6 * i + 3 + static_cast<std::size_t>(k)] = iwt[k] + w[k] * fps;
    }
  }
  for (auto* list : {&unbounded_, &bounded_}) {
    for (Row& r : *list) {
      r.rhs *= fps;
      r.cfm *= fps;
      r.rhs -= Dot6(r.j1, &tmp[6 * static_cast<std::size_t>(r.b1)]);
      if (r.b2 >= 0) r.rhs -= Dot6(r.j2, &tmp[6 * static_cast<std::size_t>(r.b2)]);
    }
  }
}

void ChainStep::SolveRows() {
  const int nu = static_cast<int>(unbounded_.size());
  const int nb = static_cast<int>(bounded_.size());
  last_nu_ = nu;
  last_nb_ = nb;
  const std::size_t nbody = bodies_.size();
  // J M^-1 for each row: 12 numbers (body 1 then body 2).
  auto jm_of = [&](const Row& r, double* out) {
    for (int side = 0; side < 2; ++side) {
      const int b = side == 0 ? r.b1 : r.b2;
      const double* j = side == 0 ? r.j1 : r.j2;
      double* o = out + 6 * side;
      if (b < 0) {
        for (int k = 0; k < 6; ++k) o[k] = 0;
        continue;
      }
      const double im = bodies_[static_cast<std::size_t>(b)].inv_mass;
      for (int k = 0; k < 3; ++k) o[k] = j[k] * im;
      Mul(&inv_inertia_w_[9 * static_cast<std::size_t>(b)], j + 3, o + 3);
    }
  };
  jm_u_.resize(12 * static_cast<std::size_t>(nu));
  jm_b_.resize(12 * static_cast<std::size_t>(nb));
  for (int i = 0; i < nu; ++i) jm_of(unbounded_[static_cast<std::size_t>(i)], &jm_u_[12 * i]);
  for (int i = 0; i < nb; ++i) jm_of(bounded_[static_cast<std::size_t>(i)], &jm_b_[12 * i]);
  // A entry of rows r (its J M^-1 in jm) and s.
  auto entry = [](const Row& r, const double* jm, const Row& s) {
    double v = 0;
    if (r.b1 == s.b1) v += Dot6(jm, s.j1);
    if (r.b1 == s.b2) v += Dot6(jm, s.j2);
    if (r.b2 >= 0) {
      if (r.b2 == s.b1) v += Dot6(jm + 6, s.j1);
      if (r.b2 == s.b2) v += Dot6(jm + 6, s.j2);
    }
    return v;
  };

  // The envelope: the first U row touching each body bounds where a row's non-zeros start.
  std::vector<int>& first_u_of_body = first_u_of_body_;
  first_u_of_body.assign(nbody, nu);
  for (int i = nu - 1; i >= 0; --i) {
    const Row& r = unbounded_[static_cast<std::size_t>(i)];
    first_u_of_body[static_cast<std::size_t>(r.b1)] = i;
    if (r.b2 >= 0) first_u_of_body[static_cast<std::size_t>(r.b2)] = i;
  }
  auto first_of = [&](const Row& r) {
    int f = first_u_of_body[static_cast<std::size_t>(r.b1)];
    if (r.b2 >= 0) f = std::min(f, first_u_of_body[static_cast<std::size_t>(r.b2)]);
    return f;
  };
  first_.resize(static_cast<std::size_t>(nu));
  factor_.resize(static_cast<std::size_t>(nu) * static_cast<std::size_t>(nu));
  double* L = factor_.data();
  std::vector<double>& u = u_;
  u.resize(static_cast<std::size_t>(nu));
  for (int i = 0; i < nu; ++i) {
    const Row& ri = unbounded_[static_cast<std::size_t>(i)];
    const int fi = std::min(first_of(ri), i);
    first_[static_cast<std::size_t>(i)] = fi;
    double* li = L + static_cast<std::size_t>(i) * nu;
    for (int j = fi; j < i; ++j) {
      double s = entry(ri, &jm_u_[12 * i], unbounded_[static_cast<std::size_t>(j)]);
      const int k0 = std::max(fi, first_[static_cast<std::size_t>(j)]);
      const double* lj = L + static_cast<std::size_t>(j) * nu;
      for (int k = k0; k < j; ++k) s -= u[static_cast<std::size_t>(k)] * lj[k];
      u[static_cast<std::size_t>(j)] = s;                   // L_ij D_j
      li[j] = s / L[static_cast<std::size_t>(j) * nu + j];  // L_ij
    }
    double d = entry(ri, &jm_u_[12 * i], ri) + ri.cfm;
    for (int k = fi; k < i; ++k) d -= u[static_cast<std::size_t>(k)] * li[k];
    li[i] = d;  // D_i
  }
  auto forward = [&](double* x, int start) {  // x := L^-1 x, x zero above start
    for (int i = start; i < nu; ++i) {
      const double* li = L + static_cast<std::size_t>(i) * nu;
      double s = x[i];
      for (int k = std::max(first_[static_cast<std::size_t>(i)], start); k < i; ++k)
        s -= li[k] * x[k];
      x[i] = s;
    }
  };
  // z = L^-1 rhs_U; Y = L^-1 A_UB column by column.
  std::vector<double>& z = z_;
  z.resize(static_cast<std::size_t>(nu));
  for (int i = 0; i < nu; ++i)
    z[static_cast<std::size_t>(i)] = unbounded_[static_cast<std::size_t>(i)].rhs;
  forward(z.data(), 0);
  y_.resize(static_cast<std::size_t>(nu) * static_cast<std::size_t>(nb));
  // The U rows touching each body (CSR), for the columns of A_UB.
  body_start_.assign(nbody + 1, 0);
  for (const Row& r : unbounded_) {
    ++body_start_[static_cast<std::size_t>(r.b1) + 1];
    if (r.b2 >= 0) ++body_start_[static_cast<std::size_t>(r.b2) + 1];
  }
  for (std::size_t b = 0; b < nbody; ++b) body_start_[b + 1] += body_start_[b];
  body_rows_.resize(static_cast<std::size_t>(body_start_[nbody]));
  {
    std::vector<int>& fill = y_first_;  // reused as a cursor
    fill.assign(body_start_.begin(), body_start_.end() - 1);
    for (int i = 0; i < nu; ++i) {
      const Row& r = unbounded_[static_cast<std::size_t>(i)];
      body_rows_[static_cast<std::size_t>(fill[static_cast<std::size_t>(r.b1)]++)] = i;
      if (r.b2 >= 0)
        body_rows_[static_cast<std::size_t>(fill[static_cast<std::size_t>(r.b2)]++)] = i;
    }
  }
  y_first_.resize(static_cast<std::size_t>(nb));
  // A bounded row with the Jacobian of the one before it (a servo and its gear friction) shares
  // its column of Y and its entries of S.
  root_.resize(static_cast<std::size_t>(nb));
  for (int c = 0; c < nb; ++c) {
    const Row& rc = bounded_[static_cast<std::size_t>(c)];
    root_[static_cast<std::size_t>(c)] = c;
    if (c == 0) continue;
    const Row& rp = bounded_[static_cast<std::size_t>(c - 1)];
    if (rp.b1 == rc.b1 && rp.b2 == rc.b2 && std::memcmp(rp.j1, rc.j1, sizeof rc.j1) == 0 &&
        std::memcmp(rp.j2, rc.j2, sizeof rc.j2) == 0)
      root_[static_cast<std::size_t>(c)] = root_[static_cast<std::size_t>(c - 1)];
  }
  for (int c = 0; c < nb; ++c) {
    if (root_[static_cast<std::size_t>(c)] != c) {
      y_first_[static_cast<std::size_t>(c)] =
          y_first_[static_cast<std::size_t>(root_[static_cast<std::size_t>(c)])];
      continue;
    }
    const Row& rc = bounded_[static_cast<std::size_t>(c)];
    double* y = &y_[static_cast<std::size_t>(c) * nu];
    const int start = first_of(rc);
    y_first_[static_cast<std::size_t>(c)] = start;
    for (int i = start; i < nu; ++i) y[i] = 0;
    for (int side = 0; side < 2; ++side) {
      const int b = side == 0 ? rc.b1 : rc.b2;
      if (b < 0) continue;
      for (int k = body_start_[static_cast<std::size_t>(b)];
           k < body_start_[static_cast<std::size_t>(b) + 1]; ++k) {
        const int i = body_rows_[static_cast<std::size_t>(k)];
        const Row& ri = unbounded_[static_cast<std::size_t>(i)];
        if (side == 1 && (ri.b1 == rc.b1 || ri.b2 == rc.b1)) continue;  // done with body 1
        y[i] = entry(rc, &jm_b_[12 * c], ri);
      }
    }
    forward(y, start);
  }
  // S = A_BB - Y^T D^-1 Y and r = rhs_B - Y^T D^-1 z.
  schur_.resize(static_cast<std::size_t>(nb) * static_cast<std::size_t>(nb));
  rhs_b_.resize(static_cast<std::size_t>(nb));
  std::vector<double>& inv_d = inv_d_;
  inv_d.resize(static_cast<std::size_t>(nu));
  for (int i = 0; i < nu; ++i)
    inv_d[static_cast<std::size_t>(i)] = 1 / L[static_cast<std::size_t>(i) * nu + i];
  // Y D^-1, column by column (root columns only).
  yd_.resize(y_.size());
  for (int c = 0; c < nb; ++c) {
    if (root_[static_cast<std::size_t>(c)] != c) continue;
    const double* yc = &y_[static_cast<std::size_t>(c) * nu];
    double* ydc = &yd_[static_cast<std::size_t>(c) * nu];
    for (int i = y_first_[static_cast<std::size_t>(c)]; i < nu; ++i)
      ydc[i] = yc[i] * inv_d[static_cast<std::size_t>(i)];
  }
  // Without the rows' own CFM, S depends only on the columns: computed for root pairs.
  for (int c = 0; c < nb; ++c) {
    const int rtc = root_[static_cast<std::size_t>(c)];
    const Row& rc = bounded_[static_cast<std::size_t>(c)];
    const double* ydc = &yd_[static_cast<std::size_t>(rtc) * nu];
    const int fc = y_first_[static_cast<std::size_t>(c)];
    double rv = rc.rhs;
    const double* zc = z.data();
    for (int i = fc; i < nu; ++i) rv -= ydc[i] * zc[i];
    rhs_b_[static_cast<std::size_t>(c)] = rv;
    for (int d = c; d < nb; ++d) {
      const int rtd = root_[static_cast<std::size_t>(d)];
      double v;
      if (rtc != c || rtd != d) {
        v = schur_[static_cast<std::size_t>(std::min(rtc, rtd)) * nb + std::max(rtc, rtd)];
        if (rtc == rtd) v -= bounded_[static_cast<std::size_t>(rtc)].cfm;  // the root's diagonal
      } else {
        const Row& rd = bounded_[static_cast<std::size_t>(d)];
        v = entry(rc, &jm_b_[12 * c], rd);
        const double* yd = &y_[static_cast<std::size_t>(d) * nu];
        for (int i = std::max(fc, y_first_[static_cast<std::size_t>(d)]); i < nu; ++i)
          v -= ydc[i] * yd[i];
      }
      if (d == c) v += rc.cfm;
      schur_[static_cast<std::size_t>(c) * nb + d] = v;
      schur_[static_cast<std::size_t>(d) * nb + c] = v;
    }
  }

  // The bounded rows: Dantzig pivoting on S.
  lambda_b_.assign(static_cast<std::size_t>(nb), 0);
  double* x = lambda_b_.data();
  lo_b_.resize(static_cast<std::size_t>(nb));
  hi_b_.resize(static_cast<std::size_t>(nb));
  findex_b_.resize(static_cast<std::size_t>(nb));
  for (int i = 0; i < nb; ++i) {
    const Row& r = bounded_[static_cast<std::size_t>(i)];
    lo_b_[static_cast<std::size_t>(i)] = r.lo;
    hi_b_[static_cast<std::size_t>(i)] = r.hi;
    findex_b_[static_cast<std::size_t>(i)] = r.findex;
  }
  if (nb > 0 && !lcp_.Solve(nb, schur_.data(), rhs_b_.data(), lo_b_.data(), hi_b_.data(),
                            findex_b_.data(), x, params_.warm_start ? &lcp_start_ : nullptr))
    ++lcp_failures_;
  last_pivots_ = lcp_.last_pivots();
  // lambda_U = L^-T D^-1 (z - Y lambda_B).
  lambda_u_.assign(z.begin(), z.end());
  double* lu = lambda_u_.data();
  for (int c = 0; c < nb; ++c) {
    const double xc = x[c];
    if (xc == 0) continue;
    const double* yc = &y_[static_cast<std::size_t>(root_[static_cast<std::size_t>(c)]) * nu];
    for (int i = y_first_[static_cast<std::size_t>(c)]; i < nu; ++i) lu[i] -= yc[i] * xc;
  }
  for (int i = 0; i < nu; ++i) lu[i] *= inv_d[static_cast<std::size_t>(i)];
  for (int i = nu - 1; i >= 0; --i) {
    const double xi = lu[i];
    const double* li = L + static_cast<std::size_t>(i) * nu;
    for (int k = first_[static_cast<std::size_t>(i)]; k < i; ++k) lu[k] -= li[k] * xi;
  }
}

void ChainStep::Integrate(double h) {
  const std::size_t nbody = bodies_.size();
  std::vector<double>& cf = work_;
  cf.assign(6 * nbody, 0);
  auto apply = [&](const std::vector<Row>& rows, const std::vector<double>& lambda) {
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const Row& r = rows[i];
      const double l = lambda[i];
      double* c1 = &cf[6 * static_cast<std::size_t>(r.b1)];
      for (int k = 0; k < 6; ++k) c1[k] += r.j1[k] * l;
      if (r.b2 >= 0) {
        double* c2 = &cf[6 * static_cast<std::size_t>(r.b2)];
        for (int k = 0; k < 6; ++k) c2[k] += r.j2[k] * l;
      }
    }
  };
  apply(unbounded_, lambda_u_);
  apply(bounded_, lambda_b_);
  for (std::size_t i = 0; i < nbody; ++i) {
    const Body& b = bodies_[i];
    const double* f = &force_[6 * i];
    const double* c = &cf[6 * i];
    const dReal* v = dBodyGetLinearVel(b.id);
    const dReal* w = dBodyGetAngularVel(b.id);
    double lv[3], av[3], ta[3], dw[3];
    for (int k = 0; k < 3; ++k) {
      lv[k] = v[k] + (c[k] + f[k]) * (h * b.inv_mass);
      ta[k] = (c[3 + k] + f[3 + k]) * h;
    }
    Mul(&inv_inertia_w_[9 * i], ta, dw);
    for (int k = 0; k < 3; ++k) av[k] = w[k] + dw[k];
    const dReal* p = dBodyGetPosition(b.id);
    const double np[3] = {p[0] + h * lv[0], p[1] + h * lv[1], p[2] + h * lv[2]};
    dQuaternion q, dq;
    const dReal* q0 = dBodyGetQuaternion(b.id);
    const dVector3 avv{av[0], av[1], av[2], 0};
    dDQfromW(dq, avv, q0);
    for (int k = 0; k < 4; ++k) q[k] = q0[k] + h * dq[k];
    dBodySetLinearVel(b.id, lv[0], lv[1], lv[2]);
    dBodySetAngularVel(b.id, av[0], av[1], av[2]);
    dBodySetPosition(b.id, np[0], np[1], np[2]);
    dBodySetQuaternion(b.id, q);  // normalises it, as ODE's step does
    dBodySetForce(b.id, 0, 0, 0);
    dBodySetTorque(b.id, 0, 0, 0);
  }
}

}  // namespace ahhs::sim
