#include "tools/replay/replay_target.h"

#include <algorithm>
#include <iostream>
#include <stdexcept>

#include "base/format.h"
#include "episode/arena/direct_arena.h"
#include "evolver/evolve/evolution.h"
#include "evolver/store/run_store.h"
#include "modules/core/genome_json.h"
#include "modules/core/random.h"

namespace cli = ahhs::base::cli;

namespace ahhs::replay {

namespace ep = ahhs::episode;
namespace am = ahhs::modules;
namespace ev = ahhs::evolver;

ReplayTarget ResolveTarget(const cli::App& app, const ReplayOptions& o,
                           ahhs::sim::Envelope envelope, ahhs::sim::Envelope post_envelope) {
  ReplayTarget t;
  t.post_envelope = post_envelope;
  if (o.video_to >= 0 && o.video_to <= o.video_from)
    throw std::invalid_argument("--to must be after --from");
  if (o.mutants > 0 && o.mutants_csv.empty())
    throw std::invalid_argument("--mutants needs --mutants-csv FILE");
  if (!o.run_dir.empty()) {
    auto store = ev::RunStore::Open(o.run_dir, ev::StoreAccess::kRead);
    store->VerifyChain();  // never replay from a store changed after it was written
    const ev::EvolveConfig config = ev::ConfigFromJson(store->config());
    ev::IndividualRecord record;
    if (o.generation < 0) {
      if (o.individual >= 0) throw std::invalid_argument("--individual needs --generation");
      record = store->Best();
    } else {
      if (o.generation > store->LastGeneration())
        throw std::invalid_argument("generation " + std::to_string(o.generation) +
                                    " is not stored (the run has generations 0-" +
                                    std::to_string(store->LastGeneration()) + ")");
      int individual = o.individual;
      if (individual < 0) {
        for (const auto& g : store->LoadGenerationRecords())
          if (g.generation == o.generation) individual = g.stats.best_index;
      }
      record = store->LoadIndividual(o.generation, individual);
    }
    t.spec.config = config.scenario;
    t.stored_physics = store->physics();
    if (!o.envelope_options.given()) {
      envelope = config.scenario.envelope;
      if (!envelope.none()) t.post_envelope = envelope;
    }
    t.mutation = config.ga.mutation;
    t.spec.genome = record.genome;
    t.spec.seed = app.count("--seed") ? o.seed : record.eval_seed;
    t.what = o.run_dir + ", generation " + std::to_string(record.generation) + ", individual " +
             std::to_string(record.index);
    if (!app.count("--seed")) {
      t.stored_fitness = record.evaluation.fitness;
      if (!record.trials.empty()) {  // the stored o.seed is the first trial's
        t.stored_fitness = record.trials.front().evaluation.fitness;
        t.what += ", trial 0 of " + std::to_string(record.trials.size()) + " (the " +
                  ev::AggregateName(config.ga.aggregate) + " of all " +
                  std::to_string(record.trials.size()) + " is " +
                  ahhs::base::ExactDouble(record.evaluation.fitness) + ")";
      }
    }
  } else {
    t.spec.config = o.scenario.Config();
    const std::string error = ahhs::sim::CheckConfig(t.spec.config);
    if (!error.empty()) throw std::invalid_argument(error);
    nlohmann::json meta;
    t.spec.genome = am::LoadGenomeFile(o.genome_file, &meta);
    if (meta.is_object() && meta.contains("physics") && meta["physics"].is_string())
      t.stored_physics = meta["physics"].get<std::string>();
    // A genome file that names its run's configuration (meta.config, as best.json keeps it)
    // replays in that run's scenario (task, docking, modules, duration) unless options give it.
    if (meta.is_object() && meta.contains("config") && meta["config"].is_object()) {
      ahhs::sim::ScenarioConfig run;
      try {
        run = ev::ConfigFromJson(meta["config"]).scenario;
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(o.genome_file + ": meta.config: " + e.what());
      }
      if (!app.count("--scenario")) t.spec.config.kind = run.kind;
      if (!app.count("--docking") && !app.count("--joints")) t.spec.config.docking = run.docking;
      if (!app.count("--modules")) t.spec.config.num_modules = run.num_modules;
      if (!app.count("--duration")) t.spec.config.duration = run.duration;
    }
    const std::string fit = ep::CheckGenomeFits(t.spec.genome, t.spec.config);
    if (!fit.empty()) throw std::invalid_argument(o.genome_file + ": " + fit);
    t.spec.seed = o.seed;
    t.what = o.genome_file;
    // A genome file of a run made with an envelope (meta.config, as best.json keeps it) replays
    // under that envelope, as the run directory would, unless envelope options are given.
    if (!o.envelope_options.given() && meta.is_object() && meta.contains("config") &&
        meta["config"].is_object() && meta["config"].contains("envelope")) {
      try {
        envelope = ev::ConfigFromJson(meta["config"]).scenario.envelope;
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(o.genome_file + ": meta.config: " + e.what());
      }
      if (!envelope.none()) {
        t.post_envelope = envelope;
        t.what += " (under the envelope of its run, " + ahhs::sim::EnvelopeName(envelope) + ")";
      }
    }
    // ... and under its pendulum choices, unless options give them.
    if (!app.count("--pendulum.actuator-gain") && !app.count("--pendulum.walls") &&
        meta.is_object() && meta.contains("config") && meta["config"].is_object() &&
        meta["config"].contains("pendulum")) {
      try {
        t.spec.config.pendulum = ev::ConfigFromJson(meta["config"]).scenario.pendulum;
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(o.genome_file + ": meta.config: " + e.what());
      }
      t.what += " (with its run's pendulum choices)";
    }
    const auto stored_seed = am::StoredEvalSeed(meta);
    if (!app.count("--seed") && stored_seed) {
      t.spec.seed = *stored_seed;
      t.what += " (with the evaluation seed it stores)";
      if (meta.contains("fitness") && meta["fitness"].is_number())
        t.stored_fitness = meta["fitness"].get<double>();
      // A robust run's genome: the stored o.seed is its first trial's, `fitness` the aggregate.
      const auto trials = meta.find("trials");
      if (trials != meta.end() && trials->is_array() && !trials->empty() &&
          (*trials)[0].contains("fitness") && (*trials)[0]["fitness"].is_number()) {
        t.stored_fitness = (*trials)[0]["fitness"].get<double>();
        t.what += ", trial 0 of " + std::to_string(trials->size());
      }
    }
  }
  t.spec.config.physics_step = o.physics_step;
  t.spec.config.friction_scale = o.friction_scale;
  t.spec.config.envelope = envelope;
  // The o.physics: --o.physics, else the run's or the genome file's if this build keeps it.
  const auto keeps = ahhs::sim::ReplayablePhysics(t.spec.config.kind, t.spec.config.docking);
  const std::string current = keeps.front();
  if (!o.physics.empty()) {
    t.spec.config.physics = o.physics;
  } else if (!t.stored_physics.empty() &&
             std::find(keeps.begin(), keeps.end(), t.stored_physics) != keeps.end()) {
    t.spec.config.physics = t.stored_physics;
  } else if (!t.stored_physics.empty()) {
    std::cerr << "ahhs-replay: note: made with the " << ahhs::sim::ScenarioName(t.spec.config.kind)
              << " physics of " << t.stored_physics
              << ", which this build does not keep (CHANGELOG.md); replaying with " << current
              << '\n';
  }
  {
    const std::string error = ahhs::sim::CheckConfig(t.spec.config);
    if (!error.empty()) throw std::invalid_argument(error);
  }
  if (t.spec.config.physics == current) t.spec.config.physics.clear();
  t.physics_changed =
      !o.physics.empty() && o.physics != (t.stored_physics.empty() ? current : t.stored_physics);
  if (!o.robustness_csv.empty() && o.robustness == 0)
    throw std::invalid_argument("--robustness-csv needs --robustness N");
  if (!o.post_eval_json.empty() && o.post_eval == 0)
    throw std::invalid_argument("--post-eval-json needs --post-eval N");
  if (!o.mutation_profile.empty())
    t.mutation.profile = am::ParseMutationProfile(o.mutation_profile);
  t.spec.episode = 1;
  return t;
}

}  // namespace ahhs::replay
