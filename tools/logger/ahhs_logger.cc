// ahhs-logger: records LCM traffic into a standard LCM log file (read by lcm::LogFile,
// lcm-logplayer, lcm-logplayer-gui), like lcm-logger, without losing the bursts of a lockstep run.
//   ahhs-logger --lcm-url URL [--channel REGEX] [--force] FILE
// Why not lcm-logger: Debian's lcm-logger 1.3.1 subscribes with LCM's default queue of 30
// messages and cannot change it; one lockstep tick of a 5-module gait arena is about 20 messages,
// so a logger that is descheduled for two ticks loses messages (seen in CI: 12 of 400 (module,
// tick) pairs missing from a 2-module pendulum log). This recorder's subscription queue is
// unbounded: LCM's receive thread keeps reading the socket while the file is written.
// Stops on SIGINT or SIGTERM, after handling what has already arrived; prints the number of
// events written to stderr. Exit status 1 for a bad option, an unusable URL, an existing FILE
// without --force or a write error.
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <lcm/lcm-cpp.hpp>
#include <string>

#include "base/cli.h"
#include "bus/wire_version.h"

namespace cli = ahhs::base::cli;

namespace {

volatile std::sig_atomic_t g_stop = 0;
void OnStopSignal(int) { g_stop = 1; }

class Recorder {
 public:
  void set_log(lcm::LogFile* log) { log_ = log; }

  static void OnMessage(const lcm::ReceiveBuffer* rbuf, const std::string& channel,
                        Recorder* self) {
    self->Write(rbuf, channel);
  }
  void Write(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
    if (failed_) return;
    lcm::LogEvent e;
    e.eventnum = events_;
    e.timestamp = rbuf->recv_utime;
    e.channel = channel;
    e.datalen = static_cast<std::int32_t>(rbuf->data_size);
    e.data = rbuf->data;
    if (log_->writeEvent(&e) != 0) {
      failed_ = true;
      return;
    }
    ++events_;
  }
  long events() const { return events_; }
  bool failed() const { return failed_; }

 private:
  lcm::LogFile* log_ = nullptr;
  long events_ = 0;
  bool failed_ = false;
};

}  // namespace

int main(int argc, char** argv) {
  cli::App app{"Record LCM traffic into an LCM log file without dropping bursts"};
  std::string url, channel = ".*", path;
  bool force = false;
  app.add_option("--lcm-url", url, "LCM URL to listen on")->required();
  app.add_option("--channel", channel, "channels to record (LCM regular expression)");
  app.add_flag("-f,--force", force, "overwrite FILE if it exists");
  app.add_option("FILE", path, "the log file to write")->required();
  ahhs::base::SetVersion(app, {ahhs::bus::WireVersionLine()});
  if (const int code = ahhs::base::Parse(app, argc, argv); code >= 0) return code;

  std::error_code ec;
  if (!force && std::filesystem::exists(path, ec)) {
    std::fprintf(stderr, "ahhs-logger: %s exists (use --force to overwrite)\n", path.c_str());
    return 1;
  }
  // Our owner may start us with SIGINT ignored; a stop signal must end the recording cleanly.
  struct sigaction stop {};
  stop.sa_handler = OnStopSignal;
  sigemptyset(&stop.sa_mask);
  sigaction(SIGINT, &stop, nullptr);
  sigaction(SIGTERM, &stop, nullptr);

  lcm::LCM lcm(url);
  if (!lcm.good()) {
    std::fprintf(stderr, "ahhs-logger: cannot open LCM URL %s\n", url.c_str());
    return 1;
  }
  // Subscribe before the file exists: its existence tells a launcher that from now on every
  // message is recorded (LCM's receive thread queues them until the loop below writes them).
  Recorder recorder;
  lcm::Subscription* sub = lcm.subscribeFunction(channel, &Recorder::OnMessage, &recorder);
  sub->setQueueCapacity(1 << 30);  // effectively unbounded (LCM 1.3.1 has no "no limit" value)
  lcm::LogFile log(path, "w");
  if (!log.good()) {
    std::fprintf(stderr, "ahhs-logger: cannot write %s\n", path.c_str());
    return 1;
  }
  recorder.set_log(&log);

  while (!g_stop && !recorder.failed()) lcm.handleTimeout(100);
  // Write what LCM's receive thread has already queued, then stop.
  while (!recorder.failed() && lcm.handleTimeout(20) > 0) {
  }
  if (recorder.failed()) {
    std::fprintf(stderr, "ahhs-logger: write error on %s after %ld events\n", path.c_str(),
                 recorder.events());
    return 1;
  }
  std::fprintf(stderr, "ahhs-logger: %ld events written to %s\n", recorder.events(), path.c_str());
  return 0;
}
