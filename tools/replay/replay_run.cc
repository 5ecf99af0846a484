#include "tools/replay/replay_run.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <vector>

#include "base/atomic_file.h"
#include "base/children.h"
#include "base/cli.h"
#include "base/format.h"
#include "base/temp_files.h"
#include "episode/arena/direct_arena.h"
#include "episode/arena/episode_recorder.h"
#include "episode/arena/post_eval.h"
#include "episode/arena/robustness.h"
#include "modules/core/genome_json.h"
#include "modules/core/random.h"
#include "sim/core/behaviour.h"

namespace ahhs::replay {
namespace {

namespace fs = std::filesystem;
namespace ep = ahhs::episode;
namespace am = ahhs::modules;
using TextWriter = ahhs::base::AtomicTextFile;

}  // namespace

int RunReplay(const ReplayOptions& o, const ReplayTarget& t) {
  const bool film = !o.video.empty() || !o.filmstrip.empty();
  std::unique_ptr<ahhs::base::TempDir> film_dir;  // a private folder, removed at the end
  std::string film_log = o.log_file;
  if (film && o.log_file.empty()) {
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
        !film_log.empty() || !o.csv_file.empty() || !o.rules_csv.empty() || !o.body_csv.empty();
    ep::EpisodeRecorder recorder(t.spec, film_log, o.csv_file, o.rules_csv, o.body_csv);
    ahhs::sim::BehaviourSummary behaviour;
    std::vector<double> commands;
    const ep::EpisodeResult result = ep::RunDirectEpisode(t.spec, [&](const ep::DirectTick& tick) {
      commands.clear();
      for (int c = 0; c < tick.organism->size(); ++c) {
        const auto& a = tick.organism->state(c).actuators;
        commands.insert(commands.end(), a.data(), a.data() + a.size());
      }
      behaviour.Observe(*tick.scenario, commands);
      if (record) recorder.Observe(tick);
    });
    recorder.Commit(result);
    if (o.mutants > 0) {
      TextWriter out(o.mutants_csv);
      out.out() << "mutant,fitness,genome_hash\n";
      out.out() << "original," << ahhs::base::ExactDouble(result.ok ? result.fitness : 0) << ','
                << am::GenomeHash(t.spec.genome) << '\n';
      am::Rng rng(o.mutant_seed);
      for (int k = 0; k < o.mutants; ++k) {
        ep::EpisodeSpec mutant = t.spec;
        am::MutateOneGene(&mutant.genome, t.mutation, rng);
        const ep::EpisodeResult r = ep::RunDirectEpisode(mutant);
        out.out() << k << ',' << ahhs::base::ExactDouble(r.ok ? r.fitness : 0) << ','
                  << am::GenomeHash(mutant.genome) << '\n';
      }
      out.Commit();
      std::printf("%d single mutants evaluated into %s\n", o.mutants, o.mutants_csv.c_str());
    }
    if (o.robustness > 0) {
      const ep::Robustness r = ep::MeasureRobustness(t.spec, o.robustness);
      if (!o.robustness_csv.empty()) {
        TextWriter out(o.robustness_csv);
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
    if (o.post_eval > 0) {
      const ep::PostEvaluation p = ep::PostEvaluate(t.spec, t.post_envelope, o.post_eval);
      std::printf("%s\n", p.Describe().c_str());
      if (!o.post_eval_json.empty()) {
        nlohmann::json doc = p.ToJson();
        doc["description"] = p.Describe();
        doc["genome_hash"] = am::GenomeHashText(t.spec.genome);
        ahhs::base::WriteFileAtomically(o.post_eval_json, doc.dump(2) + "\n");
      }
    }
    std::printf("replayed %s with seed %llu\n", t.what.c_str(),
                static_cast<unsigned long long>(t.spec.seed));
    if (!t.spec.config.physics.empty())
      std::printf("physics: %s (this build's is %s)\n", t.spec.config.physics.c_str(),
                  ahhs::sim::PhysicsVersion(t.spec.config.kind, t.spec.config.docking));
    if (!result.ok) {
      std::printf("the episode failed: %s (a failed episode scores 0 in a run)\n",
                  result.error.c_str());
    }
    if (result.ok) std::printf("behaviour: %s\n", behaviour.Describe().c_str());
    const double fitness = result.ok ? result.fitness : 0;
    if (t.stored_fitness) {
      if (*t.stored_fitness == fitness) {
        std::printf("stored fitness %s: reproduced exactly\n",
                    ahhs::base::ExactDouble(*t.stored_fitness).c_str());
      } else if (o.physics_step > 0 || o.friction_scale != 1 || !t.spec.config.envelope.none() ||
                 t.physics_changed) {
        std::printf(
            "stored fitness %s: in the changed physics (--physics-step, --friction-scale, "
            "--envelope, --physics) "
            "the replay differs by %.3g\n",
            ahhs::base::ExactDouble(*t.stored_fitness).c_str(), fitness - *t.stored_fitness);
      } else {
        std::printf(
            "stored fitness %s: the replay differs by %.3g (the run was evaluated by a build "
            "whose physics or controller differ from this one)\n",
            ahhs::base::ExactDouble(*t.stored_fitness).c_str(), fitness - *t.stored_fitness);
      }
    }
    std::printf("fitness: %s\n", ahhs::base::ExactDouble(fitness).c_str());
    std::fflush(stdout);
    for (const auto& [flag, out] :
         {std::pair<std::string, std::string>{"--video", o.video},
          std::pair<std::string, std::string>{"--filmstrip", o.filmstrip}}) {
      if (out.empty()) continue;
      std::vector<std::string> args{ahhs::base::ExecutableDir() + "/ahhs-view", film_log, flag,
                                    out};
      if (o.overwrite) args.push_back("--overwrite");
      if (flag == "--video") {
        args.insert(args.end(), {"--from", ahhs::base::ExactDouble(o.video_from)});
        if (o.video_to >= 0) args.insert(args.end(), {"--to", ahhs::base::ExactDouble(o.video_to)});
      }
      if (const int code = ahhs::base::RunChildToEnd(args); code != 0) {
        std::cerr << "ahhs-replay: " << flag << " " << out << " failed (ahhs-view exit " << code
                  << ")\n";
        return ahhs::base::kExitFailure;
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "ahhs-replay: " << e.what() << '\n';
    return ahhs::base::kExitFailure;
  }
  return 0;
  return 0;
}

}  // namespace ahhs::replay
