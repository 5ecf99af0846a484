// A study directory (docs/evolution.md, "Studies"):
//   study.toml                 the plan, as given (its presets resolved into configs/)
//   configs/NAME.toml          the configuration ahhs-evolve runs: preset plus overrides
//   configs/NAME.json          its resolved form (ahhs-evolve --show-config, seed 1)
//   NAME/seed-K/               an ordinary run directory (ahhs-evolve), plus summary.json once
//                              the run is complete; a run taken from an export holds only
//                              best.json, generations.csv and summary.json
//   NAME/seed-K.log            what ahhs-evolve printed, every session appended
//   NAME/seed-K.failed         why the last attempt failed (removed when the run is retried)
// An export (ahhs-study export) has the same layout without run databases, logs and per-
// generation files: what a repository keeps, and enough to rebuild the report and replay every
// run's best genome.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "tools/study/study_plan.h"

namespace ahhs::study {

enum class RunStateKind { kPending, kStopped, kRunning, kFailed, kComplete };
const char* RunStateName(RunStateKind kind);

struct RunState {
  RunStateKind kind = RunStateKind::kPending;
  int generations_done = 0;    // committed generations (from generations.csv)
  int generations = 0;         // of the run's configuration
  std::optional<double> best;  // best fitness so far
  double wall_time = 0;        // seconds, sum over the committed generations
  bool exported_only = false;  // complete, taken from an export (no database here)
  std::string note;            // failed: the reason
};

class StudyDir {
 public:
  // Resolves a configuration file (configs/NAME.toml) into ahhs-evolve's JSON form; throws
  // StudyPlanError when ahhs-evolve refuses it.
  using Resolver = std::function<nlohmann::json(const std::string& config_file)>;
  // Makes a new study directory for `plan` (read from `plan_path`, whose text is kept). Refuses
  // a directory that holds anything.
  static StudyDir Create(const std::string& dir, const std::string& plan_path,
                         const StudyPlan& plan, const Resolver& resolve);
  // Opens a study directory (or an export). Throws StudyPlanError.
  static StudyDir Open(const std::string& dir);

  const std::string& dir() const { return dir_; }
  const StudyPlan& plan() const { return plan_; }
  const std::string& plan_text() const { return plan_text_; }
  std::vector<StudyRun> Runs() const { return StudyRuns(plan_); }

  std::string RunDir(const StudyRun& run) const;
  std::string LogFile(const StudyRun& run) const;
  std::string FailedFile(const StudyRun& run) const;
  std::string ConfigFile(const std::string& config) const;  // configs/NAME.toml
  // The run's expected ahhs-evolve configuration (configs/NAME.json with its seed).
  nlohmann::json EvolveConfig(const StudyRun& run) const;

  RunState State(const StudyRun& run) const;

  // Writes NAME/seed-K/summary.json from the finished run's database.
  void WriteSummary(const StudyRun& run) const;

  // Copies every complete run (best.json, generations.csv, summary.json) with the plan and the
  // configurations into `dest`, which must be empty, missing or an export of this same plan.
  // Returns the number of runs in the export.
  int Export(const std::string& dest) const;

  // Takes the runs that the export `src` holds complete, with this study's configuration and
  // this build's physics (sim::kPhysicsVersion), and that are not complete here. Returns the names
  // of the runs taken; a partial run here is replaced. Runs of `src` whose configuration differs
  // are reported in `skipped`.
  std::vector<std::string> Import(const std::string& src, std::vector<std::string>* skipped) const;

 private:
  StudyDir(std::string dir, StudyPlan plan, std::string plan_text);
  std::string dir_;
  StudyPlan plan_;
  std::string plan_text_;
};

}  // namespace ahhs::study
