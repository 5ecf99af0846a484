#include "tools/replay/replay_options.h"

#include "modules/core/random.h"

namespace cli = ahhs::base::cli;

namespace ahhs::replay {

namespace am = ahhs::modules;

void AddReplayOptions(cli::App& app, ReplayOptions* o) {
  app.add_option("run", o->run_dir, "run directory of ahhs-evolve");
  app.add_option("--generation", o->generation, "generation (default: the run's best individual)");
  app.add_option("--individual", o->individual,
                 "individual of --generation (default: that generation's best)");
  app.add_option("--genome", o->genome_file, "a genome file instead of a run")
      ->check(cli::ExistingFile);
  // A genome file that names its run's configuration replays in that run's scenario; these
  // options override it.
  o->scenario.Add(app, "with --genome (default: its run's, if the file names it): ",
                  "simulated seconds (0: the scenario's)");
  app.add_option("--seed", o->seed,
                 "evaluation seed, 0 to 2^64-1 (default: the stored one: the run's, or the genome "
                 "file's; else 1)")
      ->check(am::SeedTextError);
  app.add_option("--log", o->log_file, "write the episode as an LCM log");
  app.add_option("--csv", o->csv_file, "write the per-tick trace as CSV");
  app.add_option(
         "--physics-step", o->physics_step,
         "seconds per physics step (gait) or RK4 step (pendulum) instead of the scenario's: "
         "does the behaviour depend on the discretisation? (docs/scenarios.md)")
      ->check(cli::Range(0.0001, 0.05));
  app.add_option("--friction-scale", o->friction_scale,
                 "multiply the friction coefficients (gait) or pivot friction (pendulum) by this: "
                 "a perturbed physics (docs/scenarios.md)")
      ->check(cli::Range(0.01, 10.0));
  app.add_option("--physics", o->physics,
                 "the physics version to replay with (default: the one the run or genome file "
                 "names, else this build's; docs/reference.md lists those this build keeps)");
  app.add_option("--robustness", o->robustness,
                 "also replay N times with the friction scaled from 0.975 to 1.025 (not 1): is the "
                 "fitness robust or a knife-edge of deterministic chaos? (docs/scenarios.md)")
      ->check(cli::Range(2, 1000));
  app.add_option("--robustness-csv", o->robustness_csv, "where --robustness writes its results");
  o->envelope_options.Add(app,
                          "an envelope of noise for every episode replayed (default none; with "
                          "--post-eval: paper)");
  app.add_option("--post-eval", o->post_eval,
                 "also replay on N held-out episodes (seeds no run evaluates with) under the "
                 "envelope: median, quartiles, min, and the share that succeeds "
                 "(docs/evolution.md)")
      ->check(cli::Range(1, 100000));
  app.add_option("--post-eval-json", o->post_eval_json,
                 "where --post-eval writes every episode and figure (JSON)");
  app.add_option("--body-csv", o->body_csv,
                 "write the organism per tick as CSV (pendulum: cart_x, pole_angle in rad; gait: "
                 "centroid_x, centroid_y in m)");
  app.add_option("--rules-csv", o->rules_csv, "write how often each rule triggered, per module");
  app.add_option("--mutants", o->mutants, "evaluate this many single mutants of the genome")
      ->check(cli::Range(0, 100000));
  app.add_option("--mutants-csv", o->mutants_csv, "where --mutants writes its results");
  app.add_flag("--overwrite", o->overwrite, "replace output files that exist");
  app.add_option("--mutant-seed", o->mutant_seed, "seed of the mutations")
      ->check(am::SeedTextError)
      ->capture_default_str();
  app.add_option("--mutation-profile", o->mutation_profile,
                 "operator of the mutants: paper or fine-doses (default: the run's, else paper)")
      ->check(cli::IsMember({"paper", "fine-doses"}));
  app.add_option("--video", o->video,
                 "film the episode: an H.264 MP4, 1280x720, 25 fps (ahhs-view)");
  app.add_option("--filmstrip", o->filmstrip, "8 frames across the episode in one PNG (ahhs-view)");
  app.add_option("--from", o->video_from, "--video: start, simulated seconds")
      ->check(cli::Range(0.0, 1e6));
  app.add_option("--to", o->video_to, "--video: end, simulated seconds (default: the end)")
      ->check(cli::Range(0.0, 1e6));
}

}  // namespace ahhs::replay
