#include "sim/core/chain_step.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "sim/core/drive.h"
#include "sim/core/gait.h"

using namespace ahhs::sim;

namespace {

// A chain of box halves on the ground, built the same way twice: hinges with servo, stops and
// a gear-friction motor between halves 2i and 2i+1, soft fixed docks between 2i+1 and 2i+2,
// every half touching the plane. Velocities from a seeded generator.
struct World {
  dWorldID world = nullptr;
  dSpaceID space = nullptr;
  dJointGroupID contacts = nullptr;
  std::vector<dBodyID> bodies;
  std::vector<dGeomID> geoms;
  std::unique_ptr<ChainStep> chain;

  World(int halves, std::uint64_t seed, double speed, double hinge_angle, bool use_chain) {
    dInitODE2(0);
    world = dWorldCreate();
    dWorldSetGravity(world, 0, 0, -9.81);
    dWorldSetERP(world, 0.2);
    dWorldSetCFM(world, 1e-9);
    space = dSimpleSpaceCreate(nullptr);
    contacts = dJointGroupCreate(0);
    dCreatePlane(space, 0, 0, 1, 0);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    const double h = 0.00625, k = 4000, c = 40;
    for (int i = 0; i < halves; ++i) {
      dBodyID b = dBodyCreate(world);
      dMass m;
      dMassSetBoxTotal(&m, 0.25, 0.05, 0.1, 0.1);
      dBodySetMass(b, &m);
      dBodySetPosition(b, -0.05 * i, 0.002 * u(rng), 0.0495 + 0.001 * u(rng));
      dQuaternion q;
      dQFromAxisAndAngle(q, u(rng), u(rng), 1, 0.02 * u(rng));
      dBodySetQuaternion(b, q);
      dBodySetLinearVel(b, speed * u(rng), speed * u(rng), speed * u(rng));
      dBodySetAngularVel(b, 10 * speed * u(rng), 10 * speed * u(rng), 10 * speed * u(rng));
      dGeomID g = dCreateBox(space, 0.05, 0.1, 0.1);
      dGeomSetBody(g, b);
      bodies.push_back(b);
      geoms.push_back(g);
    }
    if (use_chain) chain = std::make_unique<ChainStep>(world, ChainStep::Params{});
    if (chain)
      for (dBodyID b : bodies) chain->AddBody(b);
    for (int i = 0; i + 1 < halves; ++i) {
      dBodyID a = bodies[static_cast<std::size_t>(i)], b = bodies[static_cast<std::size_t>(i + 1)];
      const dReal* pa = dBodyGetPosition(a);
      const dReal* pb = dBodyGetPosition(b);
      if (i % 2 == 0) {
        dJointID hinge = dJointCreateHinge(world, nullptr);
        dJointAttach(hinge, a, b);
        dJointSetHingeAnchor(hinge, (pa[0] + pb[0]) / 2, (pa[1] + pb[1]) / 2, 0.05);
        dJointSetHingeAxis(hinge, 0, 1, 0);
        dJointSetHingeParam(hinge, dParamLoStop, -hinge_angle);
        dJointSetHingeParam(hinge, dParamHiStop, hinge_angle);
        dJointSetHingeParam(hinge, dParamFMax, 2.2);
        dJointSetHingeParam(hinge, dParamVel, 3 * u(rng));
        dJointID gear = dJointCreateAMotor(world, nullptr);
        dJointAttach(gear, a, b);
        dJointSetAMotorNumAxes(gear, 1);
        dJointSetAMotorAxis(gear, 0, 1, 0, 1, 0);
        dJointSetAMotorParam(gear, dParamVel, 0);
        dJointSetAMotorParam(gear, dParamFMax, 0.1);
        if (chain) {
          chain->AddHinge(hinge);
          chain->AddAngularMotor(gear);
        }
      } else {
        dJointID dock = dJointCreateFixed(world, nullptr);
        dJointAttach(dock, a, b);
        dJointSetFixed(dock);
        dJointSetFixedParam(dock, dParamERP, h * k / (h * k + c));
        dJointSetFixedParam(dock, dParamCFM, 1 / (h * k + c));
        if (chain) chain->AddFixed(dock);
      }
    }
  }
  ~World() {
    dJointGroupDestroy(contacts);
    dSpaceDestroy(space);
    dWorldDestroy(world);
  }

  int Collide(double mu) {
    int n = 0;
    for (dGeomID g : geoms) {
      dContact c[4];
      const int k = dCollide(g, dSpaceGetGeom(space, 0), 4, &c[0].geom, sizeof(dContact));
      for (int i = 0; i < k; ++i, ++n) {
        c[i].surface.mode = dContactApprox1 | dContactSoftERP | dContactSoftCFM;
        c[i].surface.mu = mu;
        c[i].surface.soft_erp = 0.2;
        c[i].surface.soft_cfm = 1e-5;
        if (chain) {
          chain->AddContact(c[i], dGeomGetBody(g), nullptr);
        } else {
          dJointID j = dJointCreateContact(world, contacts, &c[i]);
          dJointAttach(j, dGeomGetBody(g), nullptr);
        }
      }
    }
    return n;
  }
  void Step(double h, double mu) {
    Collide(mu);
    if (chain) {
      chain->Step(h);
    } else {
      dWorldStep(world, h);
      dJointGroupEmpty(contacts);
    }
  }
};

double MaxDifference(const World& a, const World& b) {
  double worst = 0;
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    const dReal* v[2][4] = {{dBodyGetPosition(a.bodies[i]), dBodyGetLinearVel(a.bodies[i]),
                             dBodyGetAngularVel(a.bodies[i]), dBodyGetQuaternion(a.bodies[i])},
                            {dBodyGetPosition(b.bodies[i]), dBodyGetLinearVel(b.bodies[i]),
                             dBodyGetAngularVel(b.bodies[i]), dBodyGetQuaternion(b.bodies[i])}};
    for (int q = 0; q < 4; ++q)
      for (int k = 0; k < (q == 3 ? 4 : 3); ++k)
        worst = std::max(worst, std::fabs(v[0][q][k] - v[1][q][k]));
  }
  return worst;
}

}  // namespace

TEST_CASE("chain step: one step gives dWorldStep's answer while friction holds", "[sim][chain]") {
  // Same rows, same unique solution: a damped chain of 10 halves with contacts, servos moving,
  // friction sticking (slow bodies), from 20 random states.
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    World ode(10, seed, 0.005, M_PI / 2, false), chain(10, seed, 0.005, M_PI / 2, true);
    REQUIRE(MaxDifference(ode, chain) == 0);
    ode.Step(0.00625, 0.8);
    chain.Step(0.00625, 0.8);
    INFO("seed " << seed << ": " << chain.chain->last_bilateral_rows() << " bilateral, "
                 << chain.chain->last_bounded_rows() << " bounded rows, "
                 << chain.chain->last_pivots() << " pivots");
    CHECK(chain.chain->last_bilateral_rows() == 49);
    CHECK(chain.chain->lcp_failures() == 0);
    CHECK(MaxDifference(ode, chain) < 1e-10);
  }
}

TEST_CASE("chain step: a hinge at its stop, powered into it and away from it", "[sim][chain]") {
  // Stops at 0: every hinge sits on one of them, some servos push into it, some away.
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    World ode(6, seed, 0.005, 0.0, false), chain(6, seed, 0.005, 0.0, true);
    ode.Step(0.00625, 0.8);
    chain.Step(0.00625, 0.8);
    INFO("seed " << seed);
    CHECK(MaxDifference(ode, chain) < 1e-10);
  }
}

TEST_CASE("chain step: many steps stay close to dWorldStep's", "[sim][chain]") {
  // Over 160 steps (1 s) the two stay within rounding's growth for a chain that settles.
  World ode(10, 7, 0.005, M_PI / 2, false), chain(10, 7, 0.005, M_PI / 2, true);
  for (int i = 0; i < 160; ++i) {
    ode.Step(0.00625, 0.8);
    chain.Step(0.00625, 0.8);
  }
  CHECK(MaxDifference(ode, chain) < 1e-6);
}

TEST_CASE("chain step: a 60-s wave walks as far as with dWorldStep when not chaotic",
          "[sim][chain]") {
  // gait_test.cc runs every check of the gait with the chain solver (the default); this one
  // compares it with dWorldStep side by side on a whole episode.
  for (DockingKind j : {DockingKind::kDamped, DockingKind::kFixed}) {
    ScenarioConfig c;
    c.kind = ScenarioKind::kGait;
    c.docking = j;
    GaitScenario chain(c);
    GaitConstants dantzig;
    dantzig.solver = GaitSolver::kDantzig;
    GaitScenario ode(c, dantzig);
    for (GaitScenario* g : {&chain, &ode}) {
      g->Reset(1);
      double a[1];
      while (true) {
        for (int m = 0; m < 5; ++m) {
          DriveCommand(DriveKind::kWave, *g, m, a);
          g->SetActuators(m, a);
        }
        if (g->Step() != StepStatus::kRunning) break;
      }
    }
    INFO(DockingName(j) << " wave: chain " << chain.Fitness() << ", dWorldStep " << ode.Fitness());
    CHECK(chain.Fitness() > 0.3);
    // The rigid chain's wave is not chaotic: the same distance. The damped one's is: rounding
    // alone moves it (1.0 to 1.6 by the order of the joints' rows), so only "it walks".
    if (j == DockingKind::kFixed) CHECK(chain.Fitness() == Approx(ode.Fitness()).epsilon(0.01));
  }
}
