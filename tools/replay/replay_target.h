// What ahhs-replay replays: a run's stored individual or a genome file, with its seed, the
// envelope, the physics it was made with and the fitness it stored.
#pragma once

#include <optional>
#include <string>

#include "base/cli.h"
#include "episode/arena/episode.h"
#include "modules/core/variation.h"
#include "sim/core/envelope.h"
#include "tools/replay/replay_options.h"

namespace ahhs::replay {

struct ReplayTarget {
  ahhs::episode::EpisodeSpec spec;
  ahhs::modules::MutationParams mutation;  // of the mutants: the run's, or the paper's
  std::optional<double> stored_fitness;
  std::string stored_physics;  // the physics the run or genome file names
  bool physics_changed = false;
  std::string what;                   // for the output: which genome, which trial
  ahhs::sim::Envelope post_envelope;  // of --post-eval
};

// Resolves the target from the options (`envelope`, `post_envelope`: as the options give them;
// a run's own envelope replaces them unless envelope options were given). Throws with a
// message for the user.
ReplayTarget ResolveTarget(const base::cli::App& app, const ReplayOptions& o,
                           ahhs::sim::Envelope envelope, ahhs::sim::Envelope post_envelope);

}  // namespace ahhs::replay
