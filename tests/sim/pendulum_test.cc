#include "sim/core/pendulum.h"

#include <algorithm>
#include <catch2/catch.hpp>

#include "sim/core/drive.h"

using namespace ahhs::sim;

namespace {
ScenarioConfig Pendulum() {
  ScenarioConfig c;
  c.kind = ScenarioKind::kPendulum;
  return c;
}
void Drive(PendulumScenario& p, double a0, double a1) {
  const double left[2] = {a0, 0}, right[2] = {0, a1};
  p.SetActuators(0, left);
  p.SetActuators(1, right);
}
// Time at which angle-from-the-bottom crosses 0 going in `direction`, interpolated between ticks.
std::vector<double> BottomCrossings(PendulumScenario& p, int ticks) {
  std::vector<double> times;
  double prev = WrapAngle(p.state().phi - M_PI);
  for (int t = 0; t < ticks; ++t) {
    p.Step();
    const double now = WrapAngle(p.state().phi - M_PI);
    if (prev < 0 && now >= 0 && now - prev < M_PI) {
      const double frac = -prev / (now - prev);
      times.push_back(p.sim_time() - p.control_period() * (1 - frac));
    }
    prev = now;
  }
  return times;
}
}  // namespace

TEST_CASE("pendulum: with zero drive it hangs and scores 0", "[sim][pendulum]") {
  PendulumScenario p(Pendulum());
  p.Reset(5);
  while (p.Step() == StepStatus::kRunning) {
  }
  CHECK(p.tick() == 3000);
  CHECK(p.state().phi == M_PI);
  CHECK(p.Fitness() == Approx(0.0).margin(1e-12));
  CHECK(p.Cost() == Approx(M_PI * 3000).epsilon(1e-12));
}

TEST_CASE("pendulum: released from horizontal, swings with the physical pendulum's period",
          "[sim][pendulum]") {
  // Without friction, the period for a 90-degree amplitude is
  // 4 K(sin 45deg) sqrt(l/g) = 1.18034 * 2 pi sqrt(l/g) = 1.67439 s for l = 0.5 m.
  PendulumConstants k;
  k.pivot_friction = 0;
  k.noise = 0;
  PendulumScenario p(Pendulum(), k);
  p.Reset(1);
  p.SetState({0, 0, M_PI / 2, 0});
  const auto t = BottomCrossings(p, 1000);
  REQUIRE(t.size() >= 5);
  const double period = (t[4] - t[0]) / 4;
  CHECK(period == Approx(1.18034 * 2 * M_PI * std::sqrt(0.5 / 9.81)).epsilon(0.002));

  // Small amplitude (10 degrees) with the scenario's settings: close to 2 pi sqrt(l/g).
  PendulumScenario q(Pendulum());
  q.Reset(1);
  q.SetState({0, 0, M_PI - 10 * M_PI / 180, 0});
  const auto u = BottomCrossings(q, 800);
  REQUIRE(u.size() >= 3);
  CHECK((u[2] - u[0]) / 2 ==
        Approx(2 * M_PI * std::sqrt(0.5 / 9.81) * (1 + 0.1745 * 0.1745 / 16)).epsilon(0.01));
}

TEST_CASE("pendulum: the 3.5 ms integrator agrees with a fine reference integration",
          "[sim][pendulum]") {
  // Reference: the same equations (cart speed through a first-order lag, phi'' = (g sin phi +
  // a cos phi) / l - friction omega) with RK4 at a thousandth of a tick and the library's sin and
  // cos. Started fast (8 rad/s, turning over the top) and away from the walls, 700 ticks (12 s)
  // of a varying command must agree to 1e-6 (the sensors' noise is 0.023 of their range).
  PendulumConstants k;
  k.noise = 0;
  PendulumScenario p(Pendulum(), k);
  p.Reset(1);
  p.SetState({0, 0, 2.5, 8.0});
  double ref[4] = {0, 0, 2.5, 8.0};
  auto deriv = [&](const double s[4], double v_cmd, double d[4]) {
    const double a = (v_cmd - s[1]) / k.motor_time_constant;
    d[0] = s[1];
    d[1] = a;
    d[2] = s[3];
    d[3] = (k.gravity * std::sin(s[2]) + a * std::cos(s[2])) / k.length - k.pivot_friction * s[3];
  };
  for (int tick = 0; tick < 700; ++tick) {
    const double a0 = 0.3 * std::sin(tick * 0.11), a1 = 0.3 * std::cos(tick * 0.07);
    const double left[2] = {a0, 0}, right[2] = {0, a1};
    p.SetActuators(0, left);
    p.SetActuators(1, right);
    REQUIRE(p.Step() == StepStatus::kRunning);
    const double v_cmd = k.max_speed * (a1 - a0) / 2;
    const double h = k.control_period / 1000;
    for (int i = 0; i < 1000; ++i) {
      double k1[4], k2[4], k3[4], k4[4], s[4];
      deriv(ref, v_cmd, k1);
      for (int j = 0; j < 4; ++j) s[j] = ref[j] + 0.5 * h * k1[j];
      deriv(s, v_cmd, k2);
      for (int j = 0; j < 4; ++j) s[j] = ref[j] + 0.5 * h * k2[j];
      deriv(s, v_cmd, k3);
      for (int j = 0; j < 4; ++j) s[j] = ref[j] + h * k3[j];
      deriv(s, v_cmd, k4);
      for (int j = 0; j < 4; ++j) ref[j] += h / 6 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j]);
    }
    REQUIRE(std::fabs(ref[0]) < 0.8);  // the walls are never touched
  }
  const auto& st = p.state();
  CHECK(st.x == Approx(ref[0]).margin(1e-6));
  CHECK(st.v == Approx(ref[1]).margin(1e-6));
  CHECK(WrapAngle(st.phi - ref[2]) == Approx(0).margin(1e-6));
  CHECK(st.omega == Approx(ref[3]).margin(1e-6));
}

TEST_CASE("pendulum: nothing caps the angular speed", "[sim][pendulum]") {
  // Released just off the top, a frictionless pendulum passes the bottom at 2 sqrt(g / l).
  PendulumConstants k;
  k.pivot_friction = 0;
  k.noise = 0;
  PendulumScenario p(Pendulum(), k);
  p.Reset(2);
  p.SetState({0, 0, 1e-6, 0});
  double fastest = 0;
  for (int t = 0; t < 400; ++t) {
    p.Step();
    fastest = std::max(fastest, std::fabs(p.state().omega));
  }
  CHECK(fastest == Approx(2 * std::sqrt(9.81 / 0.5)).epsilon(1e-3));
}

TEST_CASE("pendulum: the swing-up drive brings it over the top and keeps it turning",
          "[sim][pendulum]") {
  // The designed reference controller reads only the noisy sensors. It must pass the top
  // many times, keep the bob above the pivot most of the time, and the pendulum must turn about
  // 9 degrees per tick at its fastest (the paper's slow sampling), never more than 10.
  for (std::uint64_t seed : {1, 2, 3}) {
    PendulumScenario p(Pendulum());
    p.Reset(seed);
    double a[2];
    int over_top = 0, above = 0;
    double widest = 0, prev = p.state().phi;
    while (true) {
      for (int c = 0; c < 2; ++c) {
        DriveCommand(DriveKind::kSwingUp, p, c, a);
        p.SetActuators(c, a);
      }
      const StepStatus status = p.Step();
      const double phi = p.state().phi;
      widest = std::max(widest, std::fabs(WrapAngle(phi - prev)));
      if (std::fabs(phi) < 1 && std::fabs(prev) < 1 && (phi > 0) != (prev > 0)) ++over_top;
      if (std::fabs(phi) < M_PI / 2) ++above;
      prev = phi;
      if (status != StepStatus::kRunning) break;
    }
    INFO("seed " << seed << ": " << over_top << " passes over the top, above the pivot " << above
                 << " of 3000 ticks, widest step " << widest * 180 / M_PI << " degrees, fitness "
                 << p.Fitness());
    CHECK(over_top >= 10);
    CHECK(above > 0.6 * 3000);
    CHECK(widest * 180 / M_PI > 8.5);
    CHECK(widest * 180 / M_PI <= 10.0);
    CHECK(p.Fitness() > 0.6);
  }
}

TEST_CASE("pendulum: a constant command does not swing it up", "[sim][pendulum]") {
  // The cart runs into a wall and stops dead; the kick (at most v / l = 2 rad/s) cannot take
  // the pendulum over the top, and it swings out again.
  for (double u : {-1.0, -0.5, 0.5, 1.0}) {
    PendulumScenario p(Pendulum());
    p.Reset(1);
    Drive(p, -u, u);
    double highest = M_PI;
    while (p.Step() == StepStatus::kRunning) highest = std::min(highest, std::fabs(p.state().phi));
    INFO("speed " << u << ": closest to the top " << highest << " rad, fitness " << p.Fitness());
    CHECK(highest > M_PI / 2);
    CHECK(p.Fitness() < 0.15);
  }
}

TEST_CASE("pendulum: the cart stops dead at a wall", "[sim][pendulum]") {
  PendulumScenario p(Pendulum());
  p.Reset(3);
  Drive(p, -1, 1);  // full speed to the right
  for (int t = 0; t < 250; ++t) p.Step();
  CHECK(p.state().x == 1.0 - 0.1);
  CHECK(p.state().v == 0.0);
  double s[10];
  p.ReadSensors(1, s);
  CHECK(s[kWallRight] >= 1 - 0.023);
  p.ReadSensors(0, s);
  CHECK(s[kWallLeft] <= 0.0231);  // the left wall is 1.8 m away: 0 plus noise
  Drive(p, 1, -1);                // and back to the left wall
  for (int t = 0; t < 250; ++t) p.Step();
  CHECK(p.state().x == -(1.0 - 0.1));
}

TEST_CASE("pendulum: speed follows the command through the motor lag", "[sim][pendulum]") {
  PendulumScenario p(Pendulum());
  p.Reset(4);
  Drive(p, 0, 0.5);  // v_cmd = 1 m/s * (0.5 - 0) / 2 = 0.25 m/s
  p.Step();          // after 0.0175 s: 0.25 (1 - e^{-0.175})
  CHECK(p.state().v == Approx(0.25 * (1 - std::exp(-0.175))).epsilon(1e-6));
  for (int t = 0; t < 60; ++t) p.Step();
  CHECK(p.state().v == Approx(0.25).epsilon(1e-3));
}

TEST_CASE("pendulum: partitioned sensors read the right quadrant, with bounded noise",
          "[sim][pendulum]") {
  PendulumScenario p(Pendulum());
  p.Reset(6);
  double left[10], right[10];
  p.SetState({0, 0, M_PI / 4, 0});  // upper left, half way to the top
  p.ReadSensors(0, left);
  p.ReadSensors(1, right);
  CHECK(left[kUpperLeft] == Approx(0.5).margin(0.0231));
  CHECK(right[kUpperRight] <= 0.0231);
  CHECK(left[kLowerLeft] <= 0.0231);
  for (int j = 1; j < 10; j += 2) CHECK(left[j] == 0.0);  // odd sensors belong to the right
  for (int j = 0; j < 10; j += 2) CHECK(right[j] == 0.0);
  p.SetState({0, 0, -3 * M_PI / 4, 0});  // lower right, half way to the bottom
  p.ReadSensors(1, right);
  CHECK(right[kLowerRight] == Approx(0.5).margin(0.0231));
  p.SetState({0, 0, M_PI, 0.025 * M_PI / 0.0175});  // counter-clockwise, half the sensor range
  p.ReadSensors(0, left);
  p.ReadSensors(1, right);
  CHECK(left[kSpinPositive] == Approx(0.5).margin(0.0231));
  CHECK(right[kSpinNegative] <= 0.0231);
  // Noise: uniform within +-2.3 %, mean about 0.
  double sum = 0, worst = 0;
  for (int k = 0; k < 2000; ++k) {
    p.SetState({0, 0, M_PI / 4, 0});
    p.ReadSensors(0, left);
    sum += left[kUpperLeft] - 0.5;
    worst = std::max(worst, std::fabs(left[kUpperLeft] - 0.5));
  }
  CHECK(worst <= 0.023 + 1e-12);
  CHECK(worst > 0.02);
  CHECK(sum / 2000 == Approx(0).margin(0.002));
}

TEST_CASE("pendulum: same seed and commands give the same bits", "[sim][pendulum][determinism]") {
  auto run = [](std::uint64_t seed) {
    PendulumScenario p(Pendulum());
    p.Reset(seed);
    std::vector<double> trace;
    double s[10];
    for (int t = 0; t < 500; ++t) {
      p.ReadSensors(0, s);
      Drive(p, s[kUpperLeft] - 0.5, std::sin(t * 0.1));
      p.Step();
      trace.push_back(p.state().phi);
    }
    trace.push_back(p.Fitness());
    return trace;
  };
  CHECK(run(7) == run(7));
  CHECK(run(7) != run(8));  // the noise comes from the seed
}

TEST_CASE("pendulum: fitness landmarks", "[sim][pendulum]") {
  CHECK(PendulumFitness(M_PI * 3000, 3000) == 0.0);
  CHECK(PendulumFitness(0, 3000) == 1.0);
  CHECK(PendulumFitness(M_PI / 2 * 3000, 3000) == Approx(0.5));
}

TEST_CASE("pendulum: an actuator gain multiplies small outputs, clamped at the same top speed",
          "[sim][pendulum][choices]") {
  ScenarioConfig c = Pendulum();
  c.pendulum.actuator_gain = 10;
  PendulumScenario p(c);
  p.Reset(4);
  Drive(p, 0, 0.05);  // v_cmd = 1 m/s * clamp(10 * 0.05 / 2, -1, 1) = 0.25 m/s
  p.Step();
  CHECK(p.state().v == Approx(0.25 * (1 - std::exp(-0.175))).epsilon(1e-6));
  Drive(p, -0.5, 0.5);                    // 10 * 1 / 2 = 5: clamped to the top speed, 1 m/s
  for (int t = 0; t < 40; ++t) p.Step();  // 0.7 s: short of the wall
  CHECK(p.state().v == Approx(1.0).epsilon(1e-3));
  // Gain 1 is the scenario's mapping, bit for bit.
  ScenarioConfig one = Pendulum();
  one.pendulum.actuator_gain = 1;
  PendulumScenario a(one), b(Pendulum());
  a.Reset(9);
  b.Reset(9);
  for (int t = 0; t < 300; ++t) {
    Drive(a, 0.3 * std::sin(t * 0.1), -0.7 * std::cos(t * 0.07));
    Drive(b, 0.3 * std::sin(t * 0.1), -0.7 * std::cos(t * 0.07));
    a.Step();
    b.Step();
  }
  CHECK(a.state().x == b.state().x);
  CHECK(a.state().phi == b.state().phi);
}

TEST_CASE("pendulum: a soft wall stops the cart within 2 cm and pushes it back out",
          "[sim][pendulum][choices]") {
  ScenarioConfig c = Pendulum();
  c.pendulum.walls = PendulumWalls::kSoft;
  PendulumScenario p(c);
  p.Reset(3);
  const double x_max = 1.0 - 0.1;
  Drive(p, -1, 1);  // full speed into the right wall, and keep pushing
  double deepest = 0;
  for (int t = 0; t < 250; ++t) {
    p.Step();
    deepest = std::max(deepest, p.state().x - x_max);
    REQUIRE(std::isfinite(p.state().phi));
  }
  CHECK(deepest > 0.005);  // it goes in, as a spring does
  CHECK(deepest < 0.02);
  // Pushed by the motor it rests 5 mm deep: (v_cmd / tau) / stiffness = 10 / 2000.
  CHECK(p.state().x - x_max == Approx(0.005).epsilon(0.02));
  CHECK(std::fabs(p.state().v) < 1e-3);
  double s[10];
  p.ReadSensors(1, s);
  CHECK(s[kWallRight] >= 1 - 0.023);
  CHECK(s[kWallRight] <= 1.0);
  // Released, the wall pushes it out and never pulls it back in.
  Drive(p, 0, 0);
  for (int t = 0; t < 100; ++t) p.Step();
  CHECK(p.state().x <= x_max);
}

TEST_CASE("pendulum: its choices are checked and are the pendulum's only", "[sim][choices]") {
  ScenarioConfig c = Pendulum();
  c.pendulum.actuator_gain = 0.5;
  CHECK(CheckConfig(c) == "pendulum.actuator-gain: from 1 to 100");
  c.pendulum.actuator_gain = 10;
  CHECK(CheckConfig(c).empty());
  c.kind = ScenarioKind::kGait;
  CHECK(CheckConfig(c) ==
        "pendulum.actuator-gain and pendulum.walls are the pendulum's, not the "
        "gait's");
  CHECK(ParsePendulumWalls("soft") == PendulumWalls::kSoft);
  CHECK_THROWS_AS(ParsePendulumWalls("padded"), std::invalid_argument);
}
