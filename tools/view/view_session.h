// What one ahhs-view process shows: a log's recordings, a run's newest best (RunFollower) or a
// live arena (LiveBridge), as the page's greeting and the events sent to its pages.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "base/temp_files.h"
#include "bus/bus.h"
#include "tools/view/live_bridge.h"
#include "tools/view/run_follower.h"
#include "tools/view/view_events.h"
#include "tools/view/view_options.h"
#include "tools/view/web_server.h"

namespace ahhs::view {

class ViewSession {
 public:
  // Opens the log, run or arena the options name; throws with a message for the user.
  ViewSession(ViewOptions* o, Json hormones);

  // What is shown, for the terminal.
  const std::string& what() const { return what_; }
  // What a page gets when it connects: the hello, the recordings or newest best, live snapshots.
  std::vector<std::string> Greeting();
  // A page's message: {"type": "select", "module": M} asks for module M's panel.
  void OnPageMessage(const std::string& text);
  // Feeds the pages until `stop`: a live arena at --rate, a run every --poll seconds; a log
  // needs nothing. Returns the exit code.
  int Serve(WebServer& server, const std::atomic<bool>& stop);

 private:
  const ViewOptions& o_;
  Json hello_;
  std::mutex greeting_mutex_;
  std::vector<std::string> fixed_;  // log: the recordings; run: the newest best
  std::unique_ptr<ahhs::bus::Bus> bus_;
  std::unique_ptr<LiveBridge> bridge_;
  std::unique_ptr<RunFollower> follower_;
  std::unique_ptr<ahhs::base::TempDir> scratch_;  // --run: where the best's episode is recorded
  std::string what_;
};

}  // namespace ahhs::view
