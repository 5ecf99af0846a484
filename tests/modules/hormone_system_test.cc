// Each equation of the spec against values computed by hand (docs/model.md).
#include "modules/core/hormone_system.h"

#include <catch2/catch.hpp>

using namespace ahhs::modules;

namespace {

constexpr double kTol = 1e-15;

Genome Ahhs2(int hormones, int sensors, int actuators, std::vector<Ahhs2Rule> rules,
             HormoneGene gene = {}) {
  Genome g;
  g.variant = Variant::kAhhs2;
  g.num_sensors = sensors;
  g.num_actuators = actuators;
  g.hormones.assign(static_cast<std::size_t>(hormones), gene);
  // Rule2()'s indices assume 3 hormones, 2 sensors, 2 actuators; in smaller genomes an index
  // that does not exist is moved to item 0 (each test states the indices it relies on).
  for (auto& r : rules) {
    if (r.sensor >= sensors) r.sensor = 0;
    if (r.input >= hormones) r.input = 0;
    if (r.output >= hormones) r.output = 0;
    if (r.actuator >= actuators) r.actuator = 0;
  }
  g.ahhs2_rules = std::move(rules);
  return g;
}

Genome Ahhs1(int hormones, int sensors, int actuators, std::vector<Ahhs1Rule> rules) {
  Genome g;
  g.variant = Variant::kAhhs1;
  g.num_sensors = sensors;
  g.num_actuators = actuators;
  g.hormones.assign(static_cast<std::size_t>(hormones), HormoneGene{});
  g.ahhs1_rules = std::move(rules);
  return g;
}

Ahhs2Rule Rule2(std::array<double, 5> w) {
  Ahhs2Rule r;
  r.weights = w;
  r.zeta = 0.5;
  r.eta = 0.4;
  r.kappa = 0.05;
  r.lambda = 0.5;
  r.sensor = 1.7;    // reads S[1]
  r.input = 0.9;     // reads H[0]
  r.output = 1.25;   // 0.75 to H[1], 0.25 to H[2]
  r.actuator = 0.5;  // 0.5 to A[0], 0.5 to A[1]
  return r;
}

}  // namespace

TEST_CASE("tent trigger, paper eq. 2", "[model]") {
  CHECK(Tent(0.3, 0.5, 0.4) == Approx(0.5).epsilon(0).margin(kTol));
  CHECK(Tent(0.5, 0.5, 0.4) == 1.0);
  CHECK(Tent(0.7, 0.5, 0.4) == Approx(0.5).margin(kTol));
  CHECK(Tent(0.9, 0.5, 0.4) == 0.0);  // |x - zeta| = eta: outside (strict inequality)
  CHECK(Tent(0.1, 0.5, 0.4) == 0.0);
  CHECK(Tent(-0.2, -0.1, 0.2) == Approx(0.5).margin(kTol));
}

TEST_CASE("AHHS1 threshold trigger: strict beyond a tie band, both directions", "[model]") {
  CHECK(Threshold(0.6, 0.5, Direction::kAbove));
  CHECK_FALSE(Threshold(0.5, 0.5, Direction::kAbove));
  CHECK_FALSE(Threshold(0.4, 0.5, Direction::kAbove));
  CHECK(Threshold(0.4, 0.5, Direction::kBelow));
  CHECK_FALSE(Threshold(0.5, 0.5, Direction::kBelow));
  // Within kThresholdTie of tau counts as tau: rounding never decides a trigger.
  CHECK_FALSE(Threshold(1.0 - 1e-16, 1.0, Direction::kBelow));
  CHECK_FALSE(Threshold(0.5 + 1e-15, 0.5, Direction::kAbove));
  CHECK(Threshold(1.0 - 1e-9, 1.0, Direction::kBelow));
  CHECK(Threshold(0.5 + 1e-9, 0.5, Direction::kAbove));
}

TEST_CASE("AHHS2 sensor part with floating-index split", "[model]") {
  Controller c(Ahhs2(3, 2, 2, {Rule2({0, 1, 0, 0, 0})}));
  auto s = MakeState(c);
  const double sensors[] = {0.9, 0.3};
  Step(c, {sensors, nullptr, nullptr, 0}, &s);
  // x = S[1] = 0.3, theta = 0.5, v = 0.5 * (0.5 * 0.3 + 0.05) = 0.1 -> 0.075 to H1, 0.025 to H2.
  CHECK(s.hormones[0] == 0.0);
  CHECK(s.hormones[1] == Approx(0.075).margin(kTol));
  CHECK(s.hormones[2] == Approx(0.025).margin(kTol));
  CHECK(s.actuators.isZero());
  CHECK(s.part_activity[kActSensor] == 1);
  CHECK(s.rule_activity[0] == 1);
}

TEST_CASE("AHHS2: every rule part at once, with production and decay", "[model]") {
  const HormoneGene gene{0.01, 0.1, 0.0};
  Controller c(Ahhs2(3, 2, 2, {Rule2({0.2, 0.3, 0.1, 0.25, 0.15})}, gene));
  auto s = MakeState(c);
  s.hormones << 0.4, 0.2, 0.6;
  const double sensors[] = {0.9, 0.3};
  Step(c, {sensors, nullptr, nullptr, 0}, &s);
  // theta(S1 = 0.3) = 0.5; theta(H0 = 0.4) = 0.75.
  // sensor:    0.3 * 0.5 * 0.2                    = 0.03     -> H1 0.0225,     H2 0.0075
  // linear:    0.1 * 0.75 * (0.2 + 0.05)          = 0.01875  -> H1 0.0140625,  H2 0.0046875
  // nonlinear: 0.25*0.75 = 0.1875; H1: 0.75 * 0.1875 * (0.5*0.4*0.2 + 0.05) = 0.01265625
  //                                H2: 0.25 * 0.1875 * (0.5*0.4*0.6 + 0.05) = 0.00796875
  // actuator:  0.15 * 0.75 * 0.25                 = 0.028125 -> A0, A1 0.0140625 each
  // H' = H + 0.01 - 0.1 H + dH
  CHECK(s.hormones[0] == Approx(0.37).margin(kTol));
  CHECK(s.hormones[1] == Approx(0.23921875).margin(kTol));
  CHECK(s.hormones[2] == Approx(0.57015625).margin(kTol));
  CHECK(s.actuators[0] == Approx(0.0140625).margin(kTol));
  CHECK(s.actuators[1] == Approx(0.0140625).margin(kTol));
  for (int col = 0; col < kActivityColumns; ++col)
    CHECK(s.part_activity[static_cast<std::size_t>(col)] == 1);
}

TEST_CASE("AHHS2 output index wraps from the last item to the first", "[model]") {
  auto rule = Rule2({0, 0, 1, 0, 0});  // linear only
  rule.output = 2.5;                   // half to H2, half to H0
  rule.actuator = 1.75;                // item 1 gets 1 - 0.75, item (1+1) mod 2 = 0 gets 0.75
  rule.weights = {0, 0, 0.5, 0, 0.5};
  Controller c(Ahhs2(3, 2, 2, {rule}));
  auto s = MakeState(c);
  s.hormones << 0.4, 0, 0;
  Step(c, {nullptr, nullptr, nullptr, 0}, &s);
  const double v = 0.5 * 0.75 * 0.25;  // 0.09375
  CHECK(s.hormones[0] == Approx(0.4 + 0.5 * v).margin(kTol));
  CHECK(s.hormones[2] == Approx(0.5 * v).margin(kTol));
  CHECK(s.hormones[1] == 0.0);
  CHECK(s.actuators[0] == Approx(0.75 * v).margin(kTol));
  CHECK(s.actuators[1] == Approx(0.25 * v).margin(kTol));
}

TEST_CASE("rules see start-of-tick values only", "[model]") {
  // Rule A writes H1 from H0; rule B reads H1. B must see H1 = 0 (start of tick), not A's effect.
  auto a = Rule2({0, 0, 1, 0, 0});
  a.output = 1.0;
  auto b = Rule2({0, 0, 0, 0, 1});
  b.input = 1.0;
  b.zeta = 0.0;
  b.eta = 0.01;  // fires only while H1 is ~0
  b.actuator = 0.0;
  Controller c(Ahhs2(2, 1, 1, {a, b}));
  auto s = MakeState(c);
  s.hormones << 0.5, 0.0;
  Step(c, {nullptr, nullptr, nullptr, 0}, &s);
  CHECK(s.hormones[1] > 0.2);                          // A fired
  CHECK(s.actuators[0] == Approx(0.05).margin(kTol));  // B saw H1 = 0: theta 1, 1*(0 + 0.05)
}

TEST_CASE("absent sensor and actuator slots contribute nothing (absent is not 0)", "[model]") {
  auto rule = Rule2({0, 1, 0, 0, 0});
  rule.zeta = 0.0;  // a tent centred on 0 would fire on a reading of 0
  rule.sensor = 0.2;
  Controller c(Ahhs2(1, 2, 2, {rule}));
  auto s = MakeState(c);
  const double zeros[] = {0.0, 0.0};
  const bool absent[] = {false, true};
  Step(c, {zeros, absent, nullptr, 0}, &s);
  CHECK(s.hormones[0] == 0.0);
  CHECK(s.part_activity[kActSensor] == 0);
  const bool present[] = {true, true};
  Step(c, {zeros, present, nullptr, 0}, &s);
  CHECK(s.hormones[0] == Approx(0.05).margin(kTol));

  auto act = Rule2({0, 0, 0, 0, 1});
  act.actuator = 0.5;  // split half/half over A0, A1
  Controller ca(Ahhs2(1, 1, 2, {act}));
  auto sa = MakeState(ca);
  sa.hormones << 0.5;
  const bool own_a1[] = {false, true};
  Step(ca, {nullptr, nullptr, own_a1, 0}, &sa);
  CHECK(sa.actuators[0] == 0.0);
  CHECK(sa.actuators[1] == Approx(0.5 * (0.25 + 0.05)).margin(kTol));
}

TEST_CASE("clamping: hormones to [0, 1], actuators to [-1, 1]", "[model]") {
  auto up = Rule2({0, 0, 0.5, 0, 0.5});
  up.lambda = 2;
  up.kappa = 0.2;
  up.zeta = 0.5;
  up.eta = 0.5;
  up.output = 0;
  up.actuator = 0;
  auto down = up;
  down.lambda = -2;
  down.kappa = -0.2;
  down.output = 1;
  down.actuator = 1.0;
  std::vector<Ahhs2Rule> rules(10, up);
  rules.insert(rules.end(), 10, down);
  Controller c(Ahhs2(2, 1, 2, rules));
  auto s = MakeState(c);
  s.hormones << 0.5, 0.5;
  Step(c, {nullptr, nullptr, nullptr, 0}, &s);
  CHECK(s.hormones[0] == 1.0);
  CHECK(s.hormones[1] == 0.0);
  CHECK(s.actuators[0] == 1.0);
  CHECK(s.actuators[1] == -1.0);
}

TEST_CASE("diffusion sends D*H/P to every neighbour and removes it here", "[model]") {
  Controller c(Ahhs2(2, 1, 1, {}, HormoneGene{0, 0, 0.4}));
  auto s = MakeState(c);
  s.hormones << 0.8, 0.2;
  Step(c, {nullptr, nullptr, nullptr, 2}, &s);
  CHECK(s.outflow[0] == Approx(0.08).margin(kTol));  // 0.4 * 0.8 / 4
  CHECK(s.outflow[1] == Approx(0.02).margin(kTol));
  CHECK(s.hormones[0] == Approx(0.8 - 2 * 0.08).margin(kTol));
  CHECK(s.hormones[1] == Approx(0.2 - 2 * 0.02).margin(kTol));
  const double packet[] = {0.1, 0.3};
  ReceiveHormones(packet, &s);
  CHECK(s.hormones[1] == Approx(0.46).margin(kTol));
}

TEST_CASE("AHHS1 sensor, hormone and actuator rules, both directions", "[model]") {
  Ahhs1Rule sensor{Ahhs1Type::kSensor, 1, 0, 0.5, Direction::kAbove, 0.5, 0.1};
  Ahhs1Rule hormone{Ahhs1Type::kHormone, 0, 1, 0.3, Direction::kBelow, -1.0, 0.2};
  Ahhs1Rule actuator{Ahhs1Type::kActuator, 2, 0, 0.5, Direction::kAbove, 1.0, -0.2};
  Ahhs1Rule idle{Ahhs1Type::kIdle, 0, 0, 0.0, Direction::kAbove, 2.0, 0.2};
  Controller c(Ahhs1(3, 2, 1, {sensor, hormone, actuator, idle}));
  auto s = MakeState(c);
  s.hormones << 0.2, 0.0, 0.9;
  const double sensors[] = {0.0, 0.8};
  Step(c, {sensors, nullptr, nullptr, 0}, &s);
  CHECK(s.hormones[0] == Approx(0.2 + 0.5 * 0.8 + 0.1).margin(kTol));  // S1 = 0.8 > 0.5
  CHECK(s.hormones[1] == Approx(-1.0 * 0.2 + 0.2).margin(kTol));       // H0 = 0.2 < 0.3
  CHECK(s.actuators[0] == Approx(1.0 * 0.9 - 0.2).margin(kTol));       // H2 = 0.9 > 0.5
  CHECK(s.part_activity[0 * kActivityColumns + kActSensor] == 1);
  CHECK(s.part_activity[1 * kActivityColumns + kActLinear] == 1);
  CHECK(s.part_activity[2 * kActivityColumns + kActActuator] == 1);
  CHECK(s.rule_activity == std::vector<std::uint64_t>{1, 1, 1, 0});

  // Below the sensor threshold and at exactly tau nothing fires.
  auto s2 = MakeState(c);
  s2.hormones << 0.3, 0.0, 0.5;
  const double low[] = {0.0, 0.5};
  Step(c, {low, nullptr, nullptr, 0}, &s2);
  CHECK(s2.hormones[0] == Approx(0.3).margin(kTol));
  CHECK(s2.hormones[1] == 0.0);
  CHECK(s2.actuators[0] == 0.0);
  CHECK(s2.rule_activity == std::vector<std::uint64_t>{0, 0, 0, 0});
}

TEST_CASE("an invalid genome cannot become a controller", "[model]") {
  auto g = Ahhs2(2, 1, 1, {Rule2({0.5, 0.5, 0.5, 0, 0})});
  g.ahhs2_rules[0].sensor = 0;
  g.ahhs2_rules[0].actuator = 0;
  CHECK_THROWS_WITH(Controller(g), Catch::Contains("rules[0].weights"));
}
