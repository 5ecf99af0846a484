#include "sim/core/pendulum.h"

#include <algorithm>
#include <catch2/catch.hpp>

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
  // Without friction and without the sampling cap, the period for a 90-degree amplitude is
  // 4 K(sin 45deg) sqrt(l/g) = 1.18034 * 2 pi sqrt(l/g) = 1.67439 s for l = 0.5 m.
  PendulumConstants k;
  k.pivot_friction = 0;
  k.max_angular_speed = 1e9;
  k.noise = 0;
  PendulumScenario p(Pendulum(), k);
  p.Reset(1);
  p.SetState({0, 0, M_PI / 2, 0});
  const auto t = BottomCrossings(p, 400);
  REQUIRE(t.size() >= 5);
  const double period = (t[4] - t[0]) / 4;
  CHECK(period == Approx(1.18034 * 2 * M_PI * std::sqrt(0.5 / 9.81)).epsilon(0.002));

  // Small amplitude (10 degrees) with the task's settings: close to 2 pi sqrt(l/g), and the
  // sampling cap of 9 degrees per tick (pi rad/s) is never exceeded.
  PendulumScenario q(Pendulum());
  q.Reset(1);
  q.SetState({0, 0, M_PI - 10 * M_PI / 180, 0});
  const auto u = BottomCrossings(q, 300);
  REQUIRE(u.size() >= 3);
  CHECK((u[2] - u[0]) / 2 ==
        Approx(2 * M_PI * std::sqrt(0.5 / 9.81) * (1 + 0.1745 * 0.1745 / 16)).epsilon(0.01));
}

TEST_CASE("pendulum: the 10 ms integrator agrees with a fine reference integration",
          "[sim][pendulum]") {
  // Reference: the same equations (spec: cart speed through a first-order lag, phi'' = (g sin
  // phi + a cos phi) / l - friction omega, omega capped) with RK4 at 0.05 ms and the library's
  // sin and cos. Away from the walls, 10 s of a varying command must agree to 1e-6 (measured:
  // 4e-7 rad; the sensors' noise is 0.023 of their range).
  PendulumConstants k;
  k.noise = 0;
  PendulumScenario p(Pendulum(), k);
  p.Reset(1);
  p.SetState({0, 0, 2.5, 0});
  double ref[4] = {0, 0, 2.5, 0};
  auto deriv = [&](const double s[4], double v_cmd, double d[4]) {
    const double a = (v_cmd - s[1]) / k.motor_time_constant;
    d[0] = s[1];
    d[1] = a;
    d[2] = std::clamp(s[3], -k.max_angular_speed, k.max_angular_speed);
    d[3] = (k.gravity * std::sin(s[2]) + a * std::cos(s[2])) / k.length - k.pivot_friction * s[3];
  };
  for (int tick = 0; tick < 200; ++tick) {
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
      ref[3] = std::clamp(ref[3], -k.max_angular_speed, k.max_angular_speed);
    }
    REQUIRE(std::fabs(ref[0]) < 0.8);  // the walls are never touched
  }
  const auto& st = p.state();
  CHECK(st.x == Approx(ref[0]).margin(1e-6));
  CHECK(st.v == Approx(ref[1]).margin(1e-6));
  CHECK(WrapAngle(st.phi - ref[2]) == Approx(0).margin(1e-6));
  CHECK(st.omega == Approx(ref[3]).margin(1e-6));
}

TEST_CASE("pendulum: angular speed is capped at 9 degrees per tick", "[sim][pendulum]") {
  PendulumScenario p(Pendulum());
  p.Reset(2);
  p.SetState({0, 0, 0.01, 0});  // nearly upright: falls and would exceed pi rad/s uncapped
  double fastest = 0;
  double prev = p.state().phi;
  for (int t = 0; t < 200; ++t) {
    p.Step();
    fastest = std::max(fastest, std::fabs(p.state().omega));
    CHECK(std::fabs(WrapAngle(p.state().phi - prev)) <= 0.05 * M_PI + 1e-12);
    prev = p.state().phi;
  }
  CHECK(fastest == Approx(M_PI));
}

TEST_CASE("pendulum: the cart stops dead at a wall", "[sim][pendulum]") {
  PendulumScenario p(Pendulum());
  p.Reset(3);
  Drive(p, -1, 1);  // full speed to the right
  for (int t = 0; t < 100; ++t) p.Step();
  CHECK(p.state().x == 1.0 - 0.1);
  CHECK(p.state().v == 0.0);
  double s[10];
  p.ReadSensors(1, s);
  CHECK(s[kWallRight] >= 1 - 0.023);
  p.ReadSensors(0, s);
  CHECK(s[kWallLeft] <= 0.0231);  // the left wall is 1.8 m away: 0 plus noise
  Drive(p, 1, -1);                // and back to the left wall
  for (int t = 0; t < 100; ++t) p.Step();
  CHECK(p.state().x == -(1.0 - 0.1));
}

TEST_CASE("pendulum: speed follows the command through the motor lag", "[sim][pendulum]") {
  PendulumScenario p(Pendulum());
  p.Reset(4);
  Drive(p, 0, 0.5);  // v_cmd = 1 m/s * (0.5 - 0) / 2 = 0.25 m/s
  p.Step();          // after 0.05 s: 0.25 (1 - e^{-0.5})
  CHECK(p.state().v == Approx(0.25 * (1 - std::exp(-0.5))).epsilon(1e-6));
  for (int t = 0; t < 20; ++t) p.Step();
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
  p.SetState({0, 0, M_PI, M_PI / 2});  // spinning counter-clockwise at half the cap
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
