// The conformance kit's judgement (tools/conformance/checks.h) on hand-made records: a perfect
// firmware passes every check, and each way of breaking the timing rules (docs/hardware.md,
// "Timing rules") fails exactly the check that names it, with the evidence that shows it.
#include <catch2/catch.hpp>

#include "tools/conformance/checks.h"

using namespace ahhs::conformance;

namespace {

// 4 ticks of episode 7 from t = 1 s, then a late start at tick 10 of episode 8, 4 ticks.
PlayedClock Clock() {
  PlayedClock c;
  c.episode = 7;
  c.late_episode = 8;
  c.ticks = 4;
  c.late_from = 10;
  c.started = 1.0;
  for (int t = 0; t < 4; ++t) c.sent.push_back({PlayedClock::Key(7, t), 1.0 + 0.05 * t});
  for (int t = 10; t < 14; ++t) c.sent.push_back({PlayedClock::Key(8, t), 2.0 + 0.05 * (t - 10)});
  return c;
}

// One reading per played tick, 2 ms after its clock, module 3, the hinge where it was sent.
std::vector<Observed> Perfect(const PlayedClock& c) {
  std::vector<Observed> out;
  for (const auto& [key, time] : c.sent) {
    Observed o;
    o.episode = key / 1000000;
    o.tick = key % 1000000;
    o.module = 3;
    o.arrival = time + 0.002;
    o.hinge_angle = 0.5;
    out.push_back(o);
  }
  return out;
}

const Check& Named(const std::vector<Check>& checks, const std::string& start) {
  for (const auto& c : checks)
    if (c.name.rfind(start, 0) == 0) return c;
  FAIL("no check named " << start);
  return checks.front();
}

}  // namespace

TEST_CASE("a firmware that answers every clock at once passes every check") {
  const auto clock = Clock();
  const auto checks = JudgeFirmware(clock, Perfect(clock), 3, 0.5, -0.5, Budget{});
  std::string text;
  CHECK(PrintChecklist(checks, &text));
  CHECK(checks.size() == 7);
  CHECK_THAT(text, Catch::Contains("PASS one reading per tick, with the clock's episode and tick: "
                                   "8 ticks played: 0 without, 0 with several, 0 messages"));
  CHECK_THAT(text, Catch::Contains("median 2.0 ms, worst 2.0 ms"));
}

TEST_CASE("a missing, a repeated and a foreign reading each fail the one-per-tick check") {
  const auto clock = Clock();
  auto seen = Perfect(clock);
  seen.erase(seen.begin() + 2);  // tick 2 of episode 7: none
  seen.push_back(seen.front());  // tick 0: twice
  Observed foreign = seen.front();
  foreign.episode = 99;  // an episode never played
  seen.push_back(foreign);
  const auto checks = JudgeFirmware(clock, seen, 3, 0.5, -0.5, Budget{});
  const auto& c = Named(checks, "one reading per tick");
  CHECK_FALSE(c.pass);
  CHECK(c.evidence ==
        "8 ticks played: 1 without, 1 with several, 1 messages of no played "
        "(episode, tick)");
}

TEST_CASE("a reading from a timer of its own is late, or comes before START") {
  const auto clock = Clock();
  auto seen = Perfect(clock);
  seen[1].arrival += 0.040;  // 42 ms after its clock: over a 25 ms budget
  Observed early = seen.front();
  early.arrival = 0.5;  // before the first running clock
  seen.push_back(early);
  const auto checks = JudgeFirmware(clock, seen, 3, 0.5, -0.5, Budget{});
  CHECK_FALSE(Named(checks, "within the real-time budget").pass);
  CHECK(Named(checks, "within the real-time budget").evidence == "median 2.0 ms, worst 42.0 ms");
  CHECK_FALSE(Named(checks, "no reading before START").pass);
}

TEST_CASE("a firmware that does not join a running episode, or follows a foreign HINGE, fails") {
  const auto clock = Clock();
  auto seen = Perfect(clock);
  seen.erase(seen.begin() + 4);  // tick 10 of the late episode
  for (auto& o : seen)
    if (o.episode == 7) o.hinge_angle = -0.5;  // the foreign episode's target
  seen[5].module = 4;
  seen[6].problem = "values[2] is NaN";
  const auto checks = JudgeFirmware(clock, seen, 3, 0.5, -0.5, Budget{});
  CHECK_FALSE(Named(checks, "joins a running episode").pass);
  CHECK_FALSE(Named(checks, "follows HINGE of its episode").pass);
  CHECK(Named(checks, "readings name module 3").evidence == "1 name another");
  CHECK(Named(checks, "sizes and finite values").evidence == "1 wrong, first: values[2] is NaN");
}

TEST_CASE("a tracker is judged by the same timing rules") {
  const auto clock = Clock();
  auto states = Perfect(clock);
  std::string text;
  CHECK(PrintChecklist(JudgeTracker(clock, states, Budget{}), &text));
  states.pop_back();
  CHECK_FALSE(Named(JudgeTracker(clock, states, Budget{}), "one state per tick").pass);
}
