// The live side of ahhs-view: listens to one arena on a bus (never publishes: a viewer takes no
// part in the lockstep, so it can neither stall nor change an episode) and turns its messages
// into view events. Handlers only keep the newest message of each kind (decoded, not yet
// translated); Drain() translates what changed, so a lockstep arena running 100x real time is
// shown at the page's rate and costs the viewer one decode per message, not one event.
#pragma once

#include <ahhs/fitness_t.hpp>
#include <ahhs/hinge_command_t.hpp>
#include <ahhs/module_sensors_t.hpp>
#include <ahhs/module_trace_t.hpp>
#include <ahhs/sim_clock_t.hpp>
#include <ahhs/sim_state_t.hpp>
#include <cstdint>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "bus/bus.h"
#include "bus/typed.h"
#include "tools/view/view_events.h"

namespace ahhs::view {

class LiveBridge {
 public:
  LiveBridge(bus::Bus& bus, const std::string& arena);

  // A page wants module `module`'s sensors, commands and trace (its panel is open). Any thread.
  void Want(int module);
  // Call between Handle()s of the bus: subscribes to the modules wanted.
  void Maintain();
  // Events since the last Drain (the newest of each kind, each module's newest merged).
  std::vector<std::string> Drain();
  // What a page that connects now needs: the scene, the newest state, fitness and clock.
  std::vector<std::string> Snapshot() const;
  std::uint64_t states_seen() const;
  std::uint64_t undecodable() const;

 private:
  // The newest message of each kind, and whether Drain has sent it.
  template <class Msg>
  struct Newest {
    Msg msg{};
    bool valid = false, fresh = false;
    void Set(const Msg& m) {
      msg = m;
      valid = fresh = true;
    }
  };
  struct ModuleNewest {
    Newest<module_sensors_t> sensors;
    Newest<hinge_command_t> hinge;
    Newest<module_trace_t> trace;
  };
  static Json ModuleEvent(const ModuleNewest& m);
  // Subscribes `store(const Msg&)` to `channel`, called with the lock held.
  template <class Msg, class Store>
  void Listen(const std::string& channel, Store store);
  bus::Bus& bus_;
  std::string arena_;
  std::set<int> wanted_, subscribed_;
  mutable std::mutex mutex_;
  Newest<sim_state_t> state_, scene_;
  Newest<fitness_t> fitness_;
  Newest<sim_clock_t> clock_;
  std::map<int, ModuleNewest> modules_;
  std::uint64_t states_ = 0;
  bus::DecodeCounters counters_;
  std::vector<bus::Subscription> subscriptions_;
};

}  // namespace ahhs::view
