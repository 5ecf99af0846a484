// The live side of ahhs-view: listens to one arena on a bus (never publishes: a viewer takes no
// part in the lockstep, so it can neither stall nor change an episode) and turns its messages
// into view events. Handlers only store the newest of each kind; Drain() hands out what changed,
// so a lockstep arena running 100x real time is shown at the page's rate, not queued.
#pragma once

#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "bus/bus.h"
#include "bus/typed.h"
#include "tools/view/view_events.h"

namespace ahhs::view {

class LiveBridge {
 public:
  LiveBridge(bus::Bus& bus, const std::string& arena);

  // Events since the last Drain (the newest of each kind, each module's newest merged).
  std::vector<std::string> Drain();
  // What a page that connects now needs: the scene, the newest state, fitness and clock.
  std::vector<std::string> Snapshot() const;
  std::uint64_t states_seen() const;
  std::uint64_t undecodable() const;

 private:
  void Store(const char* kind, Json event);
  std::string arena_;
  mutable std::mutex mutex_;
  std::map<std::string, Json> newest_;  // kind -> event (scene, state, fitness, clock)
  std::map<int, Json> modules_;         // module -> merged module event
  std::map<std::string, bool> fresh_;   // kind -> changed since the last Drain
  std::map<int, bool> fresh_modules_;
  std::uint64_t states_ = 0;
  bus::DecodeCounters counters_;
  std::vector<bus::Subscription> subscriptions_;
};

}  // namespace ahhs::view
