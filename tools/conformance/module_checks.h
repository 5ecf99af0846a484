// ahhs-conformance module: what the kit played to a module controller and what came back, and
// the checklist. The judge replays the kit's inputs through modules/core's hormone system, so a
// port to another language is checked bit for bit. Pure: no LCM, no clock.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "modules/core/genome.h"
#include "tools/conformance/checks.h"

namespace ahhs::conformance {

// One tick the kit played: the module's SENSORS and the neighbours' packets of tick - 1 that
// the protocol makes it add (in the order it must add them: increasing sender id).
struct PlayedTick {
  std::int64_t tick = 0;
  int segment = 0;  // index into PlayedEpisode::segments
  std::vector<double> sensors;
  std::vector<std::pair<int, std::vector<double>>> packets;
  double last_input = 0;     // when the kit sent the tick's last input (s since the start)
  bool lost_packet = false;  // a neighbour's packet withheld: the module steps after its timeout
};

struct PlayedEpisode {
  std::int64_t episode = 0;
  modules::Genome genome;
  std::vector<int> neighbours;  // increasing
  std::vector<std::string> segments;
  std::vector<PlayedTick> ticks;
  double ready_at = -1;          // first READY of this episode (s), -1 = none
  std::int64_t ready_hash = 0;   // the hash that READY carried
  bool repeat_asked = false;     // a repeated GENOME was sent before the first tick
  bool repeat_answered = false;  // ... and READY came again after it
};

// A HINGE or HORMONE the module published.
struct ModuleOutput {
  std::int64_t episode = 0, tick = 0;
  int module = 0;
  double arrival = 0;
  std::vector<double> values;   // HINGE values, or HORMONE amounts
  std::vector<bool> present;    // HINGE only
  double target_angle = 0;      // HINGE only
  std::vector<int> to_modules;  // HORMONE only
};

struct ModuleStatusSeen {
  int module = 0;
  std::int8_t state = 0;
  std::int64_t episode = 0;
};

struct ModuleRecord {
  int id = 0;
  std::vector<PlayedEpisode> episodes;
  std::vector<std::int64_t> foreign_episodes;  // episode ids of the foreign messages sent
  std::vector<ModuleOutput> hinges, hormones;
  std::vector<ModuleStatusSeen> statuses;
};

// The checklist: handshake and hash, READY again for a repeated GENOME, one HINGE and HORMONE
// per tick, sizes and values, equality to the model per segment, the lost packet, latency.
// `lost_packet_limit`: longest wait for a withheld packet (the sim's lockstep timeout / 2).
std::vector<Check> JudgeModule(const ModuleRecord& record, const Budget& budget,
                               double lost_packet_limit);

}  // namespace ahhs::conformance
