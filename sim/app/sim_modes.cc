#include "sim/app/sim_modes.h"

#include <poll.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <vector>

#include "base/cli.h"
#include "bus/fault_bus.h"
#include "sim/core/behaviour.h"
#include "sim/core/drive.h"
#include "sim/core/scenario.h"

namespace ahhs::sim {
namespace as = ahhs::sim;
namespace {

std::atomic<bool> g_stop{false};
void OnSignal(int) { g_stop = true; }

}  // namespace

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

int RunStandalone(const StandaloneOptions& o) {
  if (o.scenario->duration_given() && !(o.scenario->duration > 0))
    throw std::invalid_argument("--duration must be a positive number of seconds");
  as::ScenarioConfig config = o.scenario->Config();
  config.envelope = o.envelope;
  if (config.kind == as::ScenarioKind::kGait && o.scenario->modules < 2)
    throw std::invalid_argument("--modules: a gait organism needs at least 2 modules");
  const as::DriveKind drive_kind = as::ParseDrive(o.drive);
  auto sim = as::MakeScenario(config);
  if (!as::DriveFits(drive_kind, *sim))
    throw std::invalid_argument("--drive " + o.drive + " is not defined for the " +
                                as::ScenarioName(config.kind) + " scenario");
  sim->Reset(o.seed);
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
    if (o.verbose && sim->tick() % static_cast<std::int64_t>(1.0 / sim->control_period()) == 0)
      std::printf("t %7.2f s  fitness %.6f  cost %.6f\n", sim->sim_time(), sim->Fitness(),
                  sim->Cost());
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (status == as::StepStatus::kFailed) {
    std::cerr << "ahhs-sim: episode failed: " << sim->error() << '\n';
    return ahhs::base::kExitFailure;
  }
  std::printf(
      "scenario %s, drive %s, seed %llu: %lld ticks, %.1f s simulated in %.3f s wall (%.0fx real "
      "time)\n",
      as::ScenarioName(config.kind), o.drive.c_str(), static_cast<unsigned long long>(o.seed),
      static_cast<long long>(sim->tick()), sim->sim_time(), wall, sim->sim_time() / wall);
  std::printf("behaviour: %s\n", behaviour.Describe().c_str());
  std::printf("cost: %.17g\n", sim->Cost());
  std::printf("fitness: %.17g\n", sim->Fitness());
  return 0;
}

}  // namespace ahhs::sim
