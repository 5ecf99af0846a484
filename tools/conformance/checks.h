// ahhs-conformance's checklist (docs/hardware.md, "Conformance kit"): what an implementation
// under test sent, as plain records, judged against the protocol. Pure: no LCM, no clock.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ahhs::conformance {

struct Check {
  std::string name;
  bool pass = false;
  std::string evidence;
};

// The clock the kit played: episode ids and, per tick, when its SIM/CLOCK went out (seconds
// since the start of the test). Phase 1: ticks 0 .. ticks-1 of `episode`; phase 2 (a late
// start): ticks late_from .. late_from + ticks-1 of `late_episode`.
struct PlayedClock {
  std::int64_t episode = 0, late_episode = 0;
  int ticks = 0;
  int late_from = 0;
  double period = 0.05;
  double started = 0;                                 // when the first RUNNING clock went out
  std::vector<std::pair<std::int64_t, double>> sent;  // (episode * 1e6 + tick, time): see Key()
  static std::int64_t Key(std::int64_t episode, std::int64_t tick) {
    return episode * 1000000 + tick;
  }
};

// One message the implementation published, as the kit saw it.
struct Observed {
  std::int64_t episode = 0, tick = 0;
  int module = 0;
  double arrival = 0;      // seconds since the start of the test
  std::string problem;     // "" or why its sizes or values are wrong
  double hinge_angle = 0;  // firmware only
};

struct Budget {
  double latency = 0.025;  // seconds from SIM/CLOCK(t) to the message of tick t
};

// Firmware: SENSORS of module `id`. `commanded` is the hinge target of the second half of each
// phase; `foreign_target` the target of HINGE commands of a foreign episode that must be ignored.
std::vector<Check> JudgeFirmware(const PlayedClock& clock, const std::vector<Observed>& readings,
                                 int id, double commanded, double foreign_target,
                                 const Budget& budget);

// Tracker: SIM/STATE with a body of every module.
std::vector<Check> JudgeTracker(const PlayedClock& clock, const std::vector<Observed>& states,
                                const Budget& budget);

// "12.3 ms": a duration in seconds as evidence.
std::string Ms(double seconds);

// "PASS name: evidence" lines; returns whether every check passed.
bool PrintChecklist(const std::vector<Check>& checks, std::string* text);

}  // namespace ahhs::conformance
