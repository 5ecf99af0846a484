// ahhs-conformance sim: what the kit asked of an episode server (a sim in real time, or the
// server of a physical organism) and what it published, and the checklist. Pure: no LCM, no
// clock.
#pragma once

#include <cstdint>
#include <vector>

#include "tools/conformance/checks.h"

namespace ahhs::conformance {

struct SimPlayed {
  int modules = 3;  // gait chain
  int ticks = 40;   // T: ticks of a full episode (duration / period)
  double period = 0.05;
  std::int64_t full = 0, stopped = 0, bad = 0, foreign = 0;  // episode ids
  double full_reset_sent = -1, stopped_reset_sent = -1;      // first RESET of each (s)
  double foreign_sent = -1;  // a foreign episode's PAUSE and STOP, during the full episode
  double stop_sent = -1;     // STOP of the stopped episode
};

struct ClockSeen {
  std::int64_t episode = 0, tick = 0;
  std::int8_t state = 0, mode = 0;
  double sim_time = 0, control_period = 0, arrival = 0;
};

struct TopologySeen {
  std::int64_t episode = 0;
  double arrival = 0;
  bool chain = false;  // num_modules and links are the gait chain of SimPlayed::modules
};

struct SensorsSeen {
  std::int64_t episode = 0, tick = 0;
  int module = 0;
};

struct SimRecord {
  SimPlayed played;
  std::vector<ClockSeen> clocks;
  std::vector<TopologySeen> topologies;
  std::vector<SensorsSeen> sensors;
};

// The checklist: RESET answered with the clock and TOPOLOGY, the chain repeated while running,
// one clock per tick in order at real-time pace, a foreign episode's commands ignored, the end
// (three FINISHED), STOP, a bad RESET refused, SENSORS all or none.
std::vector<Check> JudgeSim(const SimRecord& record, const Budget& budget);

}  // namespace ahhs::conformance
