// ahhs-bench: speed figures for docs/performance.md. Benchmarks, not tests: they print
// numbers and never fail on them. One file per subcommand (tools/bench/bench_*.h).

#include "base/cli.h"
#include "sim/core/constants.h"
#include "tools/bench/bench_arena.h"
#include "tools/bench/bench_controller.h"
#include "tools/bench/bench_evolve.h"
#include "tools/bench/bench_sim.h"

namespace cli = ahhs::base::cli;

int main(int argc, char** argv) {
  cli::App app{"ahhs-bench: speed figures (see docs/performance.md)"};
  app.require_subcommand(1);
  ahhs::bench::ControllerBench controller;
  ahhs::bench::SimBench sim;
  ahhs::bench::ArenaBench arena;
  ahhs::bench::EvolveBench evolve;
  cli::App* controller_cmd = controller.Add(app);
  cli::App* sim_cmd = sim.Add(app);
  cli::App* arena_cmd = arena.Add(app);
  cli::App* evolve_cmd = evolve.Add(app);
  ahhs::base::SetVersion(app, {ahhs::sim::PhysicsVersionLine()});
  if (const int code = ahhs::base::Parse(app, argc, argv); code >= 0) return code;
  if (controller_cmd->parsed()) controller.Run();
  if (sim_cmd->parsed()) sim.Run();
  if (arena_cmd->parsed()) arena.Run();
  if (evolve_cmd->parsed()) evolve.Run();
  return 0;
}
