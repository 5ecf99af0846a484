// ahhs-sim: the ODE arena.
//   bus mode (default): serves episodes commanded on <ARENA>/SIM/CONTROL (docs/protocol.md);
//   --physics none: the episode server of a physical organism (clock and topology only);
//   standalone mode (--drive): one episode with built-in commands, "fitness: <value>" last.
// The three modes: sim/app/sim_modes.h.
#include <chrono>
#include <iostream>
#include <stdexcept>

#include "base/cli.h"
#include "bus/lcm_bus.h"
#include "bus/wire_version.h"
#include "modules/core/random.h"
#include "sim/app/sim_modes.h"
#include "sim/core/constants.h"
#include "sim/node/envelope_options.h"
#include "sim/node/scenario_options.h"

namespace cli = ahhs::base::cli;

namespace as = ahhs::sim;

int main(int argc, char** argv) {
  cli::App app{
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
      ->check(cli::Range(0, 600000))
      ->capture_default_str();
  app.add_option("--min-tick-us", min_tick_us,
                 "bus mode, lockstep: at least this many microseconds of wall time per tick")
      ->check(cli::Range(0, 10000000))
      ->capture_default_str();
  app.add_option(
         "--state-rate", node_options.state_rate,
         "bus mode: SIM/STATE messages per simulated second (0 = once per tick in lockstep, "
         "40 in real time)")
      ->check(cli::Range(0.0, 1000.0))
      ->capture_default_str();
  app.add_option("--episodes", episodes,
                 "bus mode: exit after this many episodes (0 = serve until killed)")
      ->check(cli::NonNegativeNumber)
      ->capture_default_str();
  std::string drive = "zero";
  as::ScenarioOptions scenario;
  std::uint64_t seed = 1;
  bool verbose = false;
  scenario.Add(app, "", "episode length, simulated seconds (default: the scenario's)");
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
      ->check(cli::Range(0, 32767));
  std::string physics = "ode";
  as::EpisodeServerOptions server_options;
  int confirm_timeout_s = 600;
  bool no_confirm = false;
  app.add_option("--physics", physics,
                 "bus mode: ode (simulate the organism) or none (episode server of a physical "
                 "organism: clock and topology only, docs/hardware.md)")
      ->check(cli::IsMember({"ode", "none"}))
      ->capture_default_str();
  app.add_flag("--no-confirm", no_confirm,
               "--physics none: start each episode without waiting for the operator");
  app.add_option("--confirm-timeout", confirm_timeout_s,
                 "--physics none: seconds to wait for the operator's confirmation before giving "
                 "an episode up")
      ->check(cli::Range(1, 86400))
      ->capture_default_str();
  as::EnvelopeOptions envelope_options;
  envelope_options.Add(app,
                       "with --drive: an envelope of noise drawn from --seed (default none; in bus "
                       "mode each RESET brings its own; docs/scenarios.md)");
  ahhs::base::SetVersion(app, {ahhs::bus::WireVersionLine(), ahhs::sim::PhysicsVersionLine()});
  if (const int code = ahhs::base::Parse(app, argc, argv); code >= 0) return code;
  as::Envelope envelope;
  try {
    envelope = envelope_options.Resolve();
    if (envelope_options.given() && drive_opt->count() == 0)
      throw std::invalid_argument("--envelope needs --drive (in bus mode RESET brings it)");
  } catch (const std::invalid_argument& e) {
    std::cerr << "ahhs-sim: " << e.what() << '\n';
    return ahhs::base::kExitUsage;
  }

  if (physics == "none") {
    if (drive_opt->count() > 0 || !hardware_modules.empty()) {
      std::cerr << "ahhs-sim: --drive and --hardware-modules need the physics; --physics none "
                   "serves the bus only\n";
      return ahhs::base::kExitUsage;
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
    as::StandaloneOptions standalone;
    standalone.scenario = &scenario;
    standalone.drive = drive;
    standalone.seed = seed;
    standalone.verbose = verbose;
    standalone.envelope = envelope;
    return as::RunStandalone(standalone);
  } catch (const std::exception& e) {
    std::cerr << "ahhs-sim: " << e.what() << '\n';
    return 1;
  }
}
