#include "tools/view/live_bridge.h"

#include <algorithm>

#include "bus/channels.h"

namespace ahhs::view {

template <class Msg, class Store>
void LiveBridge::Listen(const std::string& channel, Store store) {
  // Every handler only stores the message, under the lock Drain() and Snapshot() take.
  subscriptions_.push_back(bus::SubscribeTyped<Msg>(
      bus_, channel,
      [this, store](const std::string&, const Msg& m) {
        std::lock_guard<std::mutex> lock(mutex_);
        store(m);
      },
      &counters_));
}

LiveBridge::LiveBridge(bus::Bus& bus, const std::string& arena) : bus_(bus), arena_(arena) {
  const bus::ArenaChannels ch(arena);
  Listen<sim_state_t>(ch.SimState(), [this](const sim_state_t& m) {
    if (scene_.valid && scene_.msg.episode != m.episode) scene_ = {};  // a new episode
    if (state_.valid && state_.msg.episode != m.episode) modules_.clear();
    state_.Set(m);
    ++states_;
  });
  Listen<sim_state_t>(ch.SimScene(), [this](const sim_state_t& m) { scene_.Set(m); });
  Listen<fitness_t>(ch.Fitness(), [this](const fitness_t& m) { fitness_.Set(m); });
  Listen<sim_clock_t>(ch.SimClock(), [this](const sim_clock_t& m) { clock_.Set(m); });
}

void LiveBridge::Want(int module) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (module >= 0 && module < 1000) wanted_.insert(module);
}

void LiveBridge::Maintain() {
  // A module's channels, by name, only once a page has asked for that module: the bus's kernel
  // filter then passes the states and nothing per module, so watching costs the arena's machine
  // two datagrams a tick (docs/performance.md).
  std::set<int> wanted;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    wanted = wanted_;
  }
  const bus::ArenaChannels ch(arena_);
  for (int i : wanted) {
    if (subscribed_.count(i)) continue;
    subscribed_.insert(i);
    Listen<module_sensors_t>(
        ch.Sensors(i), [this](const module_sensors_t& m) { modules_[m.module].sensors.Set(m); });
    Listen<hinge_command_t>(ch.Hinge(i),
                            [this](const hinge_command_t& m) { modules_[m.module].hinge.Set(m); });
    Listen<module_trace_t>(ch.Trace(i),
                           [this](const module_trace_t& m) { modules_[m.module].trace.Set(m); });
  }
}

Json LiveBridge::ModuleEvent(const ModuleNewest& m) {
  // The module's newest sensors, commands and trace, merged (each may be of its own tick).
  Json e;
  auto merge = [&e](const Json& part) {
    for (const auto& kv : part.items()) e[kv.key()] = kv.value();
  };
  if (m.sensors.valid) merge(SensorsEvent(m.sensors.msg));
  if (m.hinge.valid) merge(HingeEvent(m.hinge.msg));
  if (m.trace.valid) merge(TraceEvent(m.trace.msg));
  return e;
}

std::vector<std::string> LiveBridge::Drain() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<std::string> out;
  // Scene before state, state before the modules and fitness of its tick.
  if (clock_.fresh) out.push_back(ClockEvent(clock_.msg).dump());
  if (scene_.fresh) out.push_back(SceneEvent(scene_.msg).dump());
  if (state_.fresh) out.push_back(StateEvent(state_.msg).dump());
  clock_.fresh = scene_.fresh = state_.fresh = false;
  for (auto& [id, m] : modules_) {
    if (m.sensors.fresh || m.hinge.fresh || m.trace.fresh) out.push_back(ModuleEvent(m).dump());
    m.sensors.fresh = m.hinge.fresh = m.trace.fresh = false;
  }
  if (fitness_.fresh) out.push_back(FitnessEvent(fitness_.msg).dump());
  fitness_.fresh = false;
  return out;
}

std::vector<std::string> LiveBridge::Snapshot() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<std::string> out;
  if (clock_.valid) out.push_back(ClockEvent(clock_.msg).dump());
  if (scene_.valid) out.push_back(SceneEvent(scene_.msg).dump());
  if (state_.valid) out.push_back(StateEvent(state_.msg).dump());
  for (const auto& kv : modules_) out.push_back(ModuleEvent(kv.second).dump());
  if (fitness_.valid) out.push_back(FitnessEvent(fitness_.msg).dump());
  return out;
}

std::uint64_t LiveBridge::states_seen() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return states_;
}

std::uint64_t LiveBridge::undecodable() const { return counters_.dropped; }

}  // namespace ahhs::view
