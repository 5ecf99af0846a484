#include "evolver/farm/arena_evaluator.h"

#include <unistd.h>

#include <stdexcept>

#include "tools/launch/episode_runner.h"
#include "tools/launch/process_arena.h"

namespace ahhs::evolver {

ArenaKind ParseArenaKind(const std::string& name) {
  if (name == "direct") return ArenaKind::kDirect;
  if (name == "fused") return ArenaKind::kFused;
  if (name == "processes") return ArenaKind::kProcesses;
  throw std::invalid_argument("unknown arena '" + name + "' (direct, fused or processes)");
}

const char* ArenaKindName(ArenaKind kind) {
  switch (kind) {
    case ArenaKind::kDirect:
      return "direct";
    case ArenaKind::kFused:
      return "fused";
    case ArenaKind::kProcesses:
      return "processes";
  }
  return "?";
}

ArenaEvaluator::ArenaEvaluator(ArenaKind kind, std::string url, std::string arena_name)
    : kind_(kind), url_(std::move(url)), arena_name_(std::move(arena_name)) {}

ArenaEvaluator::~ArenaEvaluator() = default;

EvalOutcome ArenaEvaluator::Evaluate(const EvalJob& job) {
  launch::EpisodeSpec spec;
  spec.config = job.config;
  spec.genome = job.genome;
  spec.seed = job.seed;
  // Episode ids only need to be unique on the arena's bus.
  spec.episode = static_cast<std::int64_t>(getpid()) * 1000000 + ++episodes_;
  spec.arena = arena_name_;
  EvalOutcome out;
  const std::string fit = launch::CheckGenomeFits(job.genome, job.config);
  if (!fit.empty()) {
    out.status = EvalOutcome::Status::kError;
    out.message = fit;
    return out;
  }
  launch::EpisodeResult r;
  switch (kind_) {
    case ArenaKind::kDirect:
      r = launch::RunDirectEpisode(spec);
      break;
    case ArenaKind::kFused:
      r = launch::RunFused(spec);
      break;
    case ArenaKind::kProcesses: {
      const int modules =
          job.config.kind == sim::ScenarioKind::kPendulum ? 2 : job.config.num_modules;
      if (processes_ && (!processes_->healthy() || processes_->options().num_modules != modules))
        processes_.reset();
      if (!processes_) {
        launch::ProcessArenaOptions o;
        o.url = url_;
        o.arena = arena_name_;
        o.num_modules = modules;
        processes_ = std::make_unique<launch::ProcessArena>(o);
      }
      spec.episode_timeout = std::chrono::seconds(600);
      r = processes_->Run(spec, [](std::string*) { return true; });
      break;
    }
  }
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
