#include "tools/study/study_runs.h"

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

#include "base/cli.h"
#include "evolver/store/run_store.h"

namespace cli = ahhs::base::cli;

namespace ahhs::study {

namespace fs = std::filesystem;
using base::kExitFailure;
using base::kExitInterrupted;
using base::kExitUsage;
using nlohmann::json;

namespace {

struct Running {
  StudyRun run;
  std::chrono::steady_clock::time_point started;
};

// The ahhs-evolve command of one run, new or resumed, on its own port (ttl=0), with the run's
// local workers; logged to the run's log, which the command's output is appended to.
std::vector<std::string> EvolveArgv(const StudyDir& study, const StudyRun& run,
                                    const RunOptions& options, const std::string& evolve) {
  const std::string dir = study.RunDir(run);
  std::error_code ec;
  fs::remove(study.FailedFile(run), ec);
  fs::create_directories(fs::path(dir).parent_path(), ec);
  const std::string url = "udpm://239.255.76.67:" + std::to_string(options.port_base + run.index) +
                          "?ttl=0&recv_buf_size=4194304";
  std::vector<std::string> argv{evolve};
  // A run whose database was made (its first export exists) is resumed; anything less is
  // started again from nothing.
  if (fs::exists(fs::path(dir) / "generations.csv", ec))
    argv.insert(argv.end(), {"--resume", dir});
  else
    argv.insert(argv.end(), {"--config", study.ConfigFile(run.config), "--seed",
                             std::to_string(run.seed), "--out", dir, "--overwrite"});
  argv.insert(argv.end(), {"--workers", std::to_string(options.workers_per_run), "--lcm-url", url});
  std::ofstream log(study.LogFile(run), std::ios::app);
  log << "== ahhs-study " << Stamp() << ":";
  for (const auto& a : argv) log << ' ' << a;
  log << '\n';
  return argv;
}

}  // namespace

std::string Stamp() {
  char buf[16];
  const std::time_t now = std::time(nullptr);
  std::strftime(buf, sizeof buf, "%H:%M:%S", std::localtime(&now));
  return buf;
}

std::string Seconds(double s) {
  char buf[32];
  if (s < 120)
    std::snprintf(buf, sizeof buf, "%.0f s", s);
  else if (s < 7200)
    std::snprintf(buf, sizeof buf, "%.0f min", s / 60);
  else
    std::snprintf(buf, sizeof buf, "%.1f h", s / 3600);
  return buf;
}

std::string LastLine(const std::string& path) {
  std::ifstream in(path);
  std::string line, last;
  while (std::getline(in, line)) {
    const auto cr = line.find_last_of('\r');  // progress lines redraw with \r
    if (cr != std::string::npos) line = line.substr(cr + 1);
    if (!line.empty()) last = line;
  }
  return last;
}

std::time_t ParseFinishBy(const std::string& text, std::time_t now) {
  const auto bad = [&] {
    return base::UsageError("--finish-by " + text +
                            ": give a time of day HH:MM or a duration such as 90m, 2.5h or 600s");
  };
  int hours = 0, minutes = 0, used = 0;
  if (std::sscanf(text.c_str(), "%2d:%2d%n", &hours, &minutes, &used) == 2 &&
      used == static_cast<int>(text.size()) && text.size() == 5) {
    if (hours > 23 || minutes > 59) throw bad();
    std::tm t = *std::localtime(&now);
    t.tm_hour = hours;
    t.tm_min = minutes;
    t.tm_sec = 0;
    t.tm_isdst = -1;
    std::time_t at = std::mktime(&t);
    if (at <= now) {  // tomorrow
      ++t.tm_mday;
      t.tm_isdst = -1;
      at = std::mktime(&t);
    }
    return at;
  }
  double amount = 0;
  char unit = 0;
  if (std::sscanf(text.c_str(), "%lf%c%n", &amount, &unit, &used) != 2 ||
      used != static_cast<int>(text.size()) || !(amount > 0) || amount > 1e7)
    throw bad();
  const double scale = unit == 's' ? 1 : unit == 'm' ? 60 : unit == 'h' ? 3600 : 0;
  if (scale == 0) throw bad();
  return now + static_cast<std::time_t>(amount * scale);
}

std::map<std::string, RunTimeEstimate> RunTimeEstimates(const StudyDir& study) {
  std::map<std::string, std::pair<double, int>> here, elsewhere;  // sum, count
  for (const auto& run : study.Runs()) {
    const RunState s = study.State(run);
    if (s.kind != RunStateKind::kComplete) continue;
    auto& [sum, n] = (s.exported_only ? elsewhere : here)[run.config];
    sum += s.wall_time;
    ++n;
  }
  std::map<std::string, RunTimeEstimate> estimates;
  for (const auto& [config, sum_n] : elsewhere)
    estimates[config] = {sum_n.first / sum_n.second, false};
  for (const auto& [config, sum_n] : here) estimates[config] = {sum_n.first / sum_n.second, true};
  return estimates;
}

// ahhs-evolve's resolved configuration (--show-config) of a config file.
json ResolveConfig(const std::string& evolve, const std::string& config_file) {
  const std::string command =
      "'" + evolve + "' --config '" + config_file + "' --seed 1 --show-config 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) throw StudyPlanError("cannot run " + evolve);
  std::string out;
  char buf[4096];
  while (std::size_t n = std::fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
  const int status = pclose(pipe);
  if (status != 0 || out.empty() || out[0] != '{') {
    std::string first = out.substr(0, out.find('\n'));
    throw StudyPlanError("ahhs-evolve refuses it: " + first);
  }
  return json::parse(out);
}

// The study directory is run by one ahhs-study at a time.
ahhs::base::FileLock LockStudy(const std::string& dir) {
  auto lock = ahhs::base::FileLock::TryExclusive(dir + "/study.lock");
  if (!lock) throw std::runtime_error(dir + " is in use by another ahhs-study run");
  return std::move(*lock);
}

// Starts one run's ahhs-evolve (new or resumed) as a child; returns false when the run directory
// stays in use by another process.
bool StartRun(const StudyDir& study, const StudyRun& run, const RunOptions& options,
              const std::atomic<int>& stop, const std::string& evolve,
              ahhs::base::ChildProcesses* children) {
  const std::string dir = study.RunDir(run);
  for (int k = 0; ahhs::evolver::RunStore::InUse(dir); ++k) {
    if (k == 0)
      std::printf("[%s] waiting for the last process of %s to end\n", Stamp().c_str(),
                  run.Name().c_str());
    if (k >= 600 || stop > 0) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  children->Start(run.Name(), EvolveArgv(study, run, options, evolve), false, study.LogFile(run));
  return true;
}

int RunStudy(const StudyDir& study, RunOptions options, const std::atomic<int>& stop) {
  const ahhs::base::FileLock lock = LockStudy(study.dir());
  const std::string evolve = ahhs::base::ExecutableDir() + "/ahhs-evolve";
  if (options.workers_per_run <= 0)
    options.workers_per_run = std::max(
        1, static_cast<int>(std::thread::hardware_concurrency()) / std::max(1, options.parallel));
  if (!options.from_export.empty()) {
    std::vector<std::string> skipped;
    const auto taken = study.Import(options.from_export, &skipped);
    std::printf("from the export %s: %zu complete runs taken\n", options.from_export.c_str(),
                taken.size());
    for (const auto& name : skipped)
      std::printf("  %s: not taken, its configuration or physics differs from this study's\n",
                  name.c_str());
  }
  std::vector<StudyRun> queue;
  int complete = 0;
  const auto runs = study.Runs();
  for (const auto& name : options.only)
    if (std::none_of(study.plan().configs.begin(), study.plan().configs.end(),
                     [&](const StudyConfig& c) { return c.name == name; }))
      throw StudyPlanError("--only " + name + ": the study has no such configuration");
  for (const auto& run : runs) {
    if (study.State(run).kind == RunStateKind::kComplete)
      ++complete;
    else if (options.only.empty() ||
             std::find(options.only.begin(), options.only.end(), run.config) != options.only.end())
      queue.push_back(run);
  }
  std::printf(
      "study %s in %s: %d of %zu runs complete, %zu to run, %d at a time with %d "
      "workers each\n",
      study.plan().name.c_str(), study.dir().c_str(), complete, runs.size(), queue.size(),
      options.parallel, options.workers_per_run);
  std::fflush(stdout);

  const auto estimates =
      options.finish_by != 0 ? RunTimeEstimates(study) : std::map<std::string, RunTimeEstimate>{};
  char finish_by[16] = "";
  if (options.finish_by != 0)
    std::strftime(finish_by, sizeof finish_by, "%H:%M", std::localtime(&options.finish_by));
  ahhs::base::ChildProcesses children;
  std::map<std::size_t, Running> running;  // by child index
  std::size_t next = 0;
  int failed = 0, deferred = 0;
  while ((next < queue.size() || !running.empty()) && stop == 0) {
    while (running.size() < static_cast<std::size_t>(options.parallel) && next < queue.size() &&
           stop == 0) {
      const StudyRun& run = queue[next++];
      // --finish-by: a run whose configuration's run time would end it too late waits for the
      // next session (time only moves on, so it never fits later in this one).
      if (const auto e = estimates.find(run.config);
          e != estimates.end() && static_cast<double>(std::time(nullptr)) + e->second.seconds >
                                      static_cast<double>(options.finish_by)) {
        std::printf("[%s] not starting %s: about %s, it would end after %s (--finish-by)\n",
                    Stamp().c_str(), run.Name().c_str(), Seconds(e->second.seconds).c_str(),
                    finish_by);
        std::fflush(stdout);
        ++deferred;
        continue;
      }
      bool started = false;
      try {
        started = StartRun(study, run, options, stop, evolve, &children);
      } catch (const std::exception& e) {
        std::ofstream(study.FailedFile(run)) << e.what() << '\n';
      }
      if (!started) {
        if (stop > 0) break;
        std::printf("[%s] %s could not start (its directory stays in use)\n", Stamp().c_str(),
                    run.Name().c_str());
        ++failed;
        continue;
      }
      std::printf("[%s] started %s (port %d)\n", Stamp().c_str(), run.Name().c_str(),
                  options.port_base + run.index);
      std::fflush(stdout);
      running[children.size() - 1] = {run, std::chrono::steady_clock::now()};
    }
    const auto ended = children.Reap();
    if (ended.empty()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      continue;
    }
    for (const auto& end : ended) {
      const Running done = running.at(end.index);
      running.erase(end.index);
      const int status = end.status;
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - done.started).count();
      if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
        try {
          study.WriteSummary(done.run);
          ++complete;
          const RunState state = study.State(done.run);
          std::printf("[%s] complete %s: best %.6g after %s; %d of %zu runs complete\n",
                      Stamp().c_str(), done.run.Name().c_str(), state.best.value_or(0.0),
                      Seconds(seconds).c_str(), complete, runs.size());
        } catch (const std::exception& e) {
          std::ofstream(study.FailedFile(done.run)) << e.what() << '\n';
          std::printf("[%s] FAILED %s: %s\n", Stamp().c_str(), done.run.Name().c_str(), e.what());
          ++failed;
        }
      } else if (stop == 0) {
        const std::string why = "ahhs-evolve ended (" + ahhs::base::DescribeExit(status) +
                                "): " + LastLine(study.LogFile(done.run));
        std::ofstream(study.FailedFile(done.run)) << why << '\n';
        std::printf("[%s] FAILED %s: %s (log: %s)\n", Stamp().c_str(), done.run.Name().c_str(),
                    why.c_str(), study.LogFile(done.run).c_str());
        ++failed;
      }
      std::fflush(stdout);
    }
  }
  if (stop > 0) {
    std::printf("[%s] stopping %zu runs (each keeps its committed generations)\n", Stamp().c_str(),
                running.size());
    std::fflush(stdout);
    children.StopAll(std::chrono::seconds(30));
    std::printf("stopped; continue with: %s/ahhs-study run --resume %s\n",
                ahhs::base::ExecutableDir().c_str(), study.dir().c_str());
    return kExitInterrupted;
  }
  if (failed > 0) {
    std::printf("%d runs failed (see: %s/ahhs-study status %s); run --resume to retry them\n",
                failed, ahhs::base::ExecutableDir().c_str(), study.dir().c_str());
    return kExitFailure;
  }
  if (deferred > 0) {
    std::printf(
        "%d %s not started, %s would end after %s (--finish-by); continue with: "
        "%s/ahhs-study run --resume %s\n",
        deferred, deferred == 1 ? "run" : "runs", deferred == 1 ? "it" : "they", finish_by,
        ahhs::base::ExecutableDir().c_str(), study.dir().c_str());
    return 0;
  }
  if (complete < static_cast<int>(runs.size())) {
    std::printf(
        "the chosen configurations are complete; %zu runs of the others wait (run "
        "--resume without --only)\n",
        runs.size() - static_cast<std::size_t>(complete));
    return 0;
  }
  std::printf("study complete: %zu runs in %s\n", runs.size(), study.dir().c_str());
  return 0;
}

// `PLAN --out DIR` makes a new study (its configurations resolved by ahhs-evolve), `--resume
// DIR` opens one; anything else is a usage error.
StudyDir OpenOrCreateStudy(const std::string& plan_file, const std::string& out_dir,
                           const std::string& resume_dir) {
  if (resume_dir.empty() == out_dir.empty())
    throw ahhs::base::UsageError("give PLAN --out DIR for a new study, or --resume DIR");
  if (!resume_dir.empty() && !plan_file.empty())
    throw ahhs::base::UsageError("--resume takes no plan (the study keeps its own)");
  if (!out_dir.empty() && plan_file.empty())
    throw ahhs::base::UsageError("a new study needs a PLAN");
  if (!resume_dir.empty()) return StudyDir::Open(resume_dir);
  const StudyPlan plan = LoadStudyPlan(plan_file);
  const std::string evolve = ahhs::base::ExecutableDir() + "/ahhs-evolve";
  return StudyDir::Create(out_dir, plan_file, plan,
                          [&](const std::string& f) { return ResolveConfig(evolve, f); });
}

// ahhs-study compact: every complete run of format 1 to format 3 (evolver/store/run_store.h).
// A run that another process writes is skipped (it holds the run's lock).
int Compact(const StudyDir& study) {
  std::uint64_t saved = 0;
  int compacted = 0, skipped = 0;
  for (const auto& run : study.Runs()) {
    if (study.State(run).kind != RunStateKind::kComplete) continue;
    try {
      auto store = evolver::RunStore::Open(study.RunDir(run), evolver::StoreAccess::kWrite);
      if (store->format_version() >= 2) continue;
      const std::uint64_t s = store->Compact();
      saved += s;
      ++compacted;
      std::printf("%s: %.1f MB smaller\n", run.Name().c_str(), static_cast<double>(s) / 1e6);
      std::fflush(stdout);
    } catch (const evolver::RunStoreError& e) {
      ++skipped;
      std::fprintf(stderr, "ahhs-study: %s\n", e.what());
    }
  }
  std::printf("compacted %d runs, %.1f MB saved; %d skipped\n", compacted,
              static_cast<double>(saved) / 1e6, skipped);
  return skipped == 0 ? 0 : kExitFailure;
}

int Status(const StudyDir& study) {
  const auto runs = study.Runs();
  std::map<std::string, std::pair<int, int>> per_config;  // complete, total
  std::size_t width = 3;
  for (const auto& run : runs) width = std::max(width, run.Name().size());
  std::vector<std::string> lines;
  int complete = 0, running = 0, failed = 0;
  double remaining_running = 0;
  std::map<std::string, int> waiting;       // per configuration: runs not started or failed
  std::map<std::string, double> projected;  // a running run's whole length, projected
  for (const auto& run : runs) {
    const RunState s = study.State(run);
    auto& [done, total] = per_config[run.config];
    ++total;
    std::string eta = "";
    if (s.kind == RunStateKind::kComplete) {
      ++done;
      ++complete;
    } else if (s.kind == RunStateKind::kRunning) {
      ++running;
      if (s.generations_done > 0) {
        const double per_generation = s.wall_time / s.generations_done;
        const double left = per_generation * (s.generations - s.generations_done);
        remaining_running += left;
        projected[run.config] = per_generation * s.generations;
        eta = Seconds(left);
      }
    } else {
      if (s.kind == RunStateKind::kFailed) ++failed;
      ++waiting[run.config];
    }
    char best[32] = "-";
    if (s.best) std::snprintf(best, sizeof best, "%.6g", *s.best);
    char line[512];
    std::snprintf(line, sizeof line, "%-*s  %-8s  %4d/%-4d  %-10s  %-8s  %s",
                  static_cast<int>(width), run.Name().c_str(),
                  s.exported_only ? "exported" : RunStateName(s.kind), s.generations_done,
                  s.generations, best, eta.c_str(), s.note.c_str());
    lines.push_back(line);
  }
  std::printf("study %s in %s: %d of %zu runs complete, %d running, %d failed\n",
              study.plan().name.c_str(), study.dir().c_str(), complete, runs.size(), running,
              failed);
  std::printf("\n%-*s  %-8s  %-9s  %-10s  %-8s\n", static_cast<int>(width), "run", "state", "gens",
              "best", "ETA");
  for (const auto& l : lines) std::printf("%s\n", l.c_str());
  std::printf("\n%-24s  %-9s  %s\n", "configuration", "complete", "mean run time (here)");
  // The study's time left at this machine's pace, one run at a time: the running runs' ETAs,
  // and each waiting run at its configuration's mean run time here (or, before one is complete,
  // a running run's projected length, or else the mean of its exported runs, made elsewhere);
  // configurations with none of these are counted apart.
  const auto estimates = RunTimeEstimates(study);
  double left = remaining_running;
  int timed = 0, elsewhere = 0, untimed = 0;
  for (const auto& config : study.plan().configs) {
    const auto& [done, total] = per_config[config.name];
    const auto e = estimates.find(config.name);
    const bool here = e != estimates.end() && e->second.here;
    std::printf("%-24s  %4d/%-4d  %s\n", config.name.c_str(), done, total,
                here ? Seconds(e->second.seconds).c_str() : "-");
    const int n = waiting[config.name];
    if (here || projected.count(config.name)) {
      left += n * (here ? e->second.seconds : projected[config.name]);
      timed += n;
    } else if (e != estimates.end()) {
      left += n * e->second.seconds;
      elsewhere += n;
    } else {
      untimed += n;
    }
  }
  if (running + timed + elsewhere + untimed > 0) {
    std::printf("\ntime left here, one run at a time: %s", Seconds(left).c_str());
    std::printf(" (%d running, %d waiting runs at their configuration's run time here", running,
                timed);
    if (elsewhere > 0)
      std::printf(", %d at the run time of their configuration's exported runs (made elsewhere)",
                  elsewhere);
    if (untimed > 0) std::printf("; %d more of configurations not timed yet", untimed);
    std::printf(")\n");
  }
  return 0;
}

// `ahhs-study task DIR --submission S --index I`: runs (or resumes) one run of the study to its
// end in the foreground, as a Slurm array task does. A requeued or restarted task resumes it.
int RunTask(const StudyDir& study, const std::string& submission, int index, RunOptions options,
            const std::atomic<int>& stop) {
  std::ifstream list(SubmissionRuns(submission));
  if (!list) throw std::runtime_error(SubmissionRuns(submission) + " cannot be read");
  std::string name;
  for (int i = 0; i <= index; ++i)
    if (!std::getline(list, name))
      throw std::runtime_error("array index " + std::to_string(index) + ": " +
                               SubmissionRuns(submission) + " has only " + std::to_string(i) +
                               " runs");
  const auto runs = study.Runs();
  const auto it =
      std::find_if(runs.begin(), runs.end(), [&](const StudyRun& r) { return r.Name() == name; });
  if (it == runs.end()) throw std::runtime_error("the study has no run " + name);
  const StudyRun run = *it;
  if (study.State(run).kind == RunStateKind::kComplete) {
    std::printf("[%s] %s is complete already\n", Stamp().c_str(), name.c_str());
    return 0;
  }
  ahhs::base::ChildProcesses children;
  if (!StartRun(study, run, options, stop, ahhs::base::ExecutableDir() + "/ahhs-evolve", &children))
    throw std::runtime_error(study.RunDir(run) + " stays in use by another process");
  std::printf("[%s] started %s (port %d, %d workers)\n", Stamp().c_str(), name.c_str(),
              options.port_base + run.index, options.workers_per_run);
  std::fflush(stdout);
  int status = 0;
  for (bool ended = false; !ended;) {
    if (stop > 0) {
      std::printf("[%s] stopping %s (it keeps its committed generations)\n", Stamp().c_str(),
                  name.c_str());
      children.StopAll(std::chrono::seconds(30));
      return kExitInterrupted;
    }
    for (const auto& end : children.Reap()) {
      status = end.status;
      ended = true;
    }
    if (!ended) std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  if (!(WIFEXITED(status) && WEXITSTATUS(status) == 0)) {
    const std::string why = "ahhs-evolve ended (" + ahhs::base::DescribeExit(status) +
                            "): " + LastLine(study.LogFile(run));
    std::ofstream(study.FailedFile(run)) << why << '\n';
    std::printf("[%s] FAILED %s: %s\n", Stamp().c_str(), name.c_str(), why.c_str());
    return kExitFailure;
  }
  study.WriteSummary(run);
  std::printf("[%s] complete %s: best %.6g\n", Stamp().c_str(), name.c_str(),
              study.State(run).best.value_or(0.0));
  return 0;
}

// Submits the study's unfinished runs (those of `only`, if given) as one Slurm job array.
int Submit(const StudyDir& study, const RunOptions& options, const SlurmOptions& slurm) {
  std::vector<StudyRun> queue;
  for (const auto& name : options.only)
    if (std::none_of(study.plan().configs.begin(), study.plan().configs.end(),
                     [&](const StudyConfig& c) { return c.name == name; }))
      throw StudyPlanError("--only " + name + ": the study has no such configuration");
  for (const auto& run : study.Runs())
    if (study.State(run).kind != RunStateKind::kComplete &&
        (options.only.empty() ||
         std::find(options.only.begin(), options.only.end(), run.config) != options.only.end()))
      queue.push_back(run);
  if (queue.empty()) {
    std::printf("study %s in %s: every chosen run is complete; nothing to submit\n",
                study.plan().name.c_str(), study.dir().c_str());
    return 0;
  }
  int number = 1;
  while (fs::exists(study.dir() + "/slurm/submit-" + std::to_string(number))) ++number;
  const std::string submission = study.dir() + "/slurm/submit-" + std::to_string(number);
  fs::create_directories(submission);
  {
    std::ofstream list(SubmissionRuns(submission));
    for (const auto& run : queue) list << run.Name() << '\n';
  }
  const std::string script = submission + "/array.sh";
  {
    std::ofstream out(script);
    out << "#!/bin/sh\n"
        << "# Made by ahhs-study submit: one array task per line of runs.txt.\n"
        << "#SBATCH --job-name=ahhs-" << study.plan().name << "\n"
        << "#SBATCH --array=0-" << queue.size() - 1 << "\n"
        << "#SBATCH --ntasks=1\n"
        << "#SBATCH --cpus-per-task=" << slurm.cpus_per_run << "\n"
        << "#SBATCH --output=" << submission << "/task-%a.out\n"
        << "#SBATCH --open-mode=append\n"
        << "#SBATCH --requeue\n";
    if (!slurm.partition.empty()) out << "#SBATCH --partition=" << slurm.partition << "\n";
    if (!slurm.time.empty()) out << "#SBATCH --time=" << slurm.time << "\n";
    out << "exec " << (slurm.task_wrapper.empty() ? "" : slurm.task_wrapper + " ") << "'"
        << ahhs::base::ExecutableDir() << "/ahhs-study' task '" << study.dir() << "' --submission '"
        << submission << "' --index \"$SLURM_ARRAY_TASK_ID\" --workers " << slurm.cpus_per_run
        << " --port-base " << options.port_base << "\n";
  }
  fs::permissions(script, fs::perms::owner_all | fs::perms::group_read | fs::perms::others_read);
  const std::string command = "'" + slurm.sbatch + "' --parsable '" + script + "' 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run " + slurm.sbatch);
  std::string out;
  char buf[4096];
  while (std::size_t n = std::fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
  const int status = pclose(pipe);
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  if (status != 0 || out.empty()) {
    fs::remove_all(submission);
    throw std::runtime_error("sbatch refused the job array: " +
                             (out.empty() ? std::string("no output (is Slurm installed?)") : out));
  }
  std::ofstream(submission + "/job") << out << '\n';
  std::printf(
      "study %s in %s: %zu runs submitted as Slurm job array %s (script %s); follow with "
      "squeue and %s/ahhs-study status %s\n",
      study.plan().name.c_str(), study.dir().c_str(), queue.size(), out.c_str(), script.c_str(),
      ahhs::base::ExecutableDir().c_str(), study.dir().c_str());
  return 0;
}

}  // namespace ahhs::study
