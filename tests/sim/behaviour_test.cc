// The behaviour summary against the reference drives, whose behaviour is known.
#include "sim/core/behaviour.h"

#include <catch2/catch.hpp>
#include <vector>

#include "sim/core/drive.h"
#include "sim/core/gait.h"
#include "sim/core/pendulum.h"

using namespace ahhs::sim;

namespace {
BehaviourSummary RunWith(Scenario& s, DriveKind drive) {
  BehaviourSummary b;
  std::vector<double> command(static_cast<std::size_t>(s.num_actuators())), all;
  while (true) {
    all.clear();
    for (int c = 0; c < s.num_compartments(); ++c) {
      DriveCommand(drive, s, c, command.data());
      s.SetActuators(c, command.data());
      all.insert(all.end(), command.begin(), command.end());
    }
    const StepStatus status = s.Step();
    b.Observe(s, all);
    if (status != StepStatus::kRunning) break;
  }
  return b;
}
ScenarioConfig Config(ScenarioKind kind, DockingKind docking = DockingKind::kDamped) {
  ScenarioConfig c;
  c.kind = kind;
  c.docking = docking;
  c.num_modules = kind == ScenarioKind::kPendulum ? 2 : 5;
  return c;
}
}  // namespace

TEST_CASE("behaviour: the swing-up turns the pendulum over the top, hanging does not",
          "[sim][behaviour]") {
  PendulumScenario p(Config(ScenarioKind::kPendulum));
  p.Reset(1);
  const BehaviourSummary up = RunWith(p, DriveKind::kSwingUp);
  CHECK(up.ticks() == 3000);
  CHECK(up.passes_over_top() >= 10);
  CHECK(up.ticks_above_pivot() > 1800);
  CHECK_THAT(up.Describe(), Catch::Contains("passes over the top"));
  p.Reset(1);
  const BehaviourSummary hanging = RunWith(p, DriveKind::kZero);
  CHECK(hanging.passes_over_top() == 0);
  CHECK(hanging.ticks_above_pivot() == 0);
  CHECK(hanging.widest_turn() == 0.0);
}

TEST_CASE("behaviour: a gait's commands and where it ends relative to the wall",
          "[sim][behaviour]") {
  for (DockingKind j : {DockingKind::kDamped, DockingKind::kFixed}) {
    INFO(DockingName(j));
    GaitScenario g(Config(ScenarioKind::kGait, j));
    g.Reset(1);
    const BehaviourSummary still = RunWith(g, DriveKind::kZero);
    CHECK(still.last_command_change() == -1);
    CHECK(still.WallClass() == "inside");
    CHECK_THAT(still.Describe(), Catch::Contains("commands constant after 5 s"));
    g.Reset(1);
    const BehaviourSummary wave = RunWith(g, DriveKind::kWave);
    CHECK(wave.last_command_change() > 59);
    CHECK(wave.command_swing() == Approx(1.6).margin(0.01));  // 0.8 sin(...)
    CHECK(still.command_swing() == 0.0);
    CHECK(wave.WallClass() == "over");  // the wave crawls over the wall (docs/scenarios.md)
    g.Reset(1);
    const BehaviourSummary inch = RunWith(g, DriveKind::kInchworm);
    CHECK(inch.WallClass() == "at the wall");
  }
}
