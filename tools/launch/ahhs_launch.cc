// ahhs-launch: runs one episode of a genome in an arena made of separate processes (ahhs-sim,
// one ahhs-module per compartment, ahhs-fitness), or with --fused in this process (inproc://).
// Prints "fitness: <value>" as its last line. Every child is stopped on success, on error and on
// Ctrl-C; children also die with the launcher (PR_SET_PDEATHSIG).
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <iostream>

#include "base/cli.h"
#include "bus/lcm_bus.h"
#include "bus/open_bus.h"
#include "episode/arena/episode.h"
#include "episode/arena/fused_arena.h"
#include "episode/arena/process_arena.h"
#include "modules/core/genome_json.h"
#include "modules/core/random.h"
#include "sim/node/envelope_options.h"
#include "sim/node/scenario_options.h"

namespace ep = ahhs::episode;

namespace {

std::atomic<bool> g_interrupted{false};
void OnSignal(int) { g_interrupted = true; }

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "ahhs-launch: one episode of a genome in an arena of separate processes (or --fused)"};
  std::string genome_file, url, arena, log_file, logger = "ahhs-logger";
  ahhs::sim::ScenarioOptions task;
  std::uint64_t seed = 1;
  bool fused = false, realtime = false, verbose = false;
  int timeout_s = 3600;
  int lockstep_timeout_ms = 2000;
  task.Add(app, "", "episode length, simulated seconds (default: the task's)");
  app.add_option("--genome", genome_file, "genome file (docs/genome.md)")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--seed", seed,
                 "episode seed, 0 to 2^64-1 (default: the genome file's stored evaluation seed, "
                 "else 1)")
      ->check(ahhs::modules::SeedTextError);
  app.add_flag("--fused", fused,
               "run every node in this process (on inproc://, or memq:// with --lcm-url memq://)");
  app.add_flag("--realtime", realtime,
               "the sim keeps wall-clock pace; modules act on the latest messages");
  app.add_option("--log", log_file, "record the whole episode into this LCM log file");
  bool overwrite = false;
  app.add_flag("--overwrite", overwrite, "replace the --log file if it exists");
  app.add_option("--logger", logger,
                 "recorder for --log: ahhs-logger (keeps every message) or lcm-logger (Debian's "
                 "1.3.1 queues only 30 messages and can lose lockstep bursts)")
      ->check(CLI::IsMember({"ahhs-logger", "lcm-logger"}))
      ->capture_default_str();
  app.add_option("--lcm-url", url,
                 "bus URL: for the processes (default: host-only multicast); with --fused, "
                 "inproc:// (default) or memq://");
  app.add_option("--arena", arena, "arena name (default: unique per launch)");
  app.add_option("--timeout", timeout_s, "give up after this many seconds")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--lockstep-timeout-ms", lockstep_timeout_ms,
                 "longest wait of the sim for a module's command (modules wait a quarter of it for "
                 "their neighbours' packets, so that after a loss they still answer in time); 0: "
                 "exact lockstep, nobody goes on without a message and an episode that stalls "
                 "10 s fails, as in evolution")
      ->check(CLI::Range(0, 600000))
      ->capture_default_str();
  std::string external;
  int external_timeout_s = 60;
  app.add_option("--external", external,
                 "roles others play (hardware, other languages), not started here: sim, fitness, "
                 "module:N[,M...] or modules, comma-separated (docs/hardware.md); needs --arena");
  app.add_option("--external-timeout", external_timeout_s,
                 "seconds to wait for the external roles to answer the handshake")
      ->check(CLI::Range(1, 86400))
      ->capture_default_str();
  std::string hardware_modules;
  app.add_option("--hardware-modules", hardware_modules,
                 "real time, gait: modules whose bodies are hardware (N[,M...]); the sim follows "
                 "their firmware's hinge_angle and leaves their SENSORS to it (docs/hardware.md)");
  app.add_flag("-v,--verbose", verbose, "show the children's output");
  ahhs::sim::EnvelopeOptions envelope_options;
  envelope_options.Add(app,
                       "an envelope of noise for the episode, drawn from its seed (default none; "
                       "docs/scenarios.md)");
  if (const int code = ahhs::cli::Parse(app, argc, argv); code >= 0) return code;
  ahhs::sim::Envelope envelope;
  try {
    envelope = envelope_options.Resolve();
  } catch (const std::invalid_argument& e) {
    std::cerr << "ahhs-launch: " << e.what() << '\n';
    return ahhs::cli::kExitUsage;
  }

  ep::EpisodeSpec spec;
  try {
    if (task.duration_given() && !(task.duration > 0))
      throw std::invalid_argument("--duration must be positive");
    spec.config = task.Config();
    spec.config.envelope = envelope;
    const std::string config_error = ahhs::sim::CheckConfig(spec.config);
    if (!config_error.empty()) throw std::invalid_argument(config_error);
    nlohmann::json meta;
    spec.genome = ahhs::modules::LoadGenomeFile(genome_file, &meta);
    if (!app.count("--seed")) {
      if (const auto stored = ahhs::modules::StoredEvalSeed(meta)) {
        seed = *stored;
        std::printf("seed %llu: the evaluation seed stored in %s\n",
                    static_cast<unsigned long long>(seed), genome_file.c_str());
      }
    }
    const std::string fit = ep::CheckGenomeFits(spec.genome, spec.config);
    if (!fit.empty()) throw std::invalid_argument(genome_file + ": " + fit);
    if (const std::string exists = ahhs::cli::RefuseExisting({log_file}, overwrite);
        !exists.empty()) {
      std::cerr << "ahhs-launch: " << exists << '\n';
      return ahhs::cli::kExitUsage;
    }
    if (fused && !log_file.empty())
      throw std::invalid_argument(
          "--log records bus traffic; it needs the process arena, not --fused");
    if (fused && !url.empty() && !ahhs::bus::IsInProcessUrl(url))
      throw std::invalid_argument(
          "--fused runs in this process: --lcm-url must be inproc:// or "
          "memq://, not '" +
          url + "'");
    if (!fused && ahhs::bus::IsInProcessUrl(url))
      throw std::invalid_argument("'" + url + "' stays inside one process: use it with --fused");
    if (!hardware_modules.empty() && (fused || !realtime))
      throw std::invalid_argument("--hardware-modules needs the process arena and --realtime");
    if (!external.empty()) {
      if (fused) throw std::invalid_argument("--external needs the process arena, not --fused");
      if (arena.empty())
        throw std::invalid_argument(
            "--external needs --arena NAME: the external roles must know it");
      spec.external =
          ep::ParseExternalRoles(external, ahhs::sim::ShapeOf(spec.config).compartments);
    }
  } catch (const std::exception& e) {
    std::cerr << "ahhs-launch: " << e.what() << '\n';
    return 1;
  }
  spec.seed = seed;
  spec.realtime = realtime;
  if (fused && !url.empty()) spec.fused_url = url;
  spec.episode = static_cast<std::int64_t>(getpid()) * 1000 + 1;
  spec.arena = arena.empty() ? "AHHS" + std::to_string(getpid()) : arena;
  spec.episode_timeout = std::chrono::seconds(timeout_s);
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);

  ep::EpisodeResult result;
  if (fused) {
    result = ep::RunFused(spec);
  } else {
    if (url.empty()) url = ahhs::bus::kDefaultLcmUrl;
    try {
      ep::ProcessArenaOptions options;
      options.url = url;
      options.arena = spec.arena;
      options.num_modules = spec.config.num_modules;
      options.lockstep_timeout_ms = lockstep_timeout_ms;
      options.verbose = verbose;
      options.log_file = log_file;
      options.logger = logger;
      options.external = spec.external;
      options.hardware_modules = hardware_modules;
      options.external_timeout = std::chrono::seconds(external_timeout_s);
      ep::ProcessArena arena_processes(options);
      if (!spec.external.empty())
        std::printf("arena %s on %s: waiting up to %d s for %s (external)\n", spec.arena.c_str(),
                    url.c_str(), external_timeout_s,
                    ep::DescribeExternalRoles(spec.external).c_str());
      std::fflush(stdout);
      result = arena_processes.Run(spec, [](std::string* why) {
        if (!g_interrupted) return true;
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
    return g_interrupted ? 130 : 2;
  }
  std::printf(
      "scenario %s, seed %llu, %s arena%s; ticks without a state at the fitness monitor: %d\n",
      ahhs::sim::ScenarioName(spec.config.kind), static_cast<unsigned long long>(seed),
      fused ? "fused" : "process", realtime ? ", real time" : "", result.states_missed);
  std::printf("fitness: %.17g\n", result.fitness);
  return 0;
}
