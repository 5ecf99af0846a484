// Channel names of the protocol (docs/protocol.md). Arena channels carry the arena's prefix so
// several arenas share one bus; the evaluation farm's channels have none.
#pragma once

#include <cstdint>
#include <string>

namespace ahhs::bus {

inline constexpr const char* kDefaultArena = "AHHS";

class ArenaChannels {
 public:
  explicit ArenaChannels(std::string arena = kDefaultArena) : p_(std::move(arena) + "/") {}

  std::string Sensors(int module) const {
    return p_ + "MODULE" + std::to_string(module) + "/SENSORS";
  }
  std::string Hinge(int module) const { return p_ + "MODULE" + std::to_string(module) + "/HINGE"; }
  std::string Hormone(int module) const {
    return p_ + "MODULE" + std::to_string(module) + "/HORMONE";
  }
  std::string Status(int module) const {
    return p_ + "MODULE" + std::to_string(module) + "/STATUS";
  }
  // Written by ahhs-replay into its logs only (module_trace_t).
  std::string Trace(int module) const { return p_ + "MODULE" + std::to_string(module) + "/TRACE"; }
  std::string Topology() const { return p_ + "TOPOLOGY"; }
  std::string SimControl() const { return p_ + "SIM/CONTROL"; }
  std::string SimClock() const { return p_ + "SIM/CLOCK"; }
  std::string SimState() const { return p_ + "SIM/STATE"; }
  std::string SimScene() const { return p_ + "SIM/SCENE"; }
  std::string Genome() const { return p_ + "GENOME"; }
  std::string Fitness() const { return p_ + "FITNESS"; }

 private:
  std::string p_;
};

inline constexpr const char* kEvalRequestChannel = "EVAL/REQUEST";
inline constexpr const char* kEvalGenomeChannel = "EVAL/GENOME";
inline constexpr const char* kEvalWantChannel = "EVAL/WANT";
inline constexpr const char* kEvalResultChannel = "EVAL/RESULT";
inline constexpr const char* kWorkerStatusChannel = "WORKER/STATUS";

// Microseconds since the Unix epoch, for the utime field of every message.
std::int64_t NowUtime();

}  // namespace ahhs::bus
