// ahhs-bench: speed figures for docs/performance.md. Benchmarks, not tests: they print
// numbers and never fail on them. One file per subcommand (tools/bench/bench_*.h).
#include <CLI/CLI.hpp>

#include "base/cli.h"
#include "sim/core/constants.h"
#include "tools/bench/bench_arena.h"
#include "tools/bench/bench_controller.h"
#include "tools/bench/bench_evolve.h"
#include "tools/bench/bench_sim.h"

int main(int argc, char** argv) {
  CLI::App app{"ahhs-bench: speed figures (see docs/performance.md)"};
  app.require_subcommand(1);
  ahhs::bench::ControllerBench controller;
  ahhs::bench::SimBench sim;
  ahhs::bench::ArenaBench arena;
  ahhs::bench::EvolveBench evolve;
  CLI::App* controller_cmd = controller.Add(app);
  CLI::App* sim_cmd = sim.Add(app);
  CLI::App* arena_cmd = arena.Add(app);
  CLI::App* evolve_cmd = evolve.Add(app);
  ahhs::base::SetVersion(app, {ahhs::sim::PhysicsVersionLine()});
  if (const int code = ahhs::base::Parse(app, argc, argv); code >= 0) return code;
  if (controller_cmd->parsed()) controller.Run();
  if (sim_cmd->parsed()) sim.Run();
  if (arena_cmd->parsed()) arena.Run();
  if (evolve_cmd->parsed()) evolve.Run();
  return 0;
}
