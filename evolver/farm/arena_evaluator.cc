#include "evolver/farm/arena_evaluator.h"

#include <unistd.h>

namespace ahhs::evolver {

ArenaEvaluator::ArenaEvaluator(episode::ArenaOptions options) : options_(std::move(options)) {}

ArenaEvaluator::~ArenaEvaluator() = default;

FarmResult ArenaEvaluator::Evaluate(const FarmJob& job) {
  episode::EpisodeSpec spec;
  spec.config = job.config;
  spec.genome = job.genome;
  spec.seed = job.seed;
  // Episode ids only need to be unique on the arena's bus.
  spec.episode = static_cast<std::int64_t>(getpid()) * 1000000 + ++episodes_;
  spec.arena = options_.name;
  spec.episode_timeout = std::chrono::seconds(600);
  FarmResult out;
  const std::string fit = episode::CheckGenomeFits(job.genome, job.config);
  if (!fit.empty()) {
    out.status = FarmResult::Status::kError;
    out.message = fit;
    return out;
  }
  const int compartments = sim::ShapeOf(job.config).compartments;
  if (arena_ && (!arena_->healthy() || arena_compartments_ != compartments)) arena_.reset();
  if (!arena_) {
    try {
      arena_ = episode::MakeArena(options_, job.config);
    } catch (const std::exception& e) {
      out.status = FarmResult::Status::kError;
      out.message = e.what();
      return out;
    }
    arena_compartments_ = compartments;
  }
  const episode::EpisodeResult r = arena_->Run(spec);
  if (r.ok) {
    out.status = FarmResult::Status::kOk;
    out.fitness = r.fitness;
    out.cost = r.cost;
    out.descriptor = r.descriptor;
    out.states_missed = r.states_missed;
  } else if (r.episode_failed) {
    out.status = FarmResult::Status::kOk;
    out.fitness = kFailedEpisodeFitness;
    out.message = "episode failed: " + r.error;
  } else {
    out.status = FarmResult::Status::kError;
    out.message = r.error;
  }
  return out;
}

}  // namespace ahhs::evolver
