// Child processes: the one home for starting, watching, restarting and stopping the programs a
// process owns (the process arena's sim, monitor and modules; ahhs-evolve's local workers;
// ahhs-worker's slots; ahhs-study's runs). A child dies with its owner (PR_SET_PDEATHSIG).
#pragma once

#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace ahhs::base {

// Starts `argv` (argv[0] a path) as a child that dies with this process and ignores Ctrl-C (its
// owner stops it in order). With `quiet` its stdout goes to /dev/null; with an `output_file` its
// stdout and stderr are appended to that file. No descriptor beyond stdin/stdout/stderr is
// inherited. Throws std::runtime_error when fork fails or the output file cannot be opened.
pid_t SpawnChild(const std::vector<std::string>& argv, bool quiet,
                 const std::string& output_file = "");

// Sends SIGTERM to every child (pid > 0), waits up to `grace`, then SIGKILLs the rest. Sets
// every pid to -1.
void StopChildren(std::vector<pid_t>* pids, std::chrono::milliseconds grace);

// Directory of the running executable (where the others are found: ahhs-sim, ahhs-worker, ...).
std::string ExecutableDir();

// The tools' shared files (the viewer's page, the report's Python, presets, study plans):
// ExecutableDir()/../share/ahhs with symbolic links resolved. The same in a build tree (CMake
// links build/share/ahhs to the sources) and in an installed one, which can therefore move.
std::string DataDir();

// Runs `argv` as a child (SpawnChild, output on ours) and waits for it: its exit code, or 128 +
// the signal that killed it. While it runs, `stop_requested` (when given) is asked every 50 ms;
// once true the child gets SIGTERM. Throws std::runtime_error when fork fails.
int RunChildToEnd(const std::vector<std::string>& argv,
                  const std::function<bool()>& stop_requested = {});

// "exit status N" or "killed by signal N" for a waitpid status.
std::string DescribeExit(int status);

// This machine's host name ("localhost" when it has none): names workers and runs.
std::string HostName();

// The parent pid in a /proc/PID/stat line, or -1 when the line is malformed. The command name
// may hold spaces and parentheses: the fields after it begin after its last ')'.
pid_t ParentPidFromStat(const std::string& stat);

// This process's descendants (its children, theirs, ...) as /proc shows them now: each one's
// pid, scheduler state ('R' running or waiting for a CPU, 'S' asleep, ...) and CPU time in
// nanoseconds (/proc/PID/schedstat). Empty where /proc does not give them.
struct ProcessSample {
  pid_t pid = 0;
  char state = '?';
  std::int64_t cpu_ns = 0;
};
std::vector<ProcessSample> DescendantSamples();

// Whether this process's descendants are starved of CPU: a descendant that is runnable ('R')
// now and was runnable at the sample before, at least `interval` ago, but ran for less than
// `share` of the time between them, is waiting for a CPU that the machine gives to others (a
// busy machine that runs it at idle priority); one that runs (a busy loop on an idle machine)
// or sleeps (waiting, hung) is not starved. Starved() samples at most once per `interval` and
// otherwise returns its last answer; its first answer is false.
class CpuStarvation {
 public:
  explicit CpuStarvation(std::chrono::milliseconds interval = std::chrono::seconds(1),
                         double share = 0.5)
      : interval_(interval), share_(share) {}
  bool Starved();

 private:
  std::chrono::milliseconds interval_;
  double share_;
  bool sampled_ = false, starved_ = false;
  std::chrono::steady_clock::time_point at_;
  std::vector<ProcessSample> last_;
};

// A set of named children. The destructor stops those still running (SIGTERM, then SIGKILL).
class ChildProcesses {
 public:
  struct Ended {
    std::size_t index;
    std::string name;
    int status;  // waitpid's
    bool ok() const { return status == 0; }
  };

  ChildProcesses() = default;
  ~ChildProcesses();
  ChildProcesses(const ChildProcesses&) = delete;
  ChildProcesses& operator=(const ChildProcesses&) = delete;

  // Starts a child (SpawnChild) and returns its index. Throws std::runtime_error.
  std::size_t Start(std::string name, std::vector<std::string> argv, bool quiet,
                    std::string output_file = "");
  // Starts an ended child again with the same arguments.
  void Restart(std::size_t index);
  // The children that ended since the last call; never blocks.
  std::vector<Ended> Reap();
  bool alive(std::size_t index) const { return children_.at(index).pid > 0; }
  pid_t pid(std::size_t index) const { return children_.at(index).pid; }
  std::size_t size() const { return children_.size(); }
  std::size_t running() const;
  void Signal(std::size_t index, int sig);
  // SIGTERM to every running child, SIGKILL to those still there after `grace`.
  void StopAll(std::chrono::milliseconds grace);

 private:
  struct Child {
    std::string name;
    std::vector<std::string> argv;
    bool quiet = false;
    std::string output_file;
    pid_t pid = -1;
  };
  std::vector<Child> children_;
};

}  // namespace ahhs::base
