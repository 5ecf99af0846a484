// Gait learning with a chain of modules (paper section 3.2) on ODE: each module is two boxes
// joined by a servoed main hinge; modules are docked end to end by fixed joints, either rigid
// ("fixed") or soft ("damped"); four proximity rays per module; a flat arena with a low square
// wall and static cubes outside it.
//
// ODE's dWorldQuickStep draws from a process-global random seed, so Reset() calls dRandSetSeed
// and a process must never step two gait worlds in parallel threads.
#pragma once

#include <ode/ode.h>

#include <array>
#include <memory>
#include <random>
#include <vector>

#include "sim/core/chain_step.h"
#include "sim/core/constants.h"
#include "sim/core/scenario.h"

namespace ahhs::sim {

// Sensor slots of every module (the module owns all four and its one actuator).
enum GaitSensor : int { kRayUp = 0, kRayForward = 1, kRayDown = 2, kRayBack = 3, kGaitSensors = 4 };

class GaitScenario final : public Scenario {
 public:
  explicit GaitScenario(const ScenarioConfig& config, GaitConstants constants = {});
  ~GaitScenario() override;
  GaitScenario(const GaitScenario&) = delete;
  GaitScenario& operator=(const GaitScenario&) = delete;

  void Reset(std::uint64_t seed) override;
  int num_compartments() const override { return num_modules_; }
  int num_sensors() const override { return kGaitSensors; }
  int num_actuators() const override { return 1; }
  bool sensor_owned(int, int) const override { return true; }
  bool actuator_owned(int, int) const override { return true; }
  std::vector<std::pair<int, int>> Docking() const override;
  void SetActuators(int compartment, const double* values) override;
  using Scenario::Step;
  StepStatus Step(const SubstepObserver& observer) override;
  void ReadSensors(int compartment, double* values) const override;
  double HingeAngle(int compartment) const override;
  bool FollowHinge(int compartment, double angle) override;
  void Bodies(std::vector<BodyState>* bodies) const override;
  double Fitness() const override;
  double Cost() const override;
  std::int64_t tick() const override { return tick_; }
  std::int64_t total_ticks() const override { return total_ticks_; }
  double control_period() const override { return k_.control_period; }
  const std::string& error() const override { return error_; }

  // Centroid of all module bodies (equal masses), world frame, m.
  std::array<double, 3> Centroid() const;
  // For tests: place a static box (extents in m) and re-read the sensors.
  void AddObstacle(const double position[3], const double size[3]);
  // For tests: the measured docking displacement (max over docks), m; 0 for fixed docking.
  double MaxDockingGap() const;
  // For tests: fixes one half of a module to the world (to measure what the servo can lift).
  void AnchorHalf(int module, bool back_half);
  const GaitConstants& constants() const { return k_; }

 private:
  // One half of a module: a box geom on a body. With fixed docking, a module's back half and
  // the next module's front half share one rigid body (two geoms): exactly rigid, and fewer
  // bodies for the solver than a fixed joint.
  struct Part {
    dBodyID body = nullptr;
    dGeomID geom = nullptr;
  };
  struct Module {
    Part front, back;
    dJointID hinge = nullptr;
    dJointID gear = nullptr;  // gear friction, if any
    double target = 0;        // hinge target angle, rad
    // envelope.command-delay: this tick's new target and the physics step of the tick it takes
    // effect at (-1: none pending).
    double pending = 0;
    int apply_at = -1;
  };
  void ApplyTarget(Module& m, double target);
  void Build();
  void BendChain();  // envelope.start-hinge: the drawn start angles, lowest corner on the ground
  void Destroy();
  void PhysicsStep();
  bool StateIsSane() const;
  void SampleSensors();
  double CastRay(int module, const dReal* origin, const dReal* direction) const;
  static void NearCallback(void* data, dGeomID a, dGeomID b);

  GaitConstants k_;
  Envelope envelope_;
  EnvelopeDraw draw_;          // this episode's draws (all 1 and 0 for no envelope)
  std::mt19937_64 noise_rng_;  // this episode's sensor noise
  std::uint64_t seed_ = 0;     // this episode's seed (the command delays' stream)
  int num_modules_;
  DockingKind docking_;
  double step_;   // s per physics step (by docking)
  int substeps_;  // physics steps per tick
  std::int64_t total_ticks_;
  dWorldID world_ = nullptr;
  dSpaceID space_ = nullptr;
  dJointGroupID contacts_ = nullptr;
  dGeomID ray_ = nullptr;
  std::vector<Module> modules_;
  std::vector<dJointID> docks_;
  std::unique_ptr<ChainStep> chain_;  // the chain solver (GaitSolver::kChain)
  std::vector<dGeomID> scenery_;
  std::vector<double> sensors_;  // num_modules x kGaitSensors
  std::array<double, 3> start_centroid_{};
  std::int64_t tick_ = 0;
  std::string error_;
};

// Gait fitness: horizontal centroid displacement / (wall_inner / wall_score).
double GaitFitness(double displacement, const GaitConstants& k);

}  // namespace ahhs::sim
