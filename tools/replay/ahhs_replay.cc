// ahhs-replay: re-runs one genome as one episode with everything recorded (docs/analysis.md):
//   ahhs-replay RUN_DIR [--generation G [--individual I]]   a stored individual (default: the
//                                                          run's best), with its stored seed
//   ahhs-replay --genome FILE --scenario ... --seed S       any genome
// --log FILE writes an LCM log (per tick: every module's SENSORS, HINGE and TRACE, and
// SIM/STATE and the running FITNESS; a final FITNESS); --csv FILE the same trace as CSV,
// --rules-csv FILE how often each rule triggered in each module. --mutants N evaluates N single
// mutants of the genome (the paper's mutation neighbourhood) into --mutants-csv FILE. The replay
// uses the workers' direct arena, so a stored fitness is reproduced to the bit; the output says so,
// or by how much not.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>

#include "base/atomic_file.h"
#include "base/children.h"
#include "base/cli.h"
#include "base/format.h"
#include "base/temp_files.h"
#include "episode/arena/direct_arena.h"
#include "episode/arena/episode.h"
#include "episode/arena/episode_recorder.h"
#include "episode/arena/post_eval.h"
#include "episode/arena/robustness.h"
#include "evolver/evolve/evolution.h"
#include "evolver/store/run_store.h"
#include "modules/core/genome_json.h"
#include "modules/core/random.h"
#include "modules/core/variation.h"
#include "sim/core/behaviour.h"
#include "sim/node/envelope_options.h"
#include "sim/node/scenario_options.h"

namespace fs = std::filesystem;
namespace ep = ahhs::episode;
namespace am = ahhs::modules;
namespace ev = ahhs::evolver;

namespace {

using TextWriter = ahhs::base::AtomicTextFile;

std::string HashText(const am::Genome& genome) {
  char hash[20];
  std::snprintf(hash, sizeof hash, "%016llx",
                static_cast<unsigned long long>(am::GenomeHash(genome)));
  return hash;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"ahhs-replay: one episode of a stored or given genome, with everything recorded"};
  std::string run_dir, genome_file, log_file, csv_file, rules_csv, mutants_csv;
  ahhs::sim::ScenarioOptions task;
  int generation = -1, individual = -1, mutants = 0;
  std::uint64_t seed = 1;
  std::uint64_t mutant_seed = 1;
  app.add_option("run", run_dir, "run directory of ahhs-evolve");
  app.add_option("--generation", generation, "generation (default: the run's best individual)");
  app.add_option("--individual", individual,
                 "individual of --generation (default: that generation's best)");
  app.add_option("--genome", genome_file, "a genome file instead of a run")
      ->check(CLI::ExistingFile);
  task.Add(app, "with --genome: ", "simulated seconds (0: the task's)");
  app.add_option("--seed", seed,
                 "evaluation seed, 0 to 2^64-1 (default: the stored one: the run's, or the genome "
                 "file's; else 1)")
      ->check(am::SeedTextError);
  app.add_option("--log", log_file, "write the episode as an LCM log");
  app.add_option("--csv", csv_file, "write the per-tick trace as CSV");
  std::string body_csv;
  double physics_step = 0;
  app.add_option("--physics-step", physics_step,
                 "seconds per physics step (gait) or RK4 step (pendulum) instead of the task's: "
                 "does the behaviour depend on the discretisation? (docs/scenarios.md)")
      ->check(CLI::Range(0.0001, 0.05));
  double friction_scale = 1;
  app.add_option("--friction-scale", friction_scale,
                 "multiply the friction coefficients (gait) or pivot friction (pendulum) by this: "
                 "a perturbed physics (docs/scenarios.md)")
      ->check(CLI::Range(0.01, 10.0));
  std::string physics;
  app.add_option("--physics", physics,
                 "the physics version to replay with (default: the one the run or genome file "
                 "names, else this build's; docs/reference.md lists those this build keeps)");
  int robustness = 0;
  std::string robustness_csv;
  app.add_option("--robustness", robustness,
                 "also replay N times with the friction scaled from 0.975 to 1.025 (not 1): is the "
                 "fitness robust or a knife-edge of deterministic chaos? (docs/scenarios.md)")
      ->check(CLI::Range(2, 1000));
  app.add_option("--robustness-csv", robustness_csv, "where --robustness writes its results");
  ahhs::sim::EnvelopeOptions envelope_options;
  envelope_options.Add(app,
                       "an envelope of noise for every episode replayed (default none; with "
                       "--post-eval: paper)");
  int post_eval = 0;
  app.add_option("--post-eval", post_eval,
                 "also replay on N held-out episodes (seeds no run evaluates with) under the "
                 "envelope: median, quartiles, min, and the share that succeeds "
                 "(docs/evolution.md)")
      ->check(CLI::Range(1, 100000));
  std::string post_eval_json;
  app.add_option("--post-eval-json", post_eval_json,
                 "where --post-eval writes every episode and figure (JSON)");
  app.add_option("--body-csv", body_csv,
                 "write the organism per tick as CSV (pendulum: cart_x, pole_angle in rad; gait: "
                 "centroid_x, centroid_y in m)");
  app.add_option("--rules-csv", rules_csv, "write how often each rule triggered, per module");
  app.add_option("--mutants", mutants, "evaluate this many single mutants of the genome")
      ->check(CLI::Range(0, 100000));
  app.add_option("--mutants-csv", mutants_csv, "where --mutants writes its results");
  bool overwrite = false;
  app.add_flag("--overwrite", overwrite, "replace output files that exist");
  app.add_option("--mutant-seed", mutant_seed, "seed of the mutations")
      ->check(am::SeedTextError)
      ->capture_default_str();
  std::string mutation_profile;
  app.add_option("--mutation-profile", mutation_profile,
                 "operator of the mutants: paper or fine-doses (default: the run's, else paper)")
      ->check(CLI::IsMember({"paper", "fine-doses"}));
  std::string video, filmstrip;
  double video_from = 0, video_to = -1;
  app.add_option("--video", video, "film the episode: an H.264 MP4, 1280x720, 25 fps (ahhs-view)");
  app.add_option("--filmstrip", filmstrip, "8 frames across the episode in one PNG (ahhs-view)");
  app.add_option("--from", video_from, "--video: start, simulated seconds")
      ->check(CLI::Range(0.0, 1e6));
  app.add_option("--to", video_to, "--video: end, simulated seconds (default: the end)")
      ->check(CLI::Range(0.0, 1e6));
  if (const int code = ahhs::cli::Parse(app, argc, argv); code >= 0) return code;
  // Of the replay; of --post-eval. A run's episodes keep the run's envelope unless one is given.
  ahhs::sim::Envelope envelope, post_envelope;
  try {
    envelope = envelope_options.Resolve();
    post_envelope = envelope_options.Resolve("paper");
  } catch (const std::invalid_argument& e) {
    std::cerr << "ahhs-replay: " << e.what() << '\n';
    return ahhs::cli::kExitUsage;
  }

  ep::EpisodeSpec spec;
  am::MutationParams mutation;  // of the mutants: the run's, or the paper's
  std::optional<double> stored_fitness;
  std::string stored_physics;  // the physics the run or genome file names
  bool physics_changed = false;
  std::string what;
  try {
    if (run_dir.empty() == genome_file.empty())
      throw std::invalid_argument("give either a run directory or --genome FILE");
    const std::string exists =
        ahhs::cli::RefuseExisting({log_file, csv_file, rules_csv, mutants_csv, body_csv,
                                   robustness_csv, post_eval_json, video, filmstrip},
                                  overwrite);
    if (!exists.empty()) {
      std::cerr << "ahhs-replay: " << exists << '\n';
      return ahhs::cli::kExitUsage;
    }
    if (video_to >= 0 && video_to <= video_from)
      throw std::invalid_argument("--to must be after --from");
    if (mutants > 0 && mutants_csv.empty())
      throw std::invalid_argument("--mutants needs --mutants-csv FILE");
    if (!run_dir.empty()) {
      auto store = ev::RunStore::Open(run_dir, ev::StoreAccess::kRead);
      store->VerifyChain();  // never replay from a store changed after it was written
      const ev::EvolveConfig config = ev::ConfigFromJson(store->config());
      ev::IndividualRecord record;
      if (generation < 0) {
        if (individual >= 0) throw std::invalid_argument("--individual needs --generation");
        record = store->Best();
      } else {
        if (generation > store->LastGeneration())
          throw std::invalid_argument("generation " + std::to_string(generation) +
                                      " is not stored (the run has generations 0-" +
                                      std::to_string(store->LastGeneration()) + ")");
        if (individual < 0) {
          for (const auto& g : store->LoadGenerationRecords())
            if (g.generation == generation) individual = g.stats.best_index;
        }
        record = store->LoadIndividual(generation, individual);
      }
      spec.config = config.scenario;
      stored_physics = store->physics();
      if (!envelope_options.given()) {
        envelope = config.scenario.envelope;
        if (!envelope.none()) post_envelope = envelope;
      }
      mutation = config.ga.mutation;
      spec.genome = record.genome;
      spec.seed = app.count("--seed") ? seed : record.eval_seed;
      what = run_dir + ", generation " + std::to_string(record.generation) + ", individual " +
             std::to_string(record.index);
      if (!app.count("--seed")) {
        stored_fitness = record.evaluation.fitness;
        if (!record.trials.empty()) {  // the stored seed is the first trial's
          stored_fitness = record.trials.front().evaluation.fitness;
          what += ", trial 0 of " + std::to_string(record.trials.size()) + " (the " +
                  ev::AggregateName(config.ga.aggregate) + " of all " +
                  std::to_string(record.trials.size()) + " is " +
                  ahhs::base::ExactDouble(record.evaluation.fitness) + ")";
        }
      }
    } else {
      spec.config = task.Config();
      const std::string error = ahhs::sim::CheckConfig(spec.config);
      if (!error.empty()) throw std::invalid_argument(error);
      nlohmann::json meta;
      spec.genome = am::LoadGenomeFile(genome_file, &meta);
      if (meta.is_object() && meta.contains("physics") && meta["physics"].is_string())
        stored_physics = meta["physics"].get<std::string>();
      const std::string fit = ep::CheckGenomeFits(spec.genome, spec.config);
      if (!fit.empty()) throw std::invalid_argument(genome_file + ": " + fit);
      spec.seed = seed;
      what = genome_file;
      const auto stored_seed = am::StoredEvalSeed(meta);
      if (!app.count("--seed") && stored_seed) {
        spec.seed = *stored_seed;
        what += " (with the evaluation seed it stores)";
        if (meta.contains("fitness") && meta["fitness"].is_number())
          stored_fitness = meta["fitness"].get<double>();
        // A robust run's genome: the stored seed is its first trial's, `fitness` the aggregate.
        const auto trials = meta.find("trials");
        if (trials != meta.end() && trials->is_array() && !trials->empty() &&
            (*trials)[0].contains("fitness") && (*trials)[0]["fitness"].is_number()) {
          stored_fitness = (*trials)[0]["fitness"].get<double>();
          what += ", trial 0 of " + std::to_string(trials->size());
        }
      }
    }
    spec.config.physics_step = physics_step;
    spec.config.friction_scale = friction_scale;
    spec.config.envelope = envelope;
    // The physics: --physics, else the run's or the genome file's if this build keeps it.
    const auto keeps = ahhs::sim::ReplayablePhysics(spec.config.kind, spec.config.joints);
    const std::string current = keeps.front();
    if (!physics.empty()) {
      spec.config.physics = physics;
    } else if (!stored_physics.empty() &&
               std::find(keeps.begin(), keeps.end(), stored_physics) != keeps.end()) {
      spec.config.physics = stored_physics;
    } else if (!stored_physics.empty()) {
      std::cerr << "ahhs-replay: note: made with the " << ahhs::sim::ScenarioName(spec.config.kind)
                << " physics of " << stored_physics
                << ", which this build does not keep (CHANGELOG.md); replaying with " << current
                << '\n';
    }
    {
      const std::string error = ahhs::sim::CheckConfig(spec.config);
      if (!error.empty()) throw std::invalid_argument(error);
    }
    if (spec.config.physics == current) spec.config.physics.clear();
    physics_changed =
        !physics.empty() && physics != (stored_physics.empty() ? current : stored_physics);
    if (!robustness_csv.empty() && robustness == 0)
      throw std::invalid_argument("--robustness-csv needs --robustness N");
    if (!post_eval_json.empty() && post_eval == 0)
      throw std::invalid_argument("--post-eval-json needs --post-eval N");
    if (!mutation_profile.empty()) mutation.profile = am::ParseMutationProfile(mutation_profile);
  } catch (const std::exception& e) {
    std::cerr << "ahhs-replay: " << e.what() << '\n';
    return 1;
  }
  spec.episode = 1;

  const bool film = !video.empty() || !filmstrip.empty();
  std::unique_ptr<ahhs::base::TempDir> film_dir;  // a private folder, removed at the end
  std::string film_log = log_file;
  if (film && log_file.empty()) {
    try {
      film_dir = std::make_unique<ahhs::base::TempDir>("ahhs-replay-");
    } catch (const std::exception& e) {
      std::cerr << "ahhs-replay: " << e.what() << '\n';
      return 1;
    }
    film_log = (fs::path(film_dir->path()) / "episode.lcm").string();
  }

  try {
    const bool record =
        !film_log.empty() || !csv_file.empty() || !rules_csv.empty() || !body_csv.empty();
    ep::EpisodeRecorder recorder(spec, film_log, csv_file, rules_csv, body_csv);
    ahhs::sim::BehaviourSummary behaviour;
    std::vector<double> commands;
    const ep::EpisodeResult result = ep::RunDirectEpisode(spec, [&](const ep::DirectTick& t) {
      commands.clear();
      for (int c = 0; c < t.organism->size(); ++c) {
        const auto& a = t.organism->state(c).actuators;
        commands.insert(commands.end(), a.data(), a.data() + a.size());
      }
      behaviour.Observe(*t.scenario, commands);
      if (record) recorder.Observe(t);
    });
    recorder.Commit(result);
    if (mutants > 0) {
      TextWriter out(mutants_csv);
      out.out() << "mutant,fitness,genome_hash\n";
      out.out() << "original," << ahhs::base::ExactDouble(result.ok ? result.fitness : 0) << ','
                << am::GenomeHash(spec.genome) << '\n';
      am::Rng rng(mutant_seed);
      for (int k = 0; k < mutants; ++k) {
        ep::EpisodeSpec mutant = spec;
        am::MutateOneGene(&mutant.genome, mutation, rng);
        const ep::EpisodeResult r = ep::RunDirectEpisode(mutant);
        out.out() << k << ',' << ahhs::base::ExactDouble(r.ok ? r.fitness : 0) << ','
                  << am::GenomeHash(mutant.genome) << '\n';
      }
      out.Commit();
      std::printf("%d single mutants evaluated into %s\n", mutants, mutants_csv.c_str());
    }
    if (robustness > 0) {
      const ep::Robustness r = ep::MeasureRobustness(spec, robustness);
      if (!robustness_csv.empty()) {
        TextWriter out(robustness_csv);
        out.out() << "friction_scale,fitness\n";
        for (std::size_t i = 0; i < r.scales.size(); ++i)
          out.out() << ahhs::base::ExactDouble(r.scales[i]) << ','
                    << (std::isnan(r.fitnesses[i]) ? "failed"
                                                   : ahhs::base::ExactDouble(r.fitnesses[i]))
                    << '\n';
        out.Commit();
      }
      std::printf("%s\n", r.Describe(result.ok ? result.fitness : 0).c_str());
    }
    if (post_eval > 0) {
      const ep::PostEvaluation p = ep::PostEvaluate(spec, post_envelope, post_eval);
      std::printf("%s\n", p.Describe(spec.config.kind).c_str());
      if (!post_eval_json.empty()) {
        nlohmann::json doc = p.ToJson();
        doc["description"] = p.Describe(spec.config.kind);
        doc["genome_hash"] = HashText(spec.genome);
        ahhs::base::WriteFileAtomically(post_eval_json, doc.dump(2) + "\n");
      }
    }
    std::printf("replayed %s with seed %llu\n", what.c_str(),
                static_cast<unsigned long long>(spec.seed));
    if (!spec.config.physics.empty())
      std::printf("physics: %s (this build's is %s)\n", spec.config.physics.c_str(),
                  ahhs::sim::PhysicsVersion(spec.config.kind, spec.config.joints));
    if (!result.ok) {
      std::printf("the episode failed: %s (a failed episode scores 0 in a run)\n",
                  result.error.c_str());
    }
    if (result.ok) std::printf("behaviour: %s\n", behaviour.Describe().c_str());
    const double fitness = result.ok ? result.fitness : 0;
    if (stored_fitness) {
      if (*stored_fitness == fitness) {
        std::printf("stored fitness %s: reproduced exactly\n",
                    ahhs::base::ExactDouble(*stored_fitness).c_str());
      } else if (physics_step > 0 || friction_scale != 1 || !spec.config.envelope.none() ||
                 physics_changed) {
        std::printf(
            "stored fitness %s: in the changed physics (--physics-step, --friction-scale, "
            "--envelope, --physics) "
            "the replay differs by %.3g\n",
            ahhs::base::ExactDouble(*stored_fitness).c_str(), fitness - *stored_fitness);
      } else {
        std::printf(
            "stored fitness %s: the replay differs by %.3g (the run was evaluated by a build "
            "whose physics or controller differ from this one)\n",
            ahhs::base::ExactDouble(*stored_fitness).c_str(), fitness - *stored_fitness);
      }
    }
    std::printf("fitness: %s\n", ahhs::base::ExactDouble(fitness).c_str());
    std::fflush(stdout);
    for (const auto& [flag, out] :
         {std::pair<std::string, std::string>{"--video", video},
          std::pair<std::string, std::string>{"--filmstrip", filmstrip}}) {
      if (out.empty()) continue;
      std::vector<std::string> args{ahhs::base::ExecutableDir() + "/ahhs-view", film_log, flag,
                                    out};
      if (overwrite) args.push_back("--overwrite");
      if (flag == "--video") {
        args.insert(args.end(), {"--from", ahhs::base::ExactDouble(video_from)});
        if (video_to >= 0) args.insert(args.end(), {"--to", ahhs::base::ExactDouble(video_to)});
      }
      if (const int code = ahhs::base::RunChildToEnd(args); code != 0) {
        std::cerr << "ahhs-replay: " << flag << " " << out << " failed (ahhs-view exit " << code
                  << ")\n";
        return ahhs::cli::kExitFailure;
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "ahhs-replay: " << e.what() << '\n';
    return ahhs::cli::kExitFailure;
  }
  return 0;
}
