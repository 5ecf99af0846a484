// The launcher's protocol role: one episode with a given genome on a bus where a sim, one module
// per compartment and a fitness monitor listen (docs/protocol.md, "Episode"). Used by ahhs-launch
// for separate processes and for the fused arena, where all nodes run in this process.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "bus/bus.h"
#include "modules/core/genome.h"
#include "modules/core/organism.h"
#include "sim/core/scenario.h"

namespace ahhs::launch {

struct EpisodeSpec {
  sim::ScenarioConfig config;
  modules::Genome genome;
  std::uint64_t seed = 1;    // the episode seed (on the wire: its bits in sim_control_t.seed)
  std::int64_t episode = 1;  // unique on the bus
  bool realtime = false;
  std::string arena = "AHHS";
  std::chrono::seconds handshake_timeout{20};
  // Real time only: start without the modules that have not answered after this long (a
  // physical module may come later and join the running episode).
  std::chrono::milliseconds realtime_join_wait{1500};
  std::chrono::seconds episode_timeout{3600};
  // The fused arena's bus: inproc:// (bus/in_process_bus.h, the default: no system call per
  // message) or memq:// (LCM's in-process provider). Results are the same to the bit.
  std::string fused_url = "inproc://";
};

struct EpisodeResult {
  bool ok = false;
  double fitness = 0;
  double cost = 0;
  std::string error;
  int states_missed = 0;
  // The episode itself failed (physics blew up; `error` says how): a property of the genome
  // and seed, not of the arena. False for arena failures (timeouts, dead processes).
  bool episode_failed = false;
};

// Checks the genome's sensor/actuator shape against the scenario; "" or a clear message.
std::string CheckGenomeFits(const modules::Genome& genome, const sim::ScenarioConfig& config);

// Runs the episode on `bus`. `pump(wait)` must dispatch the bus (and, for the fused arena, poll
// every node); `alive()` is asked every loop and aborts the episode when it returns false (e.g.
// a child process died or Ctrl-C); its message goes into the result.
EpisodeResult RunEpisode(bus::Bus& bus, const EpisodeSpec& spec,
                         const std::function<void(std::chrono::microseconds)>& pump,
                         const std::function<bool(std::string*)>& alive);

// The fused arena: sim node, one module node per compartment and the fitness node in this
// process on a fresh bus of `spec.fused_url`. A URL that leaves the process is an error result.
EpisodeResult RunFused(const EpisodeSpec& spec);

// What RunDirectEpisode shows an observer after every tick (ahhs-replay's trace): the sensors
// the controllers read in the tick, the organism after its step, the scenario after the tick's
// physics.
struct DirectTick {
  std::int64_t tick = 0;  // the tick just completed, 0-based
  const sim::Scenario* scenario = nullptr;
  const modules::Organism* organism = nullptr;
  const std::vector<std::vector<double>>* sensors = nullptr;  // [compartment][slot]
};
using DirectObserver = std::function<void(const DirectTick&)>;

// The reference without any bus: scenario and organism stepped in one loop (lockstep order).
// Returns the scenario's own fitness and cost; the arenas must reproduce them.
EpisodeResult RunDirectEpisode(const EpisodeSpec& spec, const DirectObserver& observer = {});
// RunDirectEpisode's fitness (tests and benchmarks of episodes that do not fail).
double RunDirect(const EpisodeSpec& spec);

// Directory of the running executable (where ahhs-launch finds ahhs-sim and the others).
std::string ExecutableDir();

}  // namespace ahhs::launch
