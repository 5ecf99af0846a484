// One episode of the paper's scenarios as an arena runs it: what to run (EpisodeSpec) and what came
// out (EpisodeResult). Every arena (episode/arena/arena.h) gives the same result to the bit.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "episode/arena/external_roles.h"
#include "modules/core/genome.h"
#include "sim/core/scenario.h"

namespace ahhs::episode {

struct EpisodeSpec {
  sim::ScenarioConfig config;
  modules::Genome genome;
  std::uint64_t seed = 1;    // the episode seed (on the wire: its bits in sim_control_t.seed)
  std::int64_t episode = 1;  // unique on the bus
  bool realtime = false;
  std::string arena = "AHHS";
  std::chrono::seconds handshake_timeout{20};
  // Roles played by processes the arena did not start (hardware, other languages): the
  // handshake then waits up to `external_timeout` (instead of `handshake_timeout`), and its
  // message names them.
  ExternalRoles external;
  std::chrono::seconds external_timeout{60};
  // Real time only: start without the modules that have not answered after this long (a
  // physical module may come later and join the running episode).
  std::chrono::milliseconds realtime_join_wait{1500};
  std::chrono::seconds episode_timeout{3600};
  // Lockstep: fail when neither the sim's clock nor the fitness monitor shows progress for this
  // long after START (0 = never). Exact lockstep stalls on a lost datagram instead of going on.
  std::chrono::seconds stall_timeout{0};
  // The fused arena's bus: inproc:// (bus/in_process_bus.h, the default: no system call per
  // message) or memq:// (LCM's in-process provider). Results are the same to the bit.
  std::string fused_url = "inproc://";
};

struct EpisodeResult {
  bool ok = false;
  double fitness = 0;
  double cost = 0;
  // The behaviour descriptor (FitnessMonitor::descriptor): pendulum 2 values, gait 2.
  std::vector<double> descriptor;
  std::string error;
  int states_missed = 0;
  // The episode itself failed (physics blew up; `error` says how): a property of the genome
  // and seed, not of the arena. False for arena failures (timeouts, dead processes).
  bool episode_failed = false;
  // What the roles reported dropping, one line each ("module 2: 11 SENSORS (NaN or out of
  // [0, 1])", "fitness monitor: 3 SIM/STATE (another episode)"): from the modules' last STATUS and
  // the monitor's final FITNESS. Empty when nothing was dropped.
  std::vector<std::string> drops;

  static EpisodeResult Failure(std::string why) {
    EpisodeResult r;
    r.error = std::move(why);
    return r;
  }
};

// Checks the genome's sensor/actuator shape against the scenario; "" or a clear message.
std::string CheckGenomeFits(const modules::Genome& genome, const sim::ScenarioConfig& config);

}  // namespace ahhs::episode
