// ahhs-study's work, apart from its command line: the local scheduler that runs a study's runs
// of ahhs-evolve as child processes (K at a time, each on its own port), its status, compaction,
// and the Slurm back end (one array task per run). docs/evolution.md, "Studies".
#pragma once

#include <atomic>
#include <ctime>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "base/children.h"
#include "base/cli.h"
#include "base/file_lock.h"
#include "tools/study/study_dir.h"

namespace ahhs::study {

// How a study's runs are started.
struct RunOptions {
  int parallel = 1;
  int workers_per_run = 0;  // 0: cores / parallel
  int port_base = 7700;
  std::string from_export;
  std::vector<std::string> only;  // configurations to run now; empty: all
  // Seconds since the epoch (0: none): start no run whose estimated time (RunTimeEstimates)
  // would end it after this; running runs are not stopped.
  std::time_t finish_by = 0;
};

// --finish-by's time: "HH:MM" (the next such local time, today or tomorrow) or a duration from
// `now` ("90m", "2.5h", "600s"), as seconds since the epoch. Throws base::UsageError.
std::time_t ParseFinishBy(const std::string& text, std::time_t now);

// The time one run of a configuration takes: the mean wall time of its complete runs made here
// (`here`), else of its exported runs (made elsewhere).
struct RunTimeEstimate {
  double seconds = 0;
  bool here = false;
};
// Per configuration with a complete run (made here or exported); `status` and --finish-by use it.
std::map<std::string, RunTimeEstimate> RunTimeEstimates(const StudyDir& study);

// The wall-clock time of day, HH:MM:SS, that begins each line of the scheduler.
std::string Stamp();
// "42 s", "17 min", "3.5 h".
std::string Seconds(double s);
// The last non-empty line of a log (progress lines redraw with \r: the text after the last one).
std::string LastLine(const std::string& path);

// ahhs-evolve's resolved configuration (--show-config) of a config file.
nlohmann::json ResolveConfig(const std::string& evolve, const std::string& config_file);
// The study directory is run by one ahhs-study at a time: throws when another holds it.
base::FileLock LockStudy(const std::string& dir);

// `PLAN --out DIR` makes a new study (its configurations resolved by ahhs-evolve), `--resume
// DIR` opens one; anything else is a usage error (base::UsageError).
StudyDir OpenOrCreateStudy(const std::string& plan_file, const std::string& out_dir,
                           const std::string& resume_dir);

// Starts one run's ahhs-evolve (new or resumed) as a child; returns false when the run directory
// stays in use by another process (or `stop` was raised while waiting for it).
bool StartRun(const StudyDir& study, const StudyRun& run, const RunOptions& options,
              const std::atomic<int>& stop, const std::string& evolve,
              base::ChildProcesses* children);

// `ahhs-study run`: every unfinished run, `options.parallel` at a time, until all are complete
// or `stop` is raised (each run keeps its committed generations). An exit code.
int RunStudy(const StudyDir& study, RunOptions options, const std::atomic<int>& stop);

// `ahhs-study compact`: every complete run of format 1 to format 3 (evolver/store/run_store.h).
// A run that another process writes is skipped (it holds the run's lock). An exit code.
int Compact(const StudyDir& study);

// `ahhs-study status`: one line per run, per configuration, and the study's ETA. An exit code.
int Status(const StudyDir& study);

// --- Slurm: one array task per run (docs/evolution.md, "On a Slurm cluster") ---

struct SlurmOptions {
  std::string partition, time;
  std::string task_wrapper;  // a command every array task runs under (e.g. a container, a netns)
  int cpus_per_run = 1;
  std::string sbatch = "sbatch";
};

// The runs of one submission, one name per line: array task i runs line i.
inline std::string SubmissionRuns(const std::string& submission) {
  return submission + "/runs.txt";
}

// `ahhs-study task DIR --submission S --index I`: runs (or resumes) one run of the study to its
// end in the foreground, as a Slurm array task does. A requeued or restarted task resumes it.
int RunTask(const StudyDir& study, const std::string& submission, int index, RunOptions options,
            const std::atomic<int>& stop);

// Submits the study's unfinished runs (those of `options.only`, if given) as one Slurm job array.
int Submit(const StudyDir& study, const RunOptions& options, const SlurmOptions& slurm);

}  // namespace ahhs::study
