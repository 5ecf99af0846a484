#include "tools/view/live_bridge.h"

#include <regex>

#include "bus/channels.h"
#include "bus/typed.h"

namespace ahhs::view {

namespace {

std::string Escaped(const std::string& arena) {
  return std::regex_replace(arena, std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)");
}

}  // namespace

LiveBridge::LiveBridge(bus::Bus& bus, const std::string& arena) : arena_(arena) {
  const bus::ArenaChannels ch(arena);
  const std::string a = Escaped(arena);
  subscriptions_.push_back(bus::SubscribeTyped<sim_state_t>(
      bus, a + "/SIM/(STATE|SCENE)",
      [this](const std::string& channel, const sim_state_t& m) {
        const bool scene =
            channel.size() >= 5 && channel.compare(channel.size() - 5, 5, "SCENE") == 0;
        if (!scene) {
          std::lock_guard<std::mutex> lock(mutex_);
          ++states_;
        }
        Store(scene ? "scene" : "state", scene ? SceneEvent(m) : StateEvent(m));
      },
      &counters_));
  subscriptions_.push_back(bus::SubscribeTyped<fitness_t>(
      bus, ch.Fitness(),
      [this](const std::string&, const fitness_t& m) { Store("fitness", FitnessEvent(m)); },
      &counters_));
  subscriptions_.push_back(bus::SubscribeTyped<sim_clock_t>(
      bus, ch.SimClock(),
      [this](const std::string&, const sim_clock_t& m) { Store("clock", ClockEvent(m)); },
      &counters_));
  auto module = [this](const Json& e) {
    std::lock_guard<std::mutex> lock(mutex_);
    const int id = e["module"].get<int>();
    Json& into = modules_[id];
    if (into.is_null() || into["tick"] != e["tick"]) into = e;  // a new tick: start afresh
    for (const auto& kv : e.items()) into[kv.key()] = kv.value();
    fresh_modules_[id] = true;
  };
  subscriptions_.push_back(bus::SubscribeTyped<module_sensors_t>(
      bus, a + "/MODULE[0-9]+/SENSORS",
      [module](const std::string&, const module_sensors_t& m) { module(SensorsEvent(m)); },
      &counters_));
  subscriptions_.push_back(bus::SubscribeTyped<hinge_command_t>(
      bus, a + "/MODULE[0-9]+/HINGE",
      [module](const std::string&, const hinge_command_t& m) { module(HingeEvent(m)); },
      &counters_));
  subscriptions_.push_back(bus::SubscribeTyped<module_trace_t>(
      bus, a + "/MODULE[0-9]+/TRACE",
      [module](const std::string&, const module_trace_t& m) { module(TraceEvent(m)); },
      &counters_));
}

void LiveBridge::Store(const char* kind, Json event) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (std::string(kind) == "state") {
    // A new episode: the old scene and modules are stale.
    auto it = newest_.find("scene");
    if (it != newest_.end() && it->second["episode"] != event["episode"]) newest_.erase(it);
  }
  newest_[kind] = std::move(event);
  fresh_[kind] = true;
}

std::vector<std::string> LiveBridge::Drain() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<std::string> out;
  // Scene before state, state before the modules and fitness of its tick.
  for (const char* kind : {"clock", "scene", "state"}) {
    if (fresh_[kind] && newest_.count(kind)) out.push_back(newest_[kind].dump());
    fresh_[kind] = false;
  }
  for (auto& kv : fresh_modules_) {
    if (kv.second) out.push_back(modules_[kv.first].dump());
    kv.second = false;
  }
  if (fresh_["fitness"] && newest_.count("fitness")) out.push_back(newest_["fitness"].dump());
  fresh_["fitness"] = false;
  return out;
}

std::vector<std::string> LiveBridge::Snapshot() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<std::string> out;
  for (const char* kind : {"clock", "scene", "state"}) {
    auto it = newest_.find(kind);
    if (it != newest_.end()) out.push_back(it->second.dump());
  }
  for (const auto& kv : modules_) out.push_back(kv.second.dump());
  auto it = newest_.find("fitness");
  if (it != newest_.end()) out.push_back(it->second.dump());
  return out;
}

std::uint64_t LiveBridge::states_seen() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return states_;
}

std::uint64_t LiveBridge::undecodable() const { return counters_.dropped; }

}  // namespace ahhs::view
