// ahhs-conformance: plays the counterpart roles against an implementation under test and checks
// the protocol (docs/hardware.md, "Conformance kit"). Prints a checklist, PASS or FAIL with the
// evidence, and exits 1 when a check fails.
//   ahhs-conformance module --arena A --id N      a module controller (HINGE, HORMONE, STATUS)
//   ahhs-conformance firmware --arena A --id N    a module's firmware (SENSORS, follows HINGE)
//   ahhs-conformance tracker --arena A --modules N  a tracker (SIM/STATE)
//   ahhs-conformance sim --arena A                an episode server in real time (SIM/CLOCK,
//   TOPOLOGY)
//   ahhs-conformance vectors --write FILE         the controller's golden vectors, offline
//   ahhs-conformance vectors --check FILE         (docs/hardware.md, "Golden vectors")
#include <fstream>
#include <iostream>
#include <sstream>

#include "base/atomic_file.h"
#include "base/cli.h"
#include "bus/fault_bus.h"
#include "bus/lcm_bus.h"
#include "bus/wire_version.h"
#include "tools/conformance/model_vectors.h"
#include "tools/conformance/module_player.h"
#include "tools/conformance/player.h"
#include "tools/conformance/sim_player.h"

namespace cli = ahhs::base::cli;

namespace {

// ahhs-conformance vectors: --write FILE (atomically) or --check FILE.
int RunVectors(const std::string& write, const std::string& check) {
  namespace ac = ahhs::conformance;
  if (write.empty() == check.empty()) {
    std::cerr << "ahhs-conformance: vectors needs --write FILE or --check FILE\n";
    return ahhs::base::kExitUsage;
  }
  try {
    if (!write.empty()) {
      ahhs::base::WriteFileAtomically(write, ac::WriteModelVectors());
      std::cout << "wrote " << write << '\n';
      return 0;
    }
    std::ifstream in(check);
    if (!in) throw std::runtime_error("cannot read " + check);
    std::stringstream text;
    text << in.rdbuf();
    const std::string error = ac::CheckModelVectors(text.str());
    if (!error.empty()) {
      std::cout << check << ": " << error << "\nNOT conformant\n";
      return ahhs::base::kExitFailure;
    }
    std::cout << check << ": every output equals modules/core to the bit\nconformant\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "ahhs-conformance: " << e.what() << '\n';
    return ahhs::base::kExitFailure;
  }
}

}  // namespace

int main(int argc, char** argv) {
  namespace ac = ahhs::conformance;
  cli::App app{
      "ahhs-conformance: checks a module controller, a firmware, a tracker or an episode server "
      "against the "
      "protocol by playing the roles around it"};
  std::string role, url = ahhs::bus::kDefaultLcmUrl;
  ac::PlayOptions options;
  double budget_ms = 25;
  app.add_option("role", role, "module, firmware, tracker, sim, or vectors (offline)")
      ->required()
      ->check(cli::IsMember({"module", "firmware", "tracker", "sim", "vectors"}));
  app.add_option("--arena", options.arena, "the arena the implementation serves");
  std::string write_vectors, check_vectors;
  auto* write_opt = app.add_option("--write", write_vectors,
                                   "vectors: write the golden vectors modules/core computes");
  app.add_option("--check", check_vectors,
                 "vectors: check a golden vectors file against modules/core")
      ->excludes(write_opt);
  app.add_option("--id", options.id, "module, firmware: the module under test")
      ->check(cli::Range(0, 1000));
  app.add_option("--modules", options.modules, "tracker: modules it tracks")
      ->check(cli::Range(1, 1000));
  app.add_option("--lcm-url", url, "LCM URL")->capture_default_str();
  app.add_option("--ticks", options.ticks, "firmware, tracker: ticks of the played episode")
      ->check(cli::Range(8, 100000))
      ->capture_default_str();
  app.add_option(
         "--budget-ms", budget_ms,
         "longest time from a tick's last input to the answer (firmware, tracker: SIM/CLOCK; "
         "module: SENSORS and packets); sim: a tick's distance from its schedule")
      ->check(cli::Range(1.0, 1000.0))
      ->capture_default_str();
  std::uint64_t seed = 1;
  app.add_option("--seed", seed, "module: seed of the genomes, sensor values and packets played")
      ->capture_default_str();
  ahhs::base::SetVersion(
      app, {ahhs::bus::WireVersionLine(),
            "model vectors " + std::to_string(ahhs::conformance::kModelVectorsVersion)});
  if (const int code = ahhs::base::Parse(app, argc, argv); code >= 0) return code;
  if (role == "vectors") return RunVectors(write_vectors, check_vectors);
  if (app.count("--arena") == 0) {
    std::cerr << "ahhs-conformance: " << role << " needs --arena A (the arena it serves)\n";
    return ahhs::base::kExitUsage;
  }
  const bool tracker = role == "tracker";
  if (role != "sim" && app.count(tracker ? "--modules" : "--id") == 0) {
    std::cerr << "ahhs-conformance: " << role << " needs "
              << (tracker ? "--modules N (modules it tracks)" : "--id N (its module)") << '\n';
    return ahhs::base::kExitUsage;
  }
  try {
    auto bus = ahhs::bus::OpenBusWithFaultInjection(url);
    ac::Budget budget;
    budget.latency = budget_ms / 1000;
    std::string plan = "playing " + std::to_string(options.ticks) + " ticks, then a late start";
    if (role == "module") plan = "playing launcher, sim and neighbours for 3 episodes";
    if (role == "sim") plan = "playing the launcher for 2 real-time episodes and a bad RESET";
    std::cout << "ahhs-conformance " << role << " on arena " << options.arena << " (" << url
              << "): " << plan << '\n'
              << std::flush;
    std::vector<ac::Check> checks;
    if (role == "sim") {
      checks = ac::PlaySim(*bus, {options.arena}, budget);
    } else if (role == "module") {
      ac::ModulePlayOptions m;
      m.arena = options.arena;
      m.id = options.id;
      m.seed = seed;
      checks = ac::PlayModule(*bus, m, budget);
    } else {
      checks = role == "firmware" ? ac::PlayFirmware(*bus, options, budget)
                                  : ac::PlayTracker(*bus, options, budget);
    }
    std::string text;
    const bool pass = ac::PrintChecklist(checks, &text);
    std::cout << text << (pass ? "conformant\n" : "NOT conformant\n");
    return pass ? 0 : ahhs::base::kExitFailure;
  } catch (const std::exception& e) {
    std::cerr << "ahhs-conformance: " << e.what() << '\n';
    return ahhs::base::kExitFailure;
  }
}
