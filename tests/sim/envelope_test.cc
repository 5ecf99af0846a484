// The envelope of noise (sim/core/envelope.h): its draws are a pure function of the seed, no
// envelope is exactly the scenario without one, and each key perturbs what it names.
#include "sim/core/envelope.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <set>

#include "sim/core/constants.h"
#include "sim/core/drive.h"
#include "sim/core/gait.h"
#include "sim/core/scenario.h"
#include "sim/node/sim_codec.h"

using namespace ahhs::sim;
using ahhs::sim_control_t;

namespace {

// A drive's episode, as ahhs-sim --drive runs it; returns the fitness.
double DriveEpisode(ScenarioKind kind, DockingKind docking, DriveKind drive, std::uint64_t seed,
                    double duration, const Envelope& envelope = {},
                    std::vector<double>* first_sensors = nullptr, const std::string& physics = "") {
  ScenarioConfig config = MakeScenarioConfig(kind, docking, 5, duration);
  config.envelope = envelope;
  config.physics = physics;
  auto sim = MakeScenario(config);
  sim->Reset(seed);
  if (first_sensors) {
    first_sensors->assign(static_cast<std::size_t>(sim->num_sensors()), 0);
    sim->ReadSensors(0, first_sensors->data());
  }
  std::vector<double> command(static_cast<std::size_t>(sim->num_actuators()));
  StepStatus status = StepStatus::kRunning;
  while (status == StepStatus::kRunning) {
    for (int c = 0; c < sim->num_compartments(); ++c) {
      DriveCommand(drive, *sim, c, command.data());
      sim->SetActuators(c, command.data());
    }
    status = sim->Step();
  }
  REQUIRE(status == StepStatus::kFinished);
  return sim->Fitness();
}

}  // namespace

TEST_CASE("envelope draws are a pure function of the seed (golden values)", "[envelope]") {
  const Envelope paper = EnvelopePreset("paper");
  const EnvelopeDraw a = DrawEnvelope(paper, 7, 5), b = DrawEnvelope(paper, 7, 5);
  CHECK(a.friction_scale == b.friction_scale);
  CHECK(a.mass_scale == b.mass_scale);
  CHECK(a.heading == b.heading);
  // Golden: a change here changes every envelope episode ever evaluated (a physics change).
  CHECK(a.friction_scale == 0.96344403677749124);
  CHECK(a.mass_scale[4] == 0.98469194204727506);
  CHECK(a.heading == 0.04462363882210655);
  CHECK(a.cart_speed_scale == 0.97242119121168136);
  for (std::size_t m = 0; m < 5; ++m) {
    CHECK(std::fabs(a.mass_scale[m] - 1) <= 0.05);
    CHECK(std::fabs(a.torque_scale[m] - 1) <= 0.05);
    CHECK(std::fabs(a.speed_scale[m] - 1) <= 0.05);
  }
  CHECK(std::fabs(a.offset_x) <= 0.005);
  CHECK(DrawEnvelope(paper, 8, 5).friction_scale != a.friction_scale);
  // Giving one key a width never changes another key's draw.
  Envelope only_mass;
  only_mass.mass = paper.mass;
  CHECK(DrawEnvelope(only_mass, 7, 5).mass_scale == a.mass_scale);
  CHECK(DrawEnvelope(only_mass, 7, 5).friction_scale == 1.0);
  const EnvelopeDraw none = DrawEnvelope(Envelope{}, 7, 5);
  CHECK(none.friction_scale == 1.0);
  CHECK(none.heading == 0.0);
  CHECK(none.mass_scale == std::vector<double>(5, 1.0));
  CHECK(none.hinge == std::vector<double>(5, 0.0));
  // A key added later draws after the others: the paper preset's draws stay what they were.
  Envelope bent = paper;
  bent.start_hinge = 0.3;
  const EnvelopeDraw c = DrawEnvelope(bent, 7, 5);
  CHECK(c.friction_scale == a.friction_scale);
  CHECK(c.speed_scale == a.speed_scale);
  for (double h : c.hinge) CHECK(std::fabs(h) <= 0.3);
  CHECK(c.hinge[0] != c.hinge[1]);
}

TEST_CASE("no envelope gives exactly the bits of the scenario without one, for every scenario",
          "[envelope]") {
  // Golden fitnesses of `ahhs-sim --drive D --seed 3 --duration 10` from the build before the
  // envelope existed (physics versions 2026-12-01 / 2026-12-01.2, still simulated on request).
  CHECK(DriveEpisode(ScenarioKind::kGait, DockingKind::kDamped, DriveKind::kWave, 3, 10, {},
                     nullptr, "2026-12-01.2") == 0.7291256053748767);
  CHECK(DriveEpisode(ScenarioKind::kGait, DockingKind::kFixed, DriveKind::kWave, 3, 10, {}, nullptr,
                     "2026-12-01") == 0.71924482214441543);
  CHECK(DriveEpisode(ScenarioKind::kPendulum, DockingKind::kDamped, DriveKind::kSwingUp, 3, 10) ==
        0.55936332404768008);
}

TEST_CASE("each envelope key perturbs the episode, and the same seed gives the same bits",
          "[envelope]") {
  const double plain =
      DriveEpisode(ScenarioKind::kGait, DockingKind::kFixed, DriveKind::kWave, 3, 5);
  for (const auto& k : EnvelopeKeys()) {
    // The pendulum's keys below; sensor noise cannot change an open-loop drive (its own test).
    if (k.field == &Envelope::start_angle || k.field == &Envelope::cart_speed ||
        k.field == &Envelope::sensor_noise)
      continue;
    Envelope e;
    // The presets have no command delay and no start hinge angles (docs/scenarios.md).
    e.*k.field = k.field == &Envelope::command_delay ? 0.5
                 : k.field == &Envelope::start_hinge ? 0.2
                                                     : EnvelopePreset("paper").*k.field;
    const double a =
        DriveEpisode(ScenarioKind::kGait, DockingKind::kFixed, DriveKind::kWave, 3, 5, e);
    const double b =
        DriveEpisode(ScenarioKind::kGait, DockingKind::kFixed, DriveKind::kWave, 3, 5, e);
    INFO(k.name);
    CHECK(a == b);
    CHECK(a != plain);
  }
  const double pendulum =
      DriveEpisode(ScenarioKind::kPendulum, DockingKind::kDamped, DriveKind::kSwingUp, 3, 5);
  for (auto field : {&Envelope::start_angle, &Envelope::cart_speed}) {
    Envelope e;
    e.*field = EnvelopePreset("paper").*field;
    CHECK(DriveEpisode(ScenarioKind::kPendulum, DockingKind::kDamped, DriveKind::kSwingUp, 3, 5,
                       e) != pendulum);
  }
}

TEST_CASE("sensor noise stays within its width and the readings' range", "[envelope]") {
  std::vector<double> clean, noisy;
  DriveEpisode(ScenarioKind::kGait, DockingKind::kFixed, DriveKind::kZero, 3, 0.1, {}, &clean);
  Envelope e;
  e.sensor_noise = 0.023;
  DriveEpisode(ScenarioKind::kGait, DockingKind::kFixed, DriveKind::kZero, 3, 0.1, e, &noisy);
  bool any = false;
  for (std::size_t j = 0; j < clean.size(); ++j) {
    CHECK(noisy[j] >= 0);
    CHECK(noisy[j] <= 1);
    CHECK(std::fabs(noisy[j] - clean[j]) <= 0.023);
    any = any || noisy[j] != clean[j];
  }
  CHECK(any);
}

TEST_CASE("a posed start keeps the chain's shape: heading and offset move it whole", "[envelope]") {
  Envelope e;
  e.start_heading = 0.5;
  e.start_offset = 0.05;
  ScenarioConfig config = MakeScenarioConfig(ScenarioKind::kGait, DockingKind::kDamped, 5, 1);
  config.envelope = e;
  GaitScenario posed(config);
  posed.Reset(11);
  GaitScenario plain(MakeScenarioConfig(ScenarioKind::kGait, DockingKind::kDamped, 5, 1));
  plain.Reset(11);
  std::vector<BodyState> a, b;
  posed.Bodies(&a);
  plain.Bodies(&b);
  // Distances between module bodies are the same: the chain was moved, not bent.
  auto dist = [](const BodyState& p, const BodyState& q) {
    return std::hypot(p.position[0] - q.position[0], p.position[1] - q.position[1],
                      p.position[2] - q.position[2]);
  };
  for (std::size_t i = 0; i + 1 < 10; ++i)
    CHECK(dist(a[i], a[i + 1]) == Approx(dist(b[i], b[i + 1])));
  CHECK(a[0].position[1] != Approx(b[0].position[1]));  // turned
  CHECK(posed.MaxDockingGap() < 1e-9);
  // A posed chain at rest stays at rest (no motion under a constant command).
  for (int t = 0; t < 20; ++t) posed.Step();
  CHECK(posed.Cost() < 1e-3);
}

TEST_CASE("envelope presets and checks", "[envelope]") {
  CHECK(EnvelopePreset("none").none());
  CHECK(EnvelopeName(EnvelopePreset("paper")) == "paper");
  CHECK(EnvelopeName(EnvelopePreset("wide")) == "wide");
  CHECK(EnvelopePreset("paper").sensor_noise == 0.023);
  CHECK_THROWS(EnvelopePreset("loud"));
  Envelope e;
  e.friction = 0.6;
  CHECK_THAT(CheckEnvelope(e), Catch::Contains("envelope.friction"));
  e = Envelope{};
  e.start_offset = -0.1;
  CHECK_THAT(CheckEnvelope(e), Catch::Contains("envelope.start-offset"));
  CHECK(CheckEnvelope(EnvelopePreset("wide")).empty());
  e = Envelope{};
  e.command_delay = 1;  // a whole tick would let the next command overtake this one
  CHECK_THAT(CheckEnvelope(e), Catch::Contains("envelope.command-delay"));
  e.command_delay = 0.99;
  CHECK(CheckEnvelope(e).empty());
  CHECK(EnvelopePreset("paper").command_delay == 0);
  CHECK(EnvelopePreset("wide").command_delay == 0);
  e = Envelope{};
  e.start_hinge = 0.8;  // beyond a quarter turn a curled chain could touch itself
  CHECK_THAT(CheckEnvelope(e), Catch::Contains("envelope.start-hinge"));
  e.start_hinge = M_PI / 4;
  CHECK(CheckEnvelope(e).empty());
  CHECK(EnvelopePreset("wide").start_hinge == 0);
}

TEST_CASE("an envelope spec is a preset with single keys on top", "[envelope]") {
  CHECK(ParseEnvelopeSpec("paper") == EnvelopePreset("paper"));
  Envelope e = EnvelopePreset("paper");
  e.command_delay = 0.5;
  e.friction = 0.125;
  CHECK(ParseEnvelopeSpec("paper,command-delay=0.5,friction=0.125") == e);
  CHECK(ParseEnvelopeSpec("none,start-hinge=0.25").start_hinge == 0.25);
  CHECK_THROWS_WITH(ParseEnvelopeSpec("loud"), Catch::Contains("none, paper or wide"));
  CHECK_THROWS_WITH(ParseEnvelopeSpec("paper,delay=0.5"), Catch::Contains("'delay=0.5'"));
  CHECK_THROWS_WITH(ParseEnvelopeSpec("paper,friction"), Catch::Contains("KEY=W"));
  CHECK_THROWS_WITH(ParseEnvelopeSpec("paper,friction=0.1x"), Catch::Contains("a number"));
  CHECK_THROWS_WITH(ParseEnvelopeSpec("paper,friction="), Catch::Contains("a number"));
  CHECK_THROWS_WITH(ParseEnvelopeSpec("paper,"), Catch::Contains("KEY=W"));
  CHECK_THROWS_WITH(ParseEnvelopeSpec("paper,command-delay=1"),
                    Catch::Contains("envelope.command-delay"));
}

TEST_CASE("a bent start: each hinge reads its drawn angle, the lowest corner is on the ground",
          "[envelope]") {
  // The lowest corner of the module boxes, from the bodies' poses.
  const auto lowest_corner = [](const std::vector<BodyState>& bodies) {
    double lowest = INFINITY;
    for (const BodyState& b : bodies) {
      if (b.module < 0) continue;
      const double w = b.quaternion[0], x = b.quaternion[1], y = b.quaternion[2],
                   z = b.quaternion[3];
      const double row_z[3] = {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)};
      for (int corner = 0; corner < 8; ++corner) {
        double cz = b.position[2];
        for (int k = 0; k < 3; ++k) cz += row_z[k] * ((corner >> k & 1) ? 0.5 : -0.5) * b.size[k];
        lowest = std::min(lowest, cz);
      }
    }
    return lowest;
  };
  for (DockingKind docking : {DockingKind::kFixed, DockingKind::kDamped}) {
    ScenarioConfig config = MakeScenarioConfig(ScenarioKind::kGait, docking, 5, 2);
    config.envelope.start_hinge = 0.6;
    config.envelope.start_heading = 0.5;  // bent about the turned hinge axes
    GaitScenario bent(config);
    bent.Reset(5);
    const EnvelopeDraw draw = DrawEnvelope(config.envelope, 5, 5);
    for (int i = 0; i < 5; ++i) {
      INFO("module " << i);
      CHECK(bent.HingeAngle(i) == Approx(draw.hinge[static_cast<std::size_t>(i)]).margin(1e-12));
    }
    std::vector<BodyState> bodies;
    bent.Bodies(&bodies);
    CHECK(lowest_corner(bodies) == Approx(0).margin(1e-12));
    CHECK(bent.MaxDockingGap() < 1e-9);
    // Commanded to hold its start angles, the servos hold them while the chain settles.
    for (int t = 0; t < 20; ++t) {
      for (int i = 0; i < 5; ++i) {
        const double a = draw.hinge[static_cast<std::size_t>(i)] / bent.constants().hinge_range;
        bent.SetActuators(i, &a);
      }
      REQUIRE(bent.Step() == StepStatus::kRunning);
    }
    for (int i = 0; i < 5; ++i)
      CHECK(bent.HingeAngle(i) == Approx(draw.hinge[static_cast<std::size_t>(i)]).margin(0.02));
    bent.Bodies(&bodies);
    CHECK(lowest_corner(bodies) == Approx(0).margin(0.005));  // resting on the ground
  }
}

TEST_CASE("command delays are a pure function of seed, tick and module, uniform on 0 to most",
          "[envelope]") {
  // Golden values: a change of the stream changes every delayed episode.
  CHECK(CommandDelaySteps(7, 0, 0, 3) == 2);
  CHECK(CommandDelaySteps(7, 1, 0, 3) == 2);
  CHECK(CommandDelaySteps(7, 0, 1, 3) == 0);
  CHECK(CommandDelaySteps(8, 0, 0, 3) == 0);
  CHECK(CommandDelaySteps(7, 0, 0, 0) == 0);
  int count[4] = {0, 0, 0, 0};
  for (std::int64_t tick = 0; tick < 4000; ++tick) {
    const int d = CommandDelaySteps(12345, tick, 2, 3);
    REQUIRE(d >= 0);
    REQUIRE(d <= 3);
    ++count[d];
  }
  for (int n : count) {  // 1000 expected each; 5 standard deviations is about 137
    CHECK(n > 860);
    CHECK(n < 1140);
  }
}

TEST_CASE("a delayed command holds the old target for its drawn physics steps, then takes effect",
          "[envelope]") {
  // Fixed docking steps 4 times a tick; w = 0.75 delays a target by 0 to 3 steps.
  const auto hinge_angles = [](double delay, bool command, std::uint64_t seed) {
    ScenarioConfig config = MakeScenarioConfig(ScenarioKind::kGait, DockingKind::kFixed, 3, 1);
    config.envelope.command_delay = delay;
    auto sim = MakeScenario(config);
    sim->Reset(seed);
    const double zero = 0, one = 1;
    for (int c = 0; c < sim->num_compartments(); ++c)
      sim->SetActuators(c, c == 0 && command ? &one : &zero);
    std::vector<double> angles;
    sim->Step([&](double) { angles.push_back(sim->HingeAngle(0)); });
    return angles;
  };
  std::set<int> seen;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const int d = CommandDelaySteps(seed, 0, 0, 3);
    seen.insert(d);
    const auto delayed = hinge_angles(0.75, true, seed);
    const auto at_once = hinge_angles(0, true, seed);
    const auto never = hinge_angles(0, false, seed);
    REQUIRE(delayed.size() == 4);
    INFO("seed " << seed << ", delay " << d << " steps");
    for (int i = 0; i < 4; ++i) {
      if (i < d)  // the old target (0) still holds: the steps of an episode without the command
        CHECK(delayed[static_cast<std::size_t>(i)] == never[static_cast<std::size_t>(i)]);
      else  // from step d on the hinge moves towards its new target
        CHECK(delayed[static_cast<std::size_t>(i)] != never[static_cast<std::size_t>(i)]);
    }
    if (d == 0) CHECK(delayed == at_once);
  }
  CHECK(seen.size() == 4);  // these seeds draw every delay, 0 to 3
  // Below one step per tick (w x 4 < 1) nothing is ever delayed: the bits of no delay.
  CHECK(hinge_angles(0.2, true, 3) == hinge_angles(0, true, 3));
}

TEST_CASE("the envelope survives the wire, and a RESET with a bad one is refused", "[envelope]") {
  ScenarioConfig config = MakeScenarioConfig(ScenarioKind::kGait, DockingKind::kFixed, 4, 3);
  config.envelope = EnvelopePreset("wide");
  config.envelope.cart_speed = 0.125;
  config.envelope.command_delay = 0.375;
  config.envelope.start_hinge = 0.25;
  sim_control_t reset{};
  reset.command = sim_control_t::RESET;
  ScenarioToWire(config, &reset);
  ScenarioConfig back;
  REQUIRE(ConfigFromReset(reset, &back) == "");
  CHECK(back.envelope == config.envelope);
  reset.envelope_mass = std::nan("");
  CHECK_THAT(ConfigFromReset(reset, &back), Catch::Contains("envelope.mass"));
  reset.envelope_mass = 0;
  reset.envelope_start_heading = 2;
  CHECK_THAT(ConfigFromReset(reset, &back), Catch::Contains("envelope.start-heading"));
}

TEST_CASE(
    "the physics travels by name, this build's own as its own, and an unknown one is refused") {
  ScenarioConfig config = MakeScenarioConfig(ScenarioKind::kGait, DockingKind::kFixed, 4, 3);
  sim_control_t reset{};
  reset.command = sim_control_t::RESET;
  ScenarioToWire(config, &reset);
  CHECK(reset.physics == kGaitFixedPhysicsVersion);  // never "": another build must see which
  ScenarioConfig back;
  REQUIRE(ConfigFromReset(reset, &back) == "");
  CHECK(back.physics.empty());  // its own
  reset.physics = "";           // a RESET made field by field asks for the receiver's own
  REQUIRE(ConfigFromReset(reset, &back) == "");
  CHECK(PhysicsOf(back) == kGaitFixedPhysicsVersion);
  KeepPhysics(kGaitChainColdPhysicsVersion, &config);
  CHECK(config.physics == kGaitChainColdPhysicsVersion);
  ScenarioToWire(config, &reset);
  REQUIRE(ConfigFromReset(reset, &back) == "");
  CHECK(back.physics == kGaitChainColdPhysicsVersion);
  reset.physics = "1999-01-01";
  CHECK_THAT(ConfigFromReset(reset, &back),
             Catch::Contains("this build simulates the gait physics of") &&
                 Catch::Contains("not 1999-01-01"));
}
