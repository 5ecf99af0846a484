#include "evolver/farm/arena_evaluator.h"

#include <unistd.h>

namespace ahhs::evolver {

ArenaEvaluator::ArenaEvaluator(arena::ArenaOptions options) : options_(std::move(options)) {}

ArenaEvaluator::~ArenaEvaluator() = default;

EvalOutcome ArenaEvaluator::Evaluate(const EvalJob& job) {
  arena::EpisodeSpec spec;
  spec.config = job.config;
  spec.genome = job.genome;
  spec.seed = job.seed;
  // Episode ids only need to be unique on the arena's bus.
  spec.episode = static_cast<std::int64_t>(getpid()) * 1000000 + ++episodes_;
  spec.arena = options_.name;
  spec.episode_timeout = std::chrono::seconds(600);
  EvalOutcome out;
  const std::string fit = arena::CheckGenomeFits(job.genome, job.config);
  if (!fit.empty()) {
    out.status = EvalOutcome::Status::kError;
    out.message = fit;
    return out;
  }
  const int compartments = sim::ShapeOf(job.config).compartments;
  if (arena_ && (!arena_->healthy() || arena_compartments_ != compartments)) arena_.reset();
  if (!arena_) {
    try {
      arena_ = arena::MakeArena(options_, job.config);
    } catch (const std::exception& e) {
      out.status = EvalOutcome::Status::kError;
      out.message = e.what();
      return out;
    }
    arena_compartments_ = compartments;
  }
  const arena::EpisodeResult r = arena_->Run(spec);
  if (r.ok) {
    out.status = EvalOutcome::Status::kOk;
    out.fitness = r.fitness;
    out.cost = r.cost;
    out.late_messages = r.states_missed;
  } else if (r.episode_failed) {
    out.status = EvalOutcome::Status::kOk;
    out.fitness = kFailedEpisodeFitness;
    out.message = "episode failed: " + r.error;
  } else {
    out.status = EvalOutcome::Status::kError;
    out.message = r.error;
  }
  return out;
}

}  // namespace ahhs::evolver
