// ahhs-sim's three ways of running: serving episodes on the bus (SimNode), the episode server of
// a physical organism (--physics none), and one standalone episode with a built-in drive.
#pragma once

#include <cstdint>
#include <string>

#include "sim/core/envelope.h"
#include "sim/node/episode_server.h"
#include "sim/node/scenario_options.h"
#include "sim/node/sim_node.h"

namespace ahhs::sim {

// Serves episodes commanded on <ARENA>/SIM/CONTROL until SIGINT/SIGTERM or `episodes` ended
// (0: no limit). Returns the exit code.
int ServeBus(const std::string& url, const SimNodeOptions& options, int episodes, bool verbose);

// The episode server of a physical organism: stdin lines confirm that the organism is back.
int ServeEpisodes(const std::string& url, const EpisodeServerOptions& options, int episodes);

// One standalone episode with a built-in drive; prints its behaviour, cost and fitness last.
struct StandaloneOptions {
  const ScenarioOptions* scenario = nullptr;
  std::string drive = "zero";
  std::uint64_t seed = 1;
  bool verbose = false;
  Envelope envelope;
};
int RunStandalone(const StandaloneOptions& o);

}  // namespace ahhs::sim
