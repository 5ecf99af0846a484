// ahhs-replay: re-runs one genome as one episode with everything recorded (docs/analysis.md):
//   ahhs-replay RUN_DIR [--generation G [--individual I]]   a stored individual (default: the
//                                                          run's best), with its stored seed
//   ahhs-replay --genome FILE --scenario ... --seed S       any genome
// --log FILE writes an LCM log (per tick: every module's SENSORS, HINGE and TRACE, and
// SIM/STATE and the running FITNESS; a final FITNESS); --csv FILE the same trace as CSV,
// --rules-csv FILE how often each rule triggered in each module. --mutants N evaluates N single
// mutants of the genome (the paper's mutation neighbourhood) into --mutants-csv FILE. The replay
// uses the workers' direct arena, so a stored fitness is reproduced to the bit; the output says so,
// or by how much not. Options: replay_options.h; what is replayed: replay_target.h; the episode
// and its outputs: replay_run.h.
#include <iostream>
#include <stdexcept>

#include "base/cli.h"
#include "bus/wire_version.h"
#include "evolver/store/run_store.h"
#include "sim/core/constants.h"
#include "tools/replay/replay_options.h"
#include "tools/replay/replay_run.h"
#include "tools/replay/replay_target.h"

namespace cli = ahhs::base::cli;

namespace ar = ahhs::replay;

int main(int argc, char** argv) {
  cli::App app{"ahhs-replay: one episode of a stored or given genome, with everything recorded"};
  ar::ReplayOptions o;
  ar::AddReplayOptions(app, &o);
  ahhs::base::SetVersion(app, {ahhs::bus::WireVersionLine(), ahhs::sim::PhysicsVersionLine(),
                               ahhs::evolver::RunStore::FormatVersionLine()});
  if (const int code = ahhs::base::Parse(app, argc, argv); code >= 0) return code;
  // Of the replay; of --post-eval. A run's episodes keep the run's envelope unless one is given.
  ahhs::sim::Envelope envelope, post_envelope;
  try {
    envelope = o.envelope_options.Resolve();
    post_envelope = o.envelope_options.Resolve("paper");
  } catch (const std::invalid_argument& e) {
    std::cerr << "ahhs-replay: " << e.what() << '\n';
    return ahhs::base::kExitUsage;
  }
  if (o.run_dir.empty() == o.genome_file.empty()) {
    std::cerr << "ahhs-replay: give either a run directory or --genome FILE\n";
    return 1;
  }
  const std::string exists =
      ahhs::base::RefuseExisting({o.log_file, o.csv_file, o.rules_csv, o.mutants_csv, o.body_csv,
                                  o.robustness_csv, o.post_eval_json, o.video, o.filmstrip},
                                 o.overwrite);
  if (!exists.empty()) {
    std::cerr << "ahhs-replay: " << exists << '\n';
    return ahhs::base::kExitUsage;
  }
  ar::ReplayTarget target;
  try {
    target = ar::ResolveTarget(app, o, envelope, post_envelope);
  } catch (const std::exception& e) {
    std::cerr << "ahhs-replay: " << e.what() << '\n';
    return 1;
  }
  return ar::RunReplay(o, target);
}
