#include "base/children.h"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <utility>

namespace ahhs::base {

pid_t SpawnChild(const std::vector<std::string>& argv, bool quiet, const std::string& output_file) {
  int out_fd = -1;
  if (!output_file.empty()) {
    out_fd = open(output_file.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (out_fd < 0) throw std::runtime_error("cannot write " + output_file);
  }
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) {
    if (out_fd >= 0) close(out_fd);
    throw std::runtime_error("fork failed");
  }
  if (pid > 0) {
    if (out_fd >= 0) close(out_fd);
    return pid;
  }
  // The child.
  prctl(PR_SET_PDEATHSIG, SIGTERM);  // never outlive the owner
  if (getppid() != parent) _exit(1);
  std::signal(SIGINT, SIG_IGN);  // Ctrl-C goes to the owner, which stops us in order
  if (out_fd >= 0) {
    dup2(out_fd, STDOUT_FILENO);
    dup2(out_fd, STDERR_FILENO);
  } else if (quiet) {
    FILE* devnull = std::fopen("/dev/null", "w");
    if (devnull) dup2(fileno(devnull), STDOUT_FILENO);
  }
  // The owner's sockets (e.g. its LCM bus) stay with the owner.
  for (int fd = 3; fd < 1024; ++fd) close(fd);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  execv(args[0], args.data());
  std::fprintf(stderr, "cannot run %s\n", args[0]);
  _exit(127);
}

void StopChildren(std::vector<pid_t>* pids, std::chrono::milliseconds grace) {
  for (pid_t pid : *pids)
    if (pid > 0) kill(pid, SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + grace;
  for (pid_t& pid : *pids) {
    while (pid > 0) {
      if (waitpid(pid, nullptr, WNOHANG) != 0) {
        pid = -1;
      } else if (std::chrono::steady_clock::now() > deadline) {
        kill(pid, SIGKILL);
        waitpid(pid, nullptr, 0);
        pid = -1;
      } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
    }
  }
}

std::string ExecutableDir() {
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return ".";
  const std::string path(buf, static_cast<std::size_t>(n));
  return path.substr(0, path.rfind('/'));
}

std::string DataDir() {
  std::error_code ec;
  const std::filesystem::path dir =
      std::filesystem::path(ExecutableDir()) / ".." / "share" / "ahhs";
  const std::filesystem::path resolved = std::filesystem::weakly_canonical(dir, ec);
  return (ec ? dir : resolved).string();
}

int RunChildToEnd(const std::vector<std::string>& argv,
                  const std::function<bool()>& stop_requested) {
  const pid_t pid = SpawnChild(argv, false);
  bool stopping = false;
  int status = 0;
  while (true) {
    const pid_t r = waitpid(pid, &status, WNOHANG);
    if (r == pid || (r < 0 && errno != EINTR)) break;
    if (!stopping && stop_requested && stop_requested()) {
      kill(pid, SIGTERM);
      stopping = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : WEXITSTATUS(status);
}

pid_t ParentPidFromStat(const std::string& stat) {
  const auto close = stat.rfind(')');
  if (close == std::string::npos) return -1;
  std::istringstream rest(stat.substr(close + 1));
  std::string state;
  long ppid = -1;
  if (!(rest >> state >> ppid) || ppid < 0) return -1;
  return static_cast<pid_t>(ppid);
}

std::vector<ProcessSample> DescendantSamples() {
  std::map<pid_t, std::vector<std::pair<pid_t, char>>> children;  // by parent: pid, state
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/proc", ec)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream f(entry.path() / "stat");
    std::string line;
    if (!std::getline(f, line)) continue;  // ended meanwhile
    const pid_t ppid = ParentPidFromStat(line);
    const auto close = line.rfind(')');
    if (ppid > 0 && close + 2 < line.size())
      children[ppid].emplace_back(static_cast<pid_t>(std::stol(name)), line[close + 2]);
  }
  std::vector<ProcessSample> out;
  std::vector<pid_t> todo{getpid()};
  while (!todo.empty()) {
    const pid_t pid = todo.back();
    todo.pop_back();
    for (const auto& [child, state] : children[pid]) {
      std::ifstream f("/proc/" + std::to_string(child) + "/schedstat");
      std::int64_t cpu = 0;
      if (f >> cpu) out.push_back({child, state, cpu});
      todo.push_back(child);
    }
  }
  return out;
}

bool CpuStarvation::Starved() {
  const auto now = std::chrono::steady_clock::now();
  if (sampled_ && now - at_ < interval_) return starved_;
  std::vector<ProcessSample> samples = DescendantSamples();
  if (sampled_) {
    const double wall_ns = std::chrono::duration<double, std::nano>(now - at_).count();
    starved_ = false;
    for (const ProcessSample& s : samples)
      for (const ProcessSample& before : last_)
        if (s.pid == before.pid && s.state == 'R' && before.state == 'R' &&
            static_cast<double>(s.cpu_ns - before.cpu_ns) < share_ * wall_ns)
          starved_ = true;
  }
  sampled_ = true;
  at_ = now;
  last_ = std::move(samples);
  return starved_;
}

std::string HostName() {
  char buf[256] = {0};
  if (gethostname(buf, sizeof buf - 1) != 0) return "localhost";
  return buf;
}

std::string DescribeExit(int status) {
  if (WIFSIGNALED(status)) return "killed by signal " + std::to_string(WTERMSIG(status));
  return "exit status " + std::to_string(WEXITSTATUS(status));
}

ChildProcesses::~ChildProcesses() { StopAll(std::chrono::seconds(3)); }

std::size_t ChildProcesses::Start(std::string name, std::vector<std::string> argv, bool quiet,
                                  std::string output_file) {
  Child c{std::move(name), std::move(argv), quiet, std::move(output_file), -1};
  c.pid = SpawnChild(c.argv, c.quiet, c.output_file);
  children_.push_back(std::move(c));
  return children_.size() - 1;
}

void ChildProcesses::Restart(std::size_t index) {
  Child& c = children_.at(index);
  if (c.pid > 0) return;
  c.pid = SpawnChild(c.argv, c.quiet, c.output_file);
}

std::vector<ChildProcesses::Ended> ChildProcesses::Reap() {
  std::vector<Ended> ended;
  for (std::size_t k = 0; k < children_.size(); ++k) {
    Child& c = children_[k];
    int status = 0;
    if (c.pid > 0 && waitpid(c.pid, &status, WNOHANG) == c.pid) {
      c.pid = -1;
      ended.push_back({k, c.name, status});
    }
  }
  return ended;
}

std::size_t ChildProcesses::running() const {
  std::size_t n = 0;
  for (const auto& c : children_) n += c.pid > 0 ? 1 : 0;
  return n;
}

void ChildProcesses::Signal(std::size_t index, int sig) {
  if (children_.at(index).pid > 0) kill(children_[index].pid, sig);
}

void ChildProcesses::StopAll(std::chrono::milliseconds grace) {
  std::vector<pid_t> pids;
  for (const auto& c : children_) pids.push_back(c.pid);
  StopChildren(&pids, grace);
  for (auto& c : children_) c.pid = -1;
}

}  // namespace ahhs::base
