#include "tools/launch/launch_app.h"

#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <string>

#include "base/cli.h"
#include "base/format.h"
#include "bus/lcm_bus.h"
#include "bus/open_bus.h"
#include "episode/arena/fused_arena.h"
#include "episode/arena/process_arena.h"
#include "episode/fitness/fitness_monitor.h"
#include "modules/core/genome_json.h"
#include "modules/core/random.h"

namespace cli = ahhs::base::cli;

namespace ahhs::launch {

namespace ep = ahhs::episode;

void AddLaunchOptions(cli::App& app, LaunchOptions* o) {
  o->scenario.Add(app, "", "episode length, simulated seconds (default: the scenario's)");
  o->scenario.AddPhysics(app);
  app.add_option("--genome", o->genome_file, "genome file (docs/genome.md)")
      ->required()
      ->check(cli::ExistingFile);
  app.add_option("--seed", o->seed,
                 "episode seed, 0 to 2^64-1 (default: the genome file's stored evaluation seed, "
                 "else 1)")
      ->check(ahhs::modules::SeedTextError);
  cli::Option* kind =
      app.add_option("--arena-kind", o->arena_kind,
                     "how the episode runs: processes (one per role, over --lcm-url) or fused "
                     "(every node in this process, on inproc://, or memq:// with --lcm-url "
                     "memq://), as ahhs-evolve's and ahhs-worker's --arena-kind")
          ->check(cli::IsMember({"processes", "fused"}))
          ->capture_default_str();
  // The old flag, for one release: it says what replaced it.
  app.add_flag("--fused", o->fused, "deprecated: use --arena-kind fused")->excludes(kind);
  app.add_flag("--realtime", o->realtime,
               "the sim keeps wall-clock pace; modules act on the latest messages");
  app.add_option("--log", o->log_file, "record the whole episode into this LCM log file");
  app.add_flag("--overwrite", o->overwrite, "replace the --log file if it exists");
  app.add_option("--logger", o->logger,
                 "recorder for --log: ahhs-logger (keeps every message) or lcm-logger (Debian's "
                 "1.3.1 queues only 30 messages and can lose lockstep bursts)")
      ->check(cli::IsMember({"ahhs-logger", "lcm-logger"}))
      ->capture_default_str();
  app.add_option("--lcm-url", o->url,
                 "bus URL: for the processes (default: host-only multicast); with --arena-kind "
                 "fused, inproc:// (default) or memq://");
  app.add_option("--arena", o->arena, "arena name (default: unique per launch)");
  app.add_option("--timeout", o->timeout_s, "give up after this many seconds")
      ->check(cli::PositiveNumber)
      ->capture_default_str();
  app.add_option("--lockstep-timeout-ms", o->lockstep_timeout_ms,
                 "longest wait of the sim for a module's command (modules wait a quarter of it for "
                 "their neighbours' packets, so that after a loss they still answer in time); 0: "
                 "exact lockstep, nobody goes on without a message and an episode that stalls "
                 "10 s fails, as in evolution")
      ->check(cli::Range(0, 600000))
      ->capture_default_str();
  app.add_option("--external", o->external,
                 "roles others play (hardware, other languages), not started here: sim, fitness, "
                 "module:N[,M...] or modules, comma-separated (docs/hardware.md); needs --arena");
  app.add_option("--external-timeout", o->external_timeout_s,
                 "seconds to wait for the external roles to answer the handshake")
      ->check(cli::Range(1, 86400))
      ->capture_default_str();
  app.add_option("--hardware-modules", o->hardware_modules,
                 "real time, gait: modules whose bodies are hardware (N[,M...]); the sim follows "
                 "their firmware's hinge_angle and leaves their SENSORS to it (docs/hardware.md)");
  app.add_flag("-v,--verbose", o->verbose, "show the children's output");
  o->envelope_options.Add(
      app,
      "an envelope of noise for the episode, drawn from its seed (default none; "
      "docs/scenarios.md)");
}

int SpecFromOptions(const cli::App& app, LaunchOptions* o, const ahhs::sim::Envelope& envelope,
                    ep::EpisodeSpec* spec, std::string* error) {
  if (app.count("--fused") > 0)
    std::cerr << "ahhs-launch: --fused is deprecated and will go; use --arena-kind fused\n";
  o->fused = o->fused || o->arena_kind == "fused";
  try {
    if (o->scenario.duration_given() && !(o->scenario.duration > 0))
      throw std::invalid_argument("--duration must be positive");
    spec->config = o->scenario.Config();
    spec->config.envelope = envelope;
    const std::string config_error = ahhs::sim::CheckConfig(spec->config);
    if (!config_error.empty()) throw std::invalid_argument(config_error);
    nlohmann::json meta;
    spec->genome = ahhs::modules::LoadGenomeFile(o->genome_file, &meta);
    if (!app.count("--seed")) {
      if (const auto stored = ahhs::modules::StoredEvalSeed(meta)) {
        o->seed = *stored;
        std::printf("seed %llu: the evaluation seed stored in %s\n",
                    static_cast<unsigned long long>(o->seed), o->genome_file.c_str());
      }
    }
    const std::string fit = ep::CheckGenomeFits(spec->genome, spec->config);
    if (!fit.empty()) throw std::invalid_argument(o->genome_file + ": " + fit);
    if (const std::string exists = ahhs::base::RefuseExisting({o->log_file}, o->overwrite);
        !exists.empty()) {
      *error = exists;
      return ahhs::base::kExitUsage;
    }
    if (o->fused && !o->log_file.empty())
      throw std::invalid_argument(
          "--log records bus traffic; it needs the process arena, not --arena-kind fused");
    if (o->fused && !o->url.empty() && !ahhs::bus::IsInProcessUrl(o->url))
      throw std::invalid_argument(
          "--arena-kind fused runs in this process: --lcm-url must be inproc:// or "
          "memq://, not '" +
          o->url + "'");
    if (!o->fused && ahhs::bus::IsInProcessUrl(o->url))
      throw std::invalid_argument("'" + o->url +
                                  "' stays inside one process: use it with --arena-kind fused");
    if (!o->hardware_modules.empty() && (o->fused || !o->realtime))
      throw std::invalid_argument("--hardware-modules needs the process arena and --realtime");
    if (!o->external.empty()) {
      if (o->fused)
        throw std::invalid_argument("--external needs the process arena, not --arena-kind fused");
      if (o->arena.empty())
        throw std::invalid_argument(
            "--external needs --arena NAME: the external roles must know it");
      spec->external =
          ep::ParseExternalRoles(o->external, ahhs::sim::ShapeOf(spec->config).compartments);
    }
  } catch (const std::exception& e) {
    *error = e.what();
    return 1;
  }
  spec->seed = o->seed;
  spec->realtime = o->realtime;
  if (o->fused && !o->url.empty()) spec->fused_url = o->url;
  spec->episode = static_cast<std::int64_t>(getpid()) * 1000 + 1;
  spec->arena = o->arena.empty() ? "AHHS" + std::to_string(getpid()) : o->arena;
  spec->episode_timeout = std::chrono::seconds(o->timeout_s);
  return 0;
}

int RunLaunch(LaunchOptions o, const ep::EpisodeSpec& spec, const std::atomic<bool>& interrupted) {
  ep::EpisodeResult result;
  if (o.fused) {
    result = ep::RunFused(spec);
  } else {
    if (o.url.empty()) o.url = ahhs::bus::kDefaultLcmUrl;
    try {
      ep::ProcessArenaOptions options;
      options.url = o.url;
      options.arena = spec.arena;
      options.num_modules = spec.config.num_modules;
      options.lockstep_timeout_ms = o.lockstep_timeout_ms;
      options.verbose = o.verbose;
      options.log_file = o.log_file;
      options.logger = o.logger;
      options.external = spec.external;
      options.hardware_modules = o.hardware_modules;
      options.external_timeout = std::chrono::seconds(o.external_timeout_s);
      ep::ProcessArena arena_processes(options);
      if (!spec.external.empty())
        std::printf("arena %s on %s: waiting up to %d s for %s (external)\n", spec.arena.c_str(),
                    o.url.c_str(), o.external_timeout_s,
                    ep::DescribeExternalRoles(spec.external).c_str());
      std::fflush(stdout);
      result = arena_processes.Run(spec, [&](std::string* why) {
        if (!interrupted) return true;
        *why = "interrupted";
        return false;
      });
      if (result.ok) arena_processes.FinishLog();
    } catch (const std::exception& e) {
      result.ok = false;
      result.error = e.what();
    }
  }
  // What the roles dropped, per channel and reason: a bring-up sees it without -v.
  for (const auto& line : result.drops) std::printf("dropped: %s\n", line.c_str());
  if (!result.ok) {
    std::cerr << "ahhs-launch: episode failed: " << result.error << '\n';
    return interrupted ? 130 : 2;
  }
  std::printf(
      "scenario %s, seed %llu, %s arena%s; ticks without a state at the fitness monitor: %d\n",
      ahhs::sim::ScenarioName(spec.config.kind), static_cast<unsigned long long>(o.seed),
      o.fused ? "fused" : "process", o.realtime ? ", real time" : "", result.states_missed);
  // The behaviour descriptor (docs/scenarios.md, "Behaviour descriptors"), exact.
  const auto names = ahhs::episode::FitnessMonitor::DescriptorNames(spec.config.kind);
  std::string descriptor;
  for (std::size_t j = 0; j < result.descriptor.size() && j < names.size(); ++j)
    descriptor += (j ? ", " : "") + names[j] + " " + ahhs::base::ExactDouble(result.descriptor[j]);
  if (!descriptor.empty()) std::printf("descriptor: %s\n", descriptor.c_str());
  std::printf("fitness: %.17g\n", result.fitness);
  return 0;
}

}  // namespace ahhs::launch
