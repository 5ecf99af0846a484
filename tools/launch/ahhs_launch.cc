// ahhs-launch: runs one episode of a genome in an arena made of separate processes (ahhs-sim,
// one ahhs-module per compartment, ahhs-fitness), or with --arena-kind fused in this process
// (inproc://).
// Prints "fitness: <value>" as its last line. Every child is stopped on success, on error and on
// Ctrl-C; children also die with the launcher (PR_SET_PDEATHSIG). tools/launch/launch_app.h.
#include <atomic>
#include <csignal>
#include <iostream>

#include "base/cli.h"
#include "bus/wire_version.h"
#include "modules/core/genome_json.h"
#include "sim/core/constants.h"
#include "tools/launch/launch_app.h"

namespace cli = ahhs::base::cli;

namespace {

std::atomic<bool> g_interrupted{false};
void OnSignal(int) { g_interrupted = true; }

}  // namespace

int main(int argc, char** argv) {
  cli::App app{
      "ahhs-launch: one episode of a genome in an arena of separate processes (or fused into "
      "this one: --arena-kind fused)"};
  ahhs::launch::LaunchOptions o;
  ahhs::launch::AddLaunchOptions(app, &o);
  ahhs::base::SetVersion(app, {ahhs::bus::WireVersionLine(), ahhs::sim::PhysicsVersionLine(),
                               ahhs::modules::GenomeFormatLine()});
  if (const int code = ahhs::base::Parse(app, argc, argv); code >= 0) return code;
  ahhs::sim::Envelope envelope;
  try {
    envelope = o.envelope_options.Resolve();
  } catch (const std::invalid_argument& e) {
    std::cerr << "ahhs-launch: " << e.what() << '\n';
    return ahhs::base::kExitUsage;
  }
  ahhs::episode::EpisodeSpec spec;
  std::string error;
  if (const int code = ahhs::launch::SpecFromOptions(app, &o, envelope, &spec, &error); code != 0) {
    std::cerr << "ahhs-launch: " << error << '\n';
    return code;
  }
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  return ahhs::launch::RunLaunch(o, spec, g_interrupted);
}
