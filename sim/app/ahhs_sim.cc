// ahhs-sim: the ODE arena.
//   bus mode (default): serves episodes commanded on <ARENA>/SIM/CONTROL (docs/protocol.md);
//   --physics none: the episode server of a physical organism (clock and topology only);
//   standalone mode (--drive): one episode with built-in commands, "fitness: <value>" last.
#include <poll.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <iostream>

#include "base/cli.h"
#include "bus/fault_bus.h"
#include "bus/lcm_bus.h"
#include "modules/core/random.h"
#include "sim/core/behaviour.h"
#include "sim/core/drive.h"
#include "sim/core/scenario.h"
#include "sim/node/envelope_options.h"
#include "sim/node/episode_server.h"
#include "sim/node/scenario_options.h"
#include "sim/node/sim_node.h"

namespace as = ahhs::sim;

namespace {

std::atomic<bool> g_stop{false};
void OnSignal(int) { g_stop = true; }

int ServeBus(const std::string& url, const as::SimNodeOptions& options, int episodes,
             bool verbose) {
  auto bus = ahhs::bus::OpenBusWithFaultInjection(url);
  as::SimNode node(bus.get(), options);
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  std::fprintf(stderr, "ahhs-sim: serving arena '%s' on %s\n", options.arena.c_str(), url.c_str());
  int ended = 0;
  auto last_phase = node.phase();
  while (!g_stop) {
    node.Poll(std::chrono::milliseconds(100));
    const auto phase = node.phase();
    if (phase == last_phase) continue;
    last_phase = phase;
    if (verbose)
      std::fprintf(stderr, "ahhs-sim: episode %lld %s\n", static_cast<long long>(node.episode()),
                   as::PhaseName(phase));
    if (phase != as::SimNode::Phase::kFinished && phase != as::SimNode::Phase::kFailed) continue;
    const auto s = node.stats();
    std::fprintf(
        stderr,
        "ahhs-sim: episode %lld %s after %lld ticks, fitness %.17g; missed %llu, late %llu, "
        "dropped %llu, hardware readings followed %llu%s%s\n",
        static_cast<long long>(node.episode()), as::PhaseName(phase),
        static_cast<long long>(node.scenario()->tick()),
        phase == as::SimNode::Phase::kFinished ? node.scenario()->Fitness() : 0.0,
        static_cast<unsigned long long>(s.missed_commands),
        static_cast<unsigned long long>(s.late_commands),
        static_cast<unsigned long long>(s.dropped_messages),
        static_cast<unsigned long long>(s.twin_readings), s.last_error.empty() ? "" : "; ",
        s.last_error.c_str());
    if (!s.drops.empty()) std::fprintf(stderr, "ahhs-sim: dropped so far: %s\n", s.drops.c_str());
    if (episodes > 0 && ++ended >= episodes) break;
  }
  return 0;
}

// The episode server of a physical organism: stdin lines confirm that the organism is back.
int ServeEpisodes(const std::string& url, const as::EpisodeServerOptions& options, int episodes) {
  auto bus = ahhs::bus::OpenBusWithFaultInjection(url);
  auto say = [](const std::string& line) { std::fprintf(stderr, "ahhs-sim: %s\n", line.c_str()); };
  as::EpisodeServer server(bus.get(), options, say);
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  std::fprintf(stderr, "ahhs-sim: episode server (no physics) for arena '%s' on %s%s\n",
               options.arena.c_str(), url.c_str(),
               options.confirm ? "; confirm each episode with Enter or SIM/CONTROL CONFIRM" : "");
  bool stdin_open = options.confirm;
  int ended = 0;
  auto last_phase = server.phase();
  while (!g_stop) {
    server.Poll(std::chrono::milliseconds(20));
    if (stdin_open) {
      pollfd in{0, POLLIN, 0};
      if (poll(&in, 1, 0) > 0) {
        char buffer[256];
        const ssize_t n = read(0, buffer, sizeof buffer);
        if (n <= 0) {
          stdin_open = false;  // end of input: confirmations come as SIM/CONTROL CONFIRM only
        } else {
          for (ssize_t k = 0; k < n; ++k)
            if (buffer[k] == '\n') server.Confirm();
        }
      }
    }
    const auto phase = server.phase();
    if (phase == last_phase) continue;
    last_phase = phase;
    if (phase == as::EpisodeServer::Phase::kFinished && !server.drops().empty())
      std::fprintf(stderr, "ahhs-sim: dropped so far: %s\n", server.drops().c_str());
    if (phase == as::EpisodeServer::Phase::kFinished && episodes > 0 && ++ended >= episodes) break;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "ahhs-sim: physics of the gait and pendulum arenas.\n"
      "Without --drive it serves episodes on the bus; with --drive it runs one standalone."};
  std::string url = ahhs::bus::kDefaultLcmUrl;
  as::SimNodeOptions node_options;
  int timeout_ms = 2000;
  int episodes = 0;
  int min_tick_us = 0;
  app.add_option("--lcm-url", url, "LCM URL (bus mode)")->capture_default_str();
  app.add_option("--arena", node_options.arena, "arena name: channel prefix (bus mode)")
      ->capture_default_str();
  app.add_option("--lockstep-timeout-ms", timeout_ms,
                 "bus mode: longest wait for a module's command (0: wait for every command, "
                 "exact lockstep)")
      ->check(CLI::Range(0, 600000))
      ->capture_default_str();
  app.add_option("--min-tick-us", min_tick_us,
                 "bus mode, lockstep: at least this many microseconds of wall time per tick")
      ->check(CLI::Range(0, 10000000))
      ->capture_default_str();
  app.add_option(
         "--state-rate", node_options.state_rate,
         "bus mode: SIM/STATE messages per simulated second (0 = once per tick in lockstep, "
         "40 in real time)")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();
  app.add_option("--episodes", episodes,
                 "bus mode: exit after this many episodes (0 = serve until killed)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  std::string drive = "zero";
  as::ScenarioOptions task;
  std::uint64_t seed = 1;
  bool verbose = false;
  task.Add(app, "", "episode length, simulated seconds (default: the task's)");
  auto* drive_opt = app.add_option(
      "--drive", drive,
      "standalone: built-in commands: zero, wave, swingup (pendulum) or inchworm (gait)");
  app.add_option("--seed", seed, "episode seed")
      ->check(ahhs::modules::SeedTextError)
      ->capture_default_str();
  app.add_flag("-v,--verbose", verbose, "print the state once per simulated second");
  std::vector<int> hardware_modules;
  app.add_option("--hardware-modules", hardware_modules,
                 "bus mode, real time, gait: these modules' bodies are hardware; their firmware "
                 "publishes their SENSORS and their simulated bodies follow the hinge_angle it "
                 "reports (docs/hardware.md)")
      ->delimiter(',')
      ->check(CLI::Range(0, 32767));
  std::string physics = "ode";
  as::EpisodeServerOptions server_options;
  int confirm_timeout_s = 600;
  bool no_confirm = false;
  app.add_option("--physics", physics,
                 "bus mode: ode (simulate the organism) or none (episode server of a physical "
                 "organism: clock and topology only, docs/hardware.md)")
      ->check(CLI::IsMember({"ode", "none"}))
      ->capture_default_str();
  app.add_flag("--no-confirm", no_confirm,
               "--physics none: start each episode without waiting for the operator");
  app.add_option("--confirm-timeout", confirm_timeout_s,
                 "--physics none: seconds to wait for the operator's confirmation before giving "
                 "an episode up")
      ->check(CLI::Range(1, 86400))
      ->capture_default_str();
  as::EnvelopeOptions envelope_options;
  envelope_options.Add(app,
                       "with --drive: an envelope of noise drawn from --seed (default none; in bus "
                       "mode each RESET brings its own; docs/scenarios.md)");
  if (const int code = ahhs::cli::Parse(app, argc, argv); code >= 0) return code;
  as::Envelope envelope;
  try {
    envelope = envelope_options.Resolve();
    if (envelope_options.given() && drive_opt->count() == 0)
      throw std::invalid_argument("--envelope needs --drive (in bus mode RESET brings it)");
  } catch (const std::invalid_argument& e) {
    std::cerr << "ahhs-sim: " << e.what() << '\n';
    return ahhs::cli::kExitUsage;
  }

  if (physics == "none") {
    if (drive_opt->count() > 0 || !hardware_modules.empty()) {
      std::cerr << "ahhs-sim: --drive and --hardware-modules need the physics; --physics none "
                   "serves the bus only\n";
      return ahhs::cli::kExitUsage;
    }
    try {
      server_options.arena = node_options.arena;
      server_options.confirm = !no_confirm;
      server_options.confirm_timeout = std::chrono::seconds(confirm_timeout_s);
      return ServeEpisodes(url, server_options, episodes);
    } catch (const std::exception& e) {
      std::cerr << "ahhs-sim: " << e.what() << '\n';
      return 1;
    }
  }
  node_options.hardware_modules.insert(hardware_modules.begin(), hardware_modules.end());
  if (drive_opt->count() == 0) {
    try {
      node_options.lockstep_timeout = std::chrono::milliseconds(timeout_ms);
      node_options.min_tick_period = std::chrono::microseconds(min_tick_us);
      return ServeBus(url, node_options, episodes, verbose);
    } catch (const std::exception& e) {
      std::cerr << "ahhs-sim: " << e.what() << '\n';
      return 1;
    }
  }
  try {
    if (task.duration_given() && !(task.duration > 0))
      throw std::invalid_argument("--duration must be a positive number of seconds");
    as::ScenarioConfig config = task.Config();
    config.envelope = envelope;
    if (config.kind == as::ScenarioKind::kGait && task.modules < 2)
      throw std::invalid_argument("--modules: a gait organism needs at least 2 modules");
    const as::DriveKind drive_kind = as::ParseDrive(drive);
    auto sim = as::MakeScenario(config);
    if (!as::DriveFits(drive_kind, *sim))
      throw std::invalid_argument("--drive " + drive + " is not defined for the " +
                                  as::ScenarioName(config.kind) + " task");
    sim->Reset(seed);
    std::vector<double> command(static_cast<std::size_t>(sim->num_actuators()));
    std::vector<double> commands;  // every compartment's, for the behaviour summary
    as::BehaviourSummary behaviour;
    const auto t0 = std::chrono::steady_clock::now();
    as::StepStatus status = as::StepStatus::kRunning;
    while (status == as::StepStatus::kRunning) {
      commands.clear();
      for (int c = 0; c < sim->num_compartments(); ++c) {
        as::DriveCommand(drive_kind, *sim, c, command.data());
        sim->SetActuators(c, command.data());
        commands.insert(commands.end(), command.begin(), command.end());
      }
      status = sim->Step();
      if (status != as::StepStatus::kFailed) behaviour.Observe(*sim, commands);
      if (verbose && sim->tick() % static_cast<std::int64_t>(1.0 / sim->control_period()) == 0)
        std::printf("t %7.2f s  fitness %.6f  cost %.6f\n", sim->sim_time(), sim->Fitness(),
                    sim->Cost());
    }
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (status == as::StepStatus::kFailed) {
      std::cerr << "ahhs-sim: episode failed: " << sim->error() << '\n';
      return ahhs::cli::kExitFailure;
    }
    std::printf(
        "scenario %s, drive %s, seed %llu: %lld ticks, %.1f s simulated in %.3f s wall (%.0fx real "
        "time)\n",
        as::ScenarioName(config.kind), drive.c_str(), static_cast<unsigned long long>(seed),
        static_cast<long long>(sim->tick()), sim->sim_time(), wall, sim->sim_time() / wall);
    std::printf("behaviour: %s\n", behaviour.Describe().c_str());
    std::printf("cost: %.17g\n", sim->Cost());
    std::printf("fitness: %.17g\n", sim->Fitness());
  } catch (const std::exception& e) {
    std::cerr << "ahhs-sim: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
