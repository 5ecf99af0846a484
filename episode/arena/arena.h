// The arena layer: one interface that runs an episode, whatever runs it (docs/development.md,
// "Map of the code"):
//   direct     scenario and controllers stepped in one loop, no bus (the fastest)
//   fused      the arena's node classes in this process on an in-process bus
//   processes  ahhs-sim, ahhs-fitness and ahhs-module processes over LCM, kept between episodes
// Every kind gives the same EpisodeResult to the bit (tests/arena, tests/evolver).
#pragma once

#include <chrono>
#include <memory>
#include <string>

#include "episode/arena/episode.h"

namespace ahhs::episode {

enum class ArenaKind { kDirect, kFused, kProcesses };
ArenaKind ParseArenaKind(const std::string& name);  // throws std::invalid_argument
const char* ArenaKindName(ArenaKind kind);

class Arena {
 public:
  virtual ~Arena() = default;
  // Runs one episode. Arena failures (a dead process, a timeout) are results with ok = false
  // and episode_failed = false; the arena may then be unhealthy and should be made again.
  virtual EpisodeResult Run(const EpisodeSpec& spec) = 0;
  virtual bool healthy() const { return true; }
};

struct ArenaOptions {
  ArenaKind kind = ArenaKind::kDirect;
  // The process arena only: LCM URL and channel prefix of its own traffic.
  std::string url;
  std::string name = "AHHS";
  // Roles others play (ParseExternalRoles text, checked against each scenario's modules), and
  // how long an episode waits for them.
  std::string external;
  std::chrono::seconds external_timeout{60};
  // Episodes at wall-clock pace (a physical organism): the process arena only.
  bool realtime = false;
};

// An arena for episodes of `config`'s shape (the process arena starts one module per
// compartment). Throws std::runtime_error when its processes cannot be started, and
// std::invalid_argument for external roles that do not fit the scenario.
std::unique_ptr<Arena> MakeArena(const ArenaOptions& options, const sim::ScenarioConfig& config);

}  // namespace ahhs::episode
