#include "tools/view/run_follower.h"

#include <cstdio>
#include <filesystem>

#include "episode/arena/direct_arena.h"
#include "episode/arena/episode_recorder.h"
#include "evolver/evolve/evolution.h"
#include "evolver/store/run_store.h"
#include "modules/core/genome.h"

namespace ahhs::view {

namespace fs = std::filesystem;

RunFollower::RunFollower(std::string run_dir, std::string scratch_dir)
    : run_dir_(std::move(run_dir)), scratch_dir_(std::move(scratch_dir)) {
  std::error_code ec;
  if (fs::exists(run_dir_, ec) && !fs::is_directory(run_dir_, ec))
    throw std::runtime_error(run_dir_ + ": not a run directory");
  const fs::path parent = fs::absolute(run_dir_, ec).parent_path();
  if (!fs::is_directory(parent, ec))
    throw std::runtime_error(run_dir_ + ": no such directory, nor its parent " + parent.string());
}

RunFollower::~RunFollower() = default;

std::string RunFollower::waiting_for() const {
  return "waiting for the first generation of " + run_dir_;
}

std::optional<Json> RunFollower::Poll() {
  if (!store_) {
    // A run that ahhs-evolve has not made yet: wait for its database and first generation.
    std::error_code ec;
    if (!fs::exists(fs::path(run_dir_) / "run.sqlite", ec)) return std::nullopt;
    try {
      store_ = evolver::RunStore::Open(run_dir_, evolver::StoreAccess::kRead);
    } catch (const std::exception&) {
      if (++open_failures_ >= 10) throw;  // not a run (or a damaged one), not just a young one
      return std::nullopt;
    }
  }
  const auto generations = store_->LoadGenerationRecords();
  if (generations.empty()) return std::nullopt;
  const auto& newest = generations.back();
  if (newest.generation == shown_generation_) return std::nullopt;
  const evolver::IndividualRecord best =
      store_->LoadIndividual(newest.generation, newest.stats.best_index);
  const std::string hash = std::to_string(modules::GenomeHash(best.genome));
  shown_generation_ = newest.generation;
  if (hash == shown_hash_) return std::nullopt;  // the same genome (an elite): keep showing it
  shown_hash_ = hash;

  episode::EpisodeSpec spec;
  spec.config = evolver::ConfigFromJson(store_->config()).scenario;
  spec.genome = best.genome;
  spec.seed = best.eval_seed;
  spec.episode = 1;
  const std::string log = (fs::path(scratch_dir_) / "best.lcm").string();
  {
    episode::EpisodeRecorder recorder(spec, log, "", "");
    const episode::EpisodeResult result =
        episode::RunDirectEpisode(spec, [&](const episode::DirectTick& t) { recorder.Observe(t); });
    recorder.Commit(result);
  }
  std::string arena_name;
  std::vector<Json> recordings = LoadRecordings(log, &arena_name);
  fs::remove(log);
  Json r = std::move(recordings.front());
  char title[160];
  std::snprintf(title, sizeof title, "generation %d, individual %d, stored fitness %.6g",
                best.generation, best.index, best.evaluation.fitness);
  r["title"] = title;
  r["run_generation"] = best.generation;
  return r;
}

}  // namespace ahhs::view
