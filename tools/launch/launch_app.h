// ahhs-launch's command line, the episode it describes, and running it in a fused or a process
// arena (episode/arena).
#pragma once

#include <atomic>
#include <cstdint>
#include <string>

#include "base/cli.h"
#include "episode/arena/episode.h"
#include "sim/node/envelope_options.h"
#include "sim/node/scenario_options.h"

namespace ahhs::launch {

struct LaunchOptions {
  std::string genome_file, url, arena, log_file, logger = "ahhs-logger", external, hardware_modules;
  ahhs::sim::ScenarioOptions scenario;
  std::uint64_t seed = 1;
  std::string arena_kind = "processes";  // --arena-kind: processes or fused
  bool fused = false;                    // arena_kind is fused (or the deprecated --fused)
  bool realtime = false, verbose = false, overwrite = false;
  int timeout_s = 3600, lockstep_timeout_ms = 2000, external_timeout_s = 60;
  ahhs::sim::EnvelopeOptions envelope_options;
};

// Declares every option on `app`.
void AddLaunchOptions(base::cli::App& app, LaunchOptions* o);

// The episode the options describe (the genome file's stored seed unless --seed): 0, or the exit
// code with `error` (2: a usage error).
int SpecFromOptions(const base::cli::App& app, LaunchOptions* o,
                    const ahhs::sim::Envelope& envelope, ahhs::episode::EpisodeSpec* spec,
                    std::string* error);

// Runs the episode; prints what the roles dropped and "fitness: <value>" last. Returns the exit
// code (130 when `interrupted` stopped it).
int RunLaunch(LaunchOptions o, const ahhs::episode::EpisodeSpec& spec,
              const std::atomic<bool>& interrupted);

}  // namespace ahhs::launch
