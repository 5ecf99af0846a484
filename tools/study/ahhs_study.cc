// ahhs-study: many runs of ahhs-evolve, described by a study plan (docs/evolution.md, "Studies").
//   ahhs-study run PLAN --out DIR [--parallel K] [--workers-per-run N] [--from-export EXPORT]
//                                 [--only CONFIGS] [--finish-by HH:MM|DURATION]
//   ahhs-study run --resume DIR [...]
//   ahhs-study status DIR
//   ahhs-study export DIR EXPORT
//   ahhs-study report DIR -o OUT
//   ahhs-study submit PLAN --out DIR --slurm [...] | submit --resume DIR --slurm
//   ahhs-study task DIR --submission S --index I    (a Slurm array task)
// Exit codes: 0 done, 1 a run or the study failed, 2 bad options or plan, 130 interrupted.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <thread>

#include "base/children.h"
#include "base/cli.h"
#include "evolver/store/run_store.h"
#include "sim/core/constants.h"
#include "tools/study/study_runs.h"

namespace cli = ahhs::base::cli;

namespace fs = std::filesystem;
namespace st = ahhs::study;
using nlohmann::json;

using ahhs::base::kExitFailure;
using ahhs::base::kExitUsage;

namespace {

std::atomic<int> g_signals{0};
void OnSignal(int) { g_signals.fetch_add(1); }

}  // namespace

int main(int argc, char** argv) {
  cli::App app{"ahhs-study: many ahhs-evolve runs from a study plan, resumable at any moment"};
  app.require_subcommand(1);
  std::string plan_file, out_dir, resume_dir, study_dir, export_dir;
  st::RunOptions options;
  cli::App* run = app.add_subcommand("run", "run (or resume) a study on this machine");
  run->add_option("plan", plan_file, "study plan (TOML, e.g. studies/paper-2010.toml)");
  auto* out = run->add_option("--out", out_dir, "new study directory");
  auto* resume = run->add_option("--resume", resume_dir, "continue the study in this directory");
  out->excludes(resume);
  run->add_option("--parallel", options.parallel, "runs at a time")
      ->check(cli::Range(1, 64))
      ->capture_default_str();
  run->add_option("--workers-per-run", options.workers_per_run,
                  "local ahhs-worker processes of each run (default: cores / parallel)")
      ->check(cli::Range(1, 256));
  run->add_option("--port-base", options.port_base,
                  "run i of the plan uses LCM port BASE + i (ttl=0), so runs never share workers")
      ->check(cli::Range(1024, 60000))
      ->capture_default_str();
  run->add_option("--only", options.only,
                  "run only these configurations now (comma-separated names); the others wait")
      ->delimiter(',');
  run->add_option("--from-export", options.from_export,
                  "take the complete runs of this export (ahhs-study export) instead of running "
                  "them again");
  std::string finish_by;
  run->add_option("--finish-by", finish_by,
                  "start no run that would end after this (HH:MM, or a duration: 90m, 2.5h), "
                  "at its configuration's mean run time as `status` estimates it; running runs "
                  "go on; a configuration not yet timed always starts");
  cli::App* status = app.add_subcommand("status", "per run: state, generation, best, ETA");
  status->add_option("study", study_dir, "study directory or export")->required();
  cli::App* exp = app.add_subcommand(
      "export",
      "copy the complete runs' best genome, generations and summary (what a repository "
      "keeps) into EXPORT");
  exp->add_option("study", study_dir, "study directory")->required();
  exp->add_option("export", export_dir, "export directory (new, or an export of this study)")
      ->required();
  cli::App* compact = app.add_subcommand(
      "compact",
      "shrink the study's complete runs of run format 1 to format 3 (genomes of every 20th "
      "generation; the others bred again when read), each checked first");
  compact->add_option("study", study_dir, "study directory")->required();
  cli::App* submit = app.add_subcommand(
      "submit", "submit a study's unfinished runs to a Slurm cluster as one job array");
  st::SlurmOptions slurm;
  bool use_slurm = false;
  st::RunOptions submit_options;
  submit->add_option("plan", plan_file, "study plan (TOML)");
  auto* submit_out =
      submit->add_option("--out", out_dir, "new study directory (shared filesystem)");
  auto* submit_resume =
      submit->add_option("--resume", resume_dir, "submit the unfinished runs of this study");
  submit_out->excludes(submit_resume);
  submit->add_flag("--slurm", use_slurm, "submit to Slurm (sbatch), the only engine")->required();
  submit->add_option("--partition", slurm.partition, "Slurm partition (default: the cluster's)");
  submit
      ->add_option("--cpus-per-run", slurm.cpus_per_run,
                   "cores of each array task: its run's local workers")
      ->check(cli::Range(1, 256))
      ->capture_default_str();
  submit->add_option("--time", slurm.time, "time limit of each array task (Slurm's format)");
  submit->add_option("--task-wrapper", slurm.task_wrapper,
                     "a command each array task runs ahhs-study task under (for example "
                     "'apptainer exec IMAGE' or tools/ahhs-netns)");
  submit
      ->add_option("--port-base", submit_options.port_base,
                   "run i of the plan uses LCM port BASE + i (ttl=0) on its node")
      ->check(cli::Range(1024, 60000))
      ->capture_default_str();
  submit->add_option("--only", submit_options.only, "submit only these configurations")
      ->delimiter(',');
  submit->add_option("--from-export", submit_options.from_export,
                     "take the complete runs of this export instead of running them again");
  cli::App* task = app.add_subcommand(
      "task", "run one run of a submission to its end (what a Slurm array task does)");
  std::string submission;
  int task_index = 0;
  st::RunOptions task_options;
  task_options.workers_per_run = 1;
  task->add_option("study", study_dir, "study directory")->required();
  task->add_option("--submission", submission, "submission directory (STUDY/slurm/submit-N)")
      ->required();
  task->add_option("--index", task_index, "array index: line of the submission's runs.txt")
      ->required()
      ->check(cli::Range(0, 1000000));
  task->add_option("--workers", task_options.workers_per_run, "local ahhs-worker processes")
      ->check(cli::Range(1, 256));
  task->add_option("--port-base", task_options.port_base, "as ahhs-study submit's")
      ->check(cli::Range(1024, 60000));
  cli::App* report = app.add_subcommand(
      "report",
      "compare the configurations of each scenario and the paper's claims (ahhs-report study): "
      "figures, results.md");
  std::string report_dir;
  bool overwrite = false, no_replay = false;
  report->add_option("study", study_dir, "study directory or export")->required();
  report->add_option("-o,--out", report_dir, "output directory")->required();
  report->add_flag("--overwrite", overwrite, "replace a report in --out");
  report->add_flag("--no-replay", no_replay, "no replay figures and no mutation neighbourhoods");
  ahhs::base::SetVersion(
      app, {ahhs::evolver::RunStore::FormatVersionLine(), ahhs::sim::PhysicsVersionLine()});
  if (const int code = ahhs::base::Parse(app, argc, argv); code >= 0) return code;

  try {
    if (*run || *task) {  // Ctrl-C, and Slurm's cancel, time limit and requeue: stop cleanly
      std::signal(SIGINT, OnSignal);
      std::signal(SIGTERM, OnSignal);
    }
    if (*run && !finish_by.empty())
      options.finish_by = st::ParseFinishBy(finish_by, std::time(nullptr));
    if (*run)
      return st::RunStudy(st::OpenOrCreateStudy(plan_file, out_dir, resume_dir), options,
                          g_signals);
    if (*status) return st::Status(st::StudyDir::Open(study_dir));
    if (*submit) {
      const st::StudyDir study = st::OpenOrCreateStudy(plan_file, out_dir, resume_dir);
      if (!submit_options.from_export.empty()) study.Import(submit_options.from_export, nullptr);
      return st::Submit(study, submit_options, slurm);
    }
    if (*task)
      return st::RunTask(st::StudyDir::Open(study_dir), submission, task_index, task_options,
                         g_signals);
    if (*report) {
      // The statistics and figures are ahhs-report's (Python): hand over to it.
      const std::string tool = ahhs::base::ExecutableDir() + "/ahhs-report";
      std::vector<std::string> args{tool, "study", study_dir, "-o", report_dir};
      if (overwrite) args.push_back("--overwrite");
      if (no_replay) args.push_back("--no-replay");
      std::vector<char*> argv_out;
      for (auto& a : args) argv_out.push_back(a.data());
      argv_out.push_back(nullptr);
      ::execv(tool.c_str(), argv_out.data());
      throw std::runtime_error("cannot run " + tool + ": " + std::strerror(errno));
    }
    if (*compact) return st::Compact(st::StudyDir::Open(study_dir));
    if (*exp) {
      const int n = st::StudyDir::Open(study_dir).Export(export_dir);
      std::printf("exported %d complete runs to %s\n", n, export_dir.c_str());
      return 0;
    }
  } catch (const ahhs::base::UsageError& e) {
    std::cerr << "ahhs-study: " << e.what() << '\n';
    return kExitUsage;
  } catch (const st::StudyPlanError& e) {
    std::cerr << "ahhs-study: " << e.what() << '\n';
    return kExitUsage;
  } catch (const std::exception& e) {
    std::cerr << "ahhs-study: " << e.what() << '\n';
    return kExitFailure;
  }
  return 0;
}
