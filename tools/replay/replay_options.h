// ahhs-replay's command line (docs/analysis.md).
#pragma once

#include <cstdint>
#include <string>

#include "base/cli.h"
#include "sim/node/envelope_options.h"
#include "sim/node/scenario_options.h"

namespace ahhs::replay {

struct ReplayOptions {
  std::string run_dir, genome_file, log_file, csv_file, rules_csv, mutants_csv, body_csv;
  ahhs::sim::ScenarioOptions scenario;
  int generation = -1, individual = -1, mutants = 0;
  std::uint64_t seed = 1, mutant_seed = 1;
  double physics_step = 0, friction_scale = 1;
  std::string physics;
  int robustness = 0;
  std::string robustness_csv;
  ahhs::sim::EnvelopeOptions envelope_options;
  int post_eval = 0;
  std::string post_eval_json;
  bool overwrite = false;
  std::string mutation_profile;
  std::string video, filmstrip;
  double video_from = 0, video_to = -1;
};

// Declares every option on `app`.
void AddReplayOptions(base::cli::App& app, ReplayOptions* o);

}  // namespace ahhs::replay
