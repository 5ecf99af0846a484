#include "sim/core/gait.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <limits>
#include <mutex>
#include <stdexcept>

namespace ahhs::sim {
namespace {

// Every geom's data pointer holds its module id + 1 (0 = scenery), so contacts and rays can
// tell a module's own geometry.
void* Tag(int module) { return reinterpret_cast<void*>(static_cast<std::intptr_t>(module + 1)); }
// Collision categories: scenery never collides with scenery, so the broad phase skips those
// pairs before testing their boxes (the near callback would drop them anyway).
constexpr unsigned long kSceneryCategory = 1, kModuleCategory = 2;
void MarkScenery(dGeomID g) {
  dGeomSetData(g, Tag(-1));
  dGeomSetCategoryBits(g, kSceneryCategory);
  dGeomSetCollideBits(g, kModuleCategory);
}
void MarkModule(dGeomID g, int module) {
  dGeomSetData(g, Tag(module));
  dGeomSetCategoryBits(g, kModuleCategory);
  dGeomSetCollideBits(g, kSceneryCategory | kModuleCategory);
}

int ModuleOf(dGeomID g) {
  return static_cast<int>(reinterpret_cast<std::intptr_t>(dGeomGetData(g))) - 1;
}

// Contact points per colliding pair. A box on the plane needs all 4 corners: with 3 a resting
// box rocks on its missing corner (the servo that must stall under three modules lifts them
// 0.33 rad), with 2 it tips; measured, not guessed.
constexpr int kMaxContacts = 4;

// ODE reports internal errors (e.g. a NaN quaternion) through these handlers and aborts the
// process when they return. Throwing instead lets Step() end the episode with an error.
struct OdeError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
[[noreturn]] void ThrowOdeError(int num, const char* msg, va_list ap) {
  char text[512];
  std::vsnprintf(text, sizeof text, msg, ap);
  throw OdeError("ODE error " + std::to_string(num) + ": " + text);
}
void IgnoreOdeMessage(int, const char*, va_list) {}

void InitOdeOnce() {
  static std::once_flag once;
  std::call_once(once, [] {
    dInitODE2(0);
    dSetErrorHandler(&ThrowOdeError);
    dSetDebugHandler(&ThrowOdeError);
    dSetMessageHandler(&IgnoreOdeMessage);
  });
}

}  // namespace

// A point given in a geom's own frame, in world coordinates (works for offset geoms).
void GeomPointToWorld(dGeomID g, const double local[3], dVector3 out) {
  const dReal* p = dGeomGetPosition(g);
  const dReal* r = dGeomGetRotation(g);  // row-major 3x4
  for (int k = 0; k < 3; ++k)
    out[k] = p[k] + r[4 * k] * local[0] + r[4 * k + 1] * local[1] + r[4 * k + 2] * local[2];
}
void GeomVectorToWorld(dGeomID g, const double local[3], dVector3 out) {
  const dReal* r = dGeomGetRotation(g);
  for (int k = 0; k < 3; ++k)
    out[k] = r[4 * k] * local[0] + r[4 * k + 1] * local[1] + r[4 * k + 2] * local[2];
}

double GaitFitness(double displacement, const GaitConstants& k) {
  return displacement / (k.wall_inner / k.fitness_wall_score);
}

GaitScenario::GaitScenario(const ScenarioConfig& config, GaitConstants constants)
    : k_(constants),
      envelope_(config.envelope),
      num_modules_(config.num_modules),
      docking_(config.docking),
      step_(docking_ == DockingKind::kDamped ? k_.physics_step_damped : k_.physics_step_fixed),
      substeps_(static_cast<int>(std::lround(k_.control_period / step_))) {
  InitOdeOnce();
  total_ticks_ = EpisodeTicks(config.duration, k_.control_period,
                              EpisodeTicks(k_.duration, k_.control_period, 0));
  Reset(0);
}

GaitScenario::~GaitScenario() { Destroy(); }

void GaitScenario::Destroy() {
  if (ray_) dGeomDestroy(ray_);
  if (contacts_) dJointGroupDestroy(contacts_);
  if (space_) dSpaceDestroy(space_);  // destroys the geoms in it
  chain_.reset();
  if (world_) dWorldDestroy(world_);  // destroys bodies and joints
  ray_ = nullptr;
  contacts_ = nullptr;
  space_ = nullptr;
  world_ = nullptr;
  modules_.clear();
  docks_.clear();
  scenery_.clear();
}

void GaitScenario::Reset(std::uint64_t seed) {
  // A fresh world every episode, and ODE's global solver seed from the episode seed: the same
  // seed and commands give the same bits.
  Destroy();
  dRandSetSeed(static_cast<unsigned long>(seed));
  draw_ = DrawEnvelope(envelope_, seed, num_modules_);
  seed_ = seed;
  noise_rng_.seed(SensorNoiseSeed(seed));
  Build();
  tick_ = 0;
  error_.clear();
  start_centroid_ = Centroid();
  SampleSensors();
}

void GaitScenario::Build() {
  world_ = dWorldCreate();
  dWorldSetGravity(world_, 0, 0, -k_.gravity);
  dWorldSetQuickStepNumIterations(world_, k_.solver_iterations);
  dWorldSetQuickStepW(world_, docking_ == DockingKind::kFixed ? k_.solver_relaxation_fixed
                                                              : k_.solver_relaxation_damped);
  const int rest_steps = static_cast<int>(std::lround(k_.rest_time / step_));
  if (rest_steps > 0 && k_.solver != GaitSolver::kChain) {
    dWorldSetAutoDisableFlag(world_, 1);
    dWorldSetAutoDisableLinearThreshold(world_, k_.rest_linear_speed);
    dWorldSetAutoDisableAngularThreshold(world_, k_.rest_angular_speed);
    dWorldSetAutoDisableSteps(world_, rest_steps);
    dWorldSetAutoDisableTime(world_, 0);
    dWorldSetAutoDisableAverageSamplesCount(world_, 1);
  }
  dWorldSetERP(world_, k_.world_erp);
  dWorldSetCFM(world_, k_.world_cfm);
  space_ = dSimpleSpaceCreate(nullptr);
  contacts_ = dJointGroupCreate(0);

  // Scenery: ground, the square wall (inner faces at +-wall_inner), 8 cubes outside it.
  scenery_.push_back(dCreatePlane(space_, 0, 0, 1, 0));
  const double w = k_.wall_inner, t = k_.wall_thickness, h = k_.wall_height;
  const double len = 2 * (w + t);
  const double walls[4][6] = {{0, w + t / 2, h / 2, len, t, h},
                              {0, -(w + t / 2), h / 2, len, t, h},
                              {w + t / 2, 0, h / 2, t, len, h},
                              {-(w + t / 2), 0, h / 2, t, len, h}};
  for (const auto& b : walls) {
    dGeomID g = dCreateBox(space_, b[3], b[4], b[5]);
    dGeomSetPosition(g, b[0], b[1], b[2]);
    scenery_.push_back(g);
  }
  const double c = k_.cube_size;
  const double cubes[8][2] = {{1.5, 0},   {-1.5, 0},   {0, 1.5},    {0, -1.5},
                              {1.1, 1.1}, {-1.1, 1.1}, {1.1, -1.1}, {-1.1, -1.1}};
  for (const auto& p : cubes) {
    dGeomID g = dCreateBox(space_, c, c, c);
    dGeomSetPosition(g, p[0], p[1], c / 2);
    scenery_.push_back(g);
  }
  for (dGeomID g : scenery_) MarkScenery(g);

  // Modules: a straight chain along +x centred on the origin, module 0 in front (largest x),
  // lying flat, hinges at 0. Half i.f is module i's front half, i.b its back half.
  const double s = k_.module_size;
  const double half_mass = k_.module_mass / 2;
  modules_.resize(static_cast<std::size_t>(num_modules_));
  auto centre_of = [&](int i) { return ((num_modules_ - 1) / 2.0 - i) * s; };
  // The envelope's start pose: the chain turned by `heading` about z and moved by the offsets.
  // Without them nothing is transformed (the same bits as without an envelope).
  const bool posed = envelope_.start_heading > 0 || envelope_.start_offset > 0;
  const double ch = std::cos(draw_.heading), sh = std::sin(draw_.heading);
  auto place = [&](double x, double y, double z, dReal* out) {
    out[0] = posed ? ch * x - sh * y + draw_.offset_x : x;
    out[1] = posed ? sh * x + ch * y + draw_.offset_y : y;
    out[2] = z;
  };
  std::vector<std::pair<dBodyID, double>> chain_x;  // each body's x along the unposed chain
  auto add_geom = [&](int module, dBodyID body, double x) {
    dGeomID g = dCreateBox(space_, s / 2, s, s);
    dGeomSetBody(g, body);
    double body_x = 0;
    for (const auto& [b, bx] : chain_x)
      if (b == body) body_x = bx;
    dGeomSetOffsetPosition(g, x - body_x, 0, 0);
    MarkModule(g, module);
    return g;
  };
  auto make_body = [&](double x, double mass, double length) {
    dBodyID body = dBodyCreate(world_);
    dReal p[3];
    place(x, 0, s / 2, p);
    dBodySetPosition(body, p[0], p[1], p[2]);
    if (posed) {
      dQuaternion q;
      dQFromAxisAndAngle(q, 0, 0, 1, draw_.heading);
      dBodySetQuaternion(body, q);
    }
    dMass m;
    dMassSetBoxTotal(&m, mass, length, s, s);
    dBodySetMass(body, &m);
    chain_x.emplace_back(body, x);
    return body;
  };
  auto mass_of = [&](int i) { return half_mass * draw_.mass_scale[static_cast<std::size_t>(i)]; };
  const bool rigid = docking_ == DockingKind::kFixed;
  for (int i = 0; i < num_modules_; ++i) {
    Module& m = modules_[static_cast<std::size_t>(i)];
    const double front_x = centre_of(i) + s / 4, back_x = centre_of(i) - s / 4;
    if (rigid && i > 0) {
      // Shares the body made with the previous module's back half (centred on the dock face).
      m.front.body = modules_[static_cast<std::size_t>(i - 1)].back.body;
    } else {
      m.front.body = make_body(front_x, mass_of(i), s / 2);
    }
    m.front.geom = add_geom(i, m.front.body, front_x);
    if (rigid && i + 1 < num_modules_) {
      m.back.body = make_body(centre_of(i) - s / 2, mass_of(i) + mass_of(i + 1),
                              s);  // back_i + front_{i+1}
    } else {
      m.back.body = make_body(back_x, mass_of(i), s / 2);
    }
    m.back.geom = add_geom(i, m.back.body, back_x);
    m.hinge = dJointCreateHinge(world_, nullptr);
    dJointAttach(m.hinge, m.front.body, m.back.body);
    dReal anchor[3];
    place(centre_of(i), 0, s / 2, anchor);
    dJointSetHingeAnchor(m.hinge, anchor[0], anchor[1], anchor[2]);
    if (posed)
      dJointSetHingeAxis(m.hinge, -sh, ch, 0);
    else
      dJointSetHingeAxis(m.hinge, 0, 1, 0);
    dJointSetHingeParam(m.hinge, dParamLoStop, -k_.hinge_range);
    dJointSetHingeParam(m.hinge, dParamHiStop, k_.hinge_range);
    dJointSetHingeParam(m.hinge, dParamFMax,
                        k_.servo_max_torque * draw_.torque_scale[static_cast<std::size_t>(i)]);
    dJointSetHingeParam(m.hinge, dParamVel, 0);
    if (k_.servo_gear_friction > 0) {
      // Gear friction: an angular motor about the hinge axis (fixed in the front half) that
      // holds zero relative speed with at most the friction torque. Back-driving the hinge takes
      // that much torque; the servo overcomes it when it moves.
      dJointID gear = dJointCreateAMotor(world_, nullptr);
      dJointAttach(gear, m.front.body, m.back.body);
      dJointSetAMotorNumAxes(gear, 1);
      dJointSetAMotorAxis(gear, 0, 1, 0, 1, 0);
      dJointSetAMotorParam(gear, dParamVel, 0);
      dJointSetAMotorParam(gear, dParamFMax, k_.servo_gear_friction);
      m.gear = gear;
    }
  }
  // Damped docking: module i's back half to module i+1's front half by a soft fixed joint.
  if (!rigid) {
    for (int i = 0; i + 1 < num_modules_; ++i) {
      dJointID dock = dJointCreateFixed(world_, nullptr);
      dJointAttach(dock, modules_[static_cast<std::size_t>(i)].back.body,
                   modules_[static_cast<std::size_t>(i + 1)].front.body);
      dJointSetFixed(dock);
      // Spring-damper as a soft constraint: ERP = hk / (hk + c), CFM = 1 / (hk + c).
      const double hk = step_ * k_.dock_stiffness;
      dJointSetFixedParam(dock, dParamERP, hk / (hk + k_.dock_damping));
      dJointSetFixedParam(dock, dParamCFM, 1.0 / (hk + k_.dock_damping));
      docks_.push_back(dock);
    }
  }
  if (envelope_.start_hinge > 0) BendChain();
  if (k_.solver == GaitSolver::kChain) {
    ChainStep::Params rest;
    rest.rest_linear_speed = k_.rest_linear_speed;
    rest.rest_angular_speed = k_.rest_angular_speed;
    rest.rest_steps = rest_steps;
    rest.warm_start = k_.chain_warm_start;
    chain_ = std::make_unique<ChainStep>(world_, rest);
    for (const Module& m : modules_) {  // bodies in chain order, each once
      if (&m == &modules_.front() || !rigid) chain_->AddBody(m.front.body);
      chain_->AddBody(m.back.body);
    }
    for (std::size_t i = 0; i < modules_.size(); ++i) {
      chain_->AddHinge(modules_[i].hinge);
      if (modules_[i].gear) chain_->AddAngularMotor(modules_[i].gear);
      if (i < docks_.size()) chain_->AddFixed(docks_[i]);
    }
  }
  ray_ = dCreateRay(nullptr, k_.sensor_range);
  sensors_.assign(static_cast<std::size_t>(num_modules_ * kGaitSensors), 0.0);
}

void GaitScenario::BendChain() {
  // The joints were made with the chain flat, so a hinge's zero stays flat. Hinge by hinge from
  // the front, every body behind it turns about its (current) anchor and axis by the drawn angle.
  std::vector<dBodyID> bodies;  // chain order, each once
  for (const Module& m : modules_)
    for (dBodyID b : {m.front.body, m.back.body})
      if (bodies.empty() || bodies.back() != b) bodies.push_back(b);
  std::size_t behind = 0;  // the first body behind hinge i
  for (std::size_t i = 0; i < modules_.size(); ++i) {
    Module& m = modules_[i];
    while (bodies[behind] != m.back.body) ++behind;
    const double angle = draw_.hinge[i];
    dVector3 a, u;
    dJointGetHingeAnchor(m.hinge, a);
    dJointGetHingeAxis(m.hinge, u);
    // ODE's hinge angle grows as body 2 (the back half) turns by minus the angle about the axis.
    dMatrix3 r;
    dRFromAxisAndAngle(r, u[0], u[1], u[2], -angle);
    dQuaternion qr;
    dQFromAxisAndAngle(qr, u[0], u[1], u[2], -angle);
    for (std::size_t k = behind; k < bodies.size(); ++k) {
      const dReal* p = dBodyGetPosition(bodies[k]);
      const double d[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
      double q[3];
      for (int row = 0; row < 3; ++row)
        q[row] = a[row] + r[4 * row] * d[0] + r[4 * row + 1] * d[1] + r[4 * row + 2] * d[2];
      dBodySetPosition(bodies[k], q[0], q[1], q[2]);
      dQuaternion turned;
      dQMultiply0(turned, qr, dBodyGetQuaternion(bodies[k]));
      dBodySetQuaternion(bodies[k], turned);
    }
    m.target = angle;  // the servo holds the start pose until the controller commands
  }
  // Put the bent chain down: its lowest corner on the ground.
  double lowest = INFINITY;
  for (const Module& m : modules_)
    for (dGeomID g : {m.front.geom, m.back.geom}) {
      dReal aabb[6];
      dGeomGetAABB(g, aabb);
      lowest = std::min(lowest, static_cast<double>(aabb[4]));
    }
  for (dBodyID b : bodies) {
    const dReal* p = dBodyGetPosition(b);
    dBodySetPosition(b, p[0], p[1], p[2] - lowest);
  }
}

std::vector<std::pair<int, int>> GaitScenario::Docking() const {
  return ChainDocking(num_modules_);
}

void GaitScenario::SetActuators(int compartment, const double* values) {
  if (!std::isfinite(values[0])) return;  // never let a bad value into the physics
  Module& m = modules_[static_cast<std::size_t>(compartment)];
  const double target = k_.hinge_range * std::clamp(values[0], -1.0, 1.0);
  if (envelope_.command_delay > 0) {  // it takes effect during the next Step()
    // envelope.command-delay: the new target waits 0 .. floor(w x substeps) physics steps.
    const int most = static_cast<int>(std::floor(envelope_.command_delay * substeps_));
    m.pending = target;
    m.apply_at = CommandDelaySteps(seed_, tick_, compartment, most);
    return;
  }
  ApplyTarget(m, target);
}

void GaitScenario::ApplyTarget(Module& m, double target) {
  if (target == m.target) return;
  m.target = target;
  // A new target wakes a resting organism (ODE then wakes every body connected to this one).
  dBodyEnable(m.front.body);
  dBodyEnable(m.back.body);
}

bool GaitScenario::FollowHinge(int compartment, double angle) {
  if (!std::isfinite(angle)) return true;
  const double range = k_.hinge_range;
  SetActuators(compartment, std::array<double, 1>{std::clamp(angle, -range, range) / range}.data());
  return true;
}

void GaitScenario::NearCallback(void* data, dGeomID a, dGeomID b) {
  auto* self = static_cast<GaitScenario*>(data);
  const int ma = ModuleOf(a), mb = ModuleOf(b);
  if (ma < 0 && mb < 0) return;  // scenery never collides with scenery
  if (ma == mb) return;          // the two halves of one module
  dBodyID ba = dGeomGetBody(a), bb = dGeomGetBody(b);
  if (ba == bb) return;  // two geoms of one rigid body
  if (ba && bb && dAreConnectedExcluding(ba, bb, dJointTypeContact)) return;  // docked halves
  dContact contact[kMaxContacts];
  const int n = dCollide(a, b, kMaxContacts, &contact[0].geom, sizeof(dContact));
  for (int i = 0; i < n; ++i) {
    contact[i].surface.mode = dContactApprox1 | dContactSoftERP | dContactSoftCFM;
    contact[i].surface.mu = self->k_.friction * self->draw_.friction_scale;
    contact[i].surface.soft_erp = self->k_.contact_erp;
    contact[i].surface.soft_cfm = self->k_.contact_cfm;
    if (self->chain_) {
      self->chain_->AddContact(contact[i], ba, bb);
      continue;
    }
    dJointID j = dJointCreateContact(self->world_, self->contacts_, &contact[i]);
    dJointAttach(j, ba, bb);
  }
}

void GaitScenario::PhysicsStep() {
  // Servo: commanded hinge speed proportional to the angle error, capped; torque capped.
  for (std::size_t i = 0; i < modules_.size(); ++i) {
    Module& m = modules_[i];
    const double error = m.target - dJointGetHingeAngle(m.hinge);
    const double cap = k_.servo_max_speed * draw_.speed_scale[i];
    dJointSetHingeParam(m.hinge, dParamVel, std::clamp(k_.servo_gain * error, -cap, cap));
  }
  if (chain_) {
    if (chain_->Resting()) return;  // nothing moves until a target changes
    dSpaceCollide(space_, this, &GaitScenario::NearCallback);
    chain_->Step(step_);
    return;
  }
  dSpaceCollide(space_, this, &GaitScenario::NearCallback);
  if (k_.solver == GaitSolver::kQuickStep)
    dWorldQuickStep(world_, step_);
  else
    dWorldStep(world_, step_);
  dJointGroupEmpty(contacts_);
}

bool GaitScenario::StateIsSane() const {
  for (const auto& m : modules_) {
    for (dBodyID b : {m.front.body, m.back.body}) {
      const dReal* p = dBodyGetPosition(b);
      const dReal* v = dBodyGetLinearVel(b);
      const dReal* w = dBodyGetAngularVel(b);
      for (int k = 0; k < 3; ++k) {
        if (!std::isfinite(p[k]) || !std::isfinite(v[k]) || !std::isfinite(w[k])) return false;
        if (std::fabs(p[k]) > 1e3 || std::fabs(v[k]) > 1e3 || std::fabs(w[k]) > 1e4) return false;
      }
    }
  }
  return true;
}

StepStatus GaitScenario::Step(const SubstepObserver& observer) {
  if (!error_.empty()) return StepStatus::kFailed;
  if (tick_ >= total_ticks_) return StepStatus::kFinished;
  for (int i = 0; i < substeps_; ++i) {
    for (Module& module : modules_) {  // envelope.command-delay: targets due at this step
      if (module.apply_at == i) {
        module.apply_at = -1;
        ApplyTarget(module, module.pending);
      }
    }
    // A blown-up simulation ends the episode with an error, never with a bogus fitness. The
    // state is checked after every physics step, before ODE could step on a non-finite value
    // (Debian's ODE aborts the process on some of those).
    try {
      PhysicsStep();
    } catch (const OdeError& e) {
      dJointGroupEmpty(contacts_);
      error_ = "physics blew up at tick " + std::to_string(tick_) + " (" + e.what() + ")";
      return StepStatus::kFailed;
    }
    if (!StateIsSane()) {
      error_ = "physics blew up at tick " + std::to_string(tick_) +
               " (a body's position or velocity is non-finite or runaway)";
      return StepStatus::kFailed;
    }
    if (chain_ && chain_->lcp_failures() > 0) {  // a step's forces are not a solution
      error_ = "physics failed at tick " + std::to_string(tick_) +
               " (the chain solver's pivoting did not finish)";
      return StepStatus::kFailed;
    }
    if (observer)
      observer((static_cast<double>(tick_) + (i + 1.0) / substeps_) * k_.control_period);
  }
  ++tick_;
  SampleSensors();
  return tick_ >= total_ticks_ ? StepStatus::kFinished : StepStatus::kRunning;
}

namespace {
struct RayHit {
  int own_module;
  double nearest;
};
void RayCallback(void* data, dGeomID ray, dGeomID other) {
  auto* hit = static_cast<RayHit*>(data);
  if (ModuleOf(other) == hit->own_module) return;  // a module's rays ignore its own geometry
  dContactGeom c[4];
  const int n = dCollide(ray, other, 4, c, sizeof(dContactGeom));
  for (int i = 0; i < n; ++i)
    hit->nearest = std::min(hit->nearest, static_cast<double>(c[i].depth));
}
}  // namespace

double GaitScenario::CastRay(int module, const dReal* origin, const dReal* direction) const {
  dGeomRaySet(ray_, origin[0], origin[1], origin[2], direction[0], direction[1], direction[2]);
  RayHit hit{module, std::numeric_limits<double>::infinity()};
  dSpaceCollide2(ray_, reinterpret_cast<dGeomID>(space_), &hit, &RayCallback);
  return hit.nearest;
}

void GaitScenario::SampleSensors() {
  // Rays start 1 mm inside the face they look out of (own geometry is ignored), so a neighbour
  // touching that face reads ~1. Up and down look out of the front half's top and bottom.
  const double s = k_.module_size;
  const double inset = 0.001;
  const double range = k_.sensor_range;
  for (int i = 0; i < num_modules_; ++i) {
    const Module& m = modules_[static_cast<std::size_t>(i)];
    struct Face {
      dGeomID geom;
      double local_point[3];
      double local_dir[3];
    };
    const Face faces[kGaitSensors] = {
        {m.front.geom, {0, 0, s / 2 - inset}, {0, 0, 1}},
        {m.front.geom, {s / 4 - inset, 0, 0}, {1, 0, 0}},
        {m.front.geom, {0, 0, -s / 2 + inset}, {0, 0, -1}},
        {m.back.geom, {-s / 4 + inset, 0, 0}, {-1, 0, 0}},
    };
    for (int j = 0; j < kGaitSensors; ++j) {
      const Face& f = faces[j];
      dVector3 origin, dir;
      GeomPointToWorld(f.geom, f.local_point, origin);
      GeomVectorToWorld(f.geom, f.local_dir, dir);
      const double d = std::max(0.0, CastRay(i, origin, dir) - inset);
      double v = d < range ? 1.0 - d / range : 0.0;
      if (envelope_.sensor_noise > 0) {  // module by module, in sensor order
        const double u = static_cast<double>(noise_rng_() >> 11) * 0x1.0p-53;
        v = std::clamp(v + (2 * u - 1) * envelope_.sensor_noise, 0.0, 1.0);
      }
      sensors_[static_cast<std::size_t>(i * kGaitSensors + j)] = v;
    }
  }
}

void GaitScenario::ReadSensors(int compartment, double* values) const {
  for (int j = 0; j < kGaitSensors; ++j)
    values[j] = sensors_[static_cast<std::size_t>(compartment * kGaitSensors + j)];
}

double GaitScenario::HingeAngle(int compartment) const {
  return dJointGetHingeAngle(modules_[static_cast<std::size_t>(compartment)].hinge);
}

std::array<double, 3> GaitScenario::Centroid() const {
  std::array<double, 3> c{0, 0, 0};
  for (const auto& m : modules_) {
    for (dGeomID g : {m.front.geom, m.back.geom}) {  // equal masses: the mean of the halves
      const dReal* p = dGeomGetPosition(g);
      for (int k = 0; k < 3; ++k) c[static_cast<std::size_t>(k)] += p[k];
    }
  }
  for (double& v : c) v /= 2.0 * num_modules_;
  return c;
}

double GaitScenario::Cost() const {
  const auto c = Centroid();
  return std::hypot(c[0] - start_centroid_[0], c[1] - start_centroid_[1]);
}

double GaitScenario::Fitness() const { return GaitFitness(Cost(), k_); }

void GaitScenario::Bodies(std::vector<BodyState>* bodies) const {
  bodies->clear();
  const double s = k_.module_size;
  for (int i = 0; i < num_modules_; ++i) {
    const Module& m = modules_[static_cast<std::size_t>(i)];
    for (dGeomID g : {m.front.geom, m.back.geom}) {
      BodyState st;
      st.module = i;
      const dReal* p = dGeomGetPosition(g);
      dQuaternion q;
      dGeomGetQuaternion(g, q);
      for (int k = 0; k < 3; ++k) st.position[k] = p[k];
      for (int k = 0; k < 4; ++k) st.quaternion[k] = q[k];
      st.size[0] = s / 2;
      st.size[1] = s;
      st.size[2] = s;
      st.mass = k_.module_mass / 2;
      bodies->push_back(st);
    }
  }
  for (dGeomID g : scenery_) {
    if (dGeomGetClass(g) != dBoxClass) continue;  // the ground plane is implied
    BodyState st;
    const dReal* p = dGeomGetPosition(g);
    dVector3 size;
    dGeomBoxGetLengths(g, size);
    for (int k = 0; k < 3; ++k) {
      st.position[k] = p[k];
      st.size[k] = size[k];
    }
    bodies->push_back(st);
  }
}

void GaitScenario::AnchorHalf(int module, bool back_half) {
  const Module& m = modules_[static_cast<std::size_t>(module)];
  dJointID anchor = dJointCreateFixed(world_, nullptr);
  dJointAttach(anchor, back_half ? m.back.body : m.front.body, nullptr);
  dJointSetFixed(anchor);
  if (chain_) chain_->AddFixed(anchor);
}

void GaitScenario::AddObstacle(const double position[3], const double size[3]) {
  dGeomID g = dCreateBox(space_, size[0], size[1], size[2]);
  dGeomSetPosition(g, position[0], position[1], position[2]);
  MarkScenery(g);
  scenery_.push_back(g);
  SampleSensors();
}

double GaitScenario::MaxDockingGap() const {
  // Distance between where the two docked faces' centres are: 0 for a rigid dock.
  double gap = 0;
  const double s = k_.module_size;
  for (int i = 0; i + 1 < num_modules_; ++i) {
    dVector3 a, b;
    const double back_face[3] = {-s / 4, 0, 0}, front_face[3] = {s / 4, 0, 0};
    GeomPointToWorld(modules_[static_cast<std::size_t>(i)].back.geom, back_face, a);
    GeomPointToWorld(modules_[static_cast<std::size_t>(i + 1)].front.geom, front_face, b);
    gap = std::max(gap, std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                                  (a[2] - b[2]) * (a[2] - b[2])));
  }
  return gap;
}

}  // namespace ahhs::sim
