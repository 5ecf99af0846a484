// One module's hormone controller on the bus (docs/protocol.md): GENOME, TOPOLOGY, its own
// SENSORS and its docked neighbours' HORMONE packets in; HINGE, HORMONE packets and STATUS out.
// Lockstep: tick t is stepped once SENSORS(t) and every neighbour's packet of tick t-1 are in,
// or when the hormone timeout passes (a missing packet is lost hormone, counted). Real time
// (learnt from SIM/CLOCK): a tick is stepped as soon as its SENSORS arrive, adding every packet
// received since the last tick.
#pragma once

#include <ahhs/genome_t.hpp>
#include <ahhs/hinge_command_t.hpp>
#include <ahhs/hormone_packet_t.hpp>
#include <ahhs/module_sensors_t.hpp>
#include <ahhs/sim_clock_t.hpp>
#include <ahhs/topology_t.hpp>
#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bus/bus.h"
#include "bus/channels.h"
#include "bus/drop_log.h"
#include "bus/typed.h"
#include "modules/core/hormone_system.h"

namespace ahhs::modules {

struct ModuleNodeOptions {
  int id = 0;
  std::string arena = bus::kDefaultArena;
  // Wait for the neighbours' packets of t-1. Must be well below the sim's lockstep timeout
  // (default 2000 ms): a module that waits as long as the sim does answers too late after a
  // lost packet, the sim moves on, and the module keeps chasing ticks it cannot complete.
  // 0: exact lockstep, it waits for every packet (with a sim that waits for every command).
  std::chrono::milliseconds hormone_timeout{500};
  std::chrono::milliseconds heartbeat{1000};
};

struct ModuleNodeStats {
  std::uint64_t ticks = 0;
  std::uint64_t missing_packets = 0;   // neighbour packets not there when the tick was stepped
  std::uint64_t late_messages = 0;     // sensors or packets for ticks already stepped
  std::uint64_t dropped_messages = 0;  // undecodable, foreign episode, invalid
  std::string drops;                   // per channel and reason (bus::DropLog::Summary), "" if none
  std::string last_error;
};

class ModuleNode {
 public:
  ModuleNode(bus::Bus* bus, ModuleNodeOptions options);

  // Dispatches messages (waiting at most max_wait) and steps every tick that is ready.
  void Poll(std::chrono::microseconds max_wait);
  // Poll() without touching the bus: steps what the messages already dispatched allow. For a
  // caller that handles one shared bus for several nodes (the fused arena).
  void Process();

  bool ready() const { return controller_ != nullptr && have_topology_; }
  std::int64_t episode() const { return episode_; }
  std::int64_t next_tick() const { return next_tick_; }
  const CompartmentState* state() const { return state_ ? &*state_ : nullptr; }
  ModuleNodeStats stats() const;

 private:
  using Clock = std::chrono::steady_clock;
  void OnGenome(const genome_t& msg);
  void OnTopology(const topology_t& msg);
  void OnSensors(const module_sensors_t& msg);
  void OnHormone(const hormone_packet_t& msg);
  void NewEpisode(std::int64_t episode);
  bool TryStep(Clock::time_point now);
  void OnClock(const sim_clock_t& msg);
  void PublishStatus(std::int8_t state);
  void SyncHormoneSubscriptions();

  bus::Bus* bus_;
  ModuleNodeOptions options_;
  bus::ArenaChannels channels_;
  // Drops, and each channel's undecodable messages.
  void Drop(const char* channel, const char* reason);
  bus::DropLog drops_;
  bus::DecodeCounters genome_counters_, topology_counters_, sensors_counters_, clock_counters_,
      hormone_counters_;
  ModuleNodeStats stats_;

  std::int64_t episode_ = 0;
  bool realtime_ = false;
  std::unique_ptr<Controller> controller_;
  std::uint64_t genome_hash_ = 0;
  std::optional<CompartmentState> state_;
  bool have_topology_ = false;
  std::vector<int> neighbours_;                             // sorted ids
  std::map<int, bus::Subscription> hormone_subscriptions_;  // by neighbour id
  hormone_packet_t hormone_packet_;  // reused for publishing (no allocation per tick)
  hinge_command_t hinge_command_;    // likewise
  // This module's channels, built once (a name built per message costs an allocation).
  std::string hormone_channel_, hinge_channel_, status_channel_;
  bool announce_ready_ = false;  // READY goes out from Process(), after subscribing
  std::int64_t next_tick_ = 0;
  std::optional<module_sensors_t> sensors_;  // SENSORS(next_tick_) once it arrived
  Clock::time_point sensors_arrival_;
  // Packets by (tick, sender): only ticks next_tick_-1 and later are kept.
  std::map<std::pair<std::int64_t, int>, std::vector<double>> packets_;
  std::unique_ptr<bool[]> sensor_present_, actuator_present_;  // masks of the current tick
  Clock::time_point next_heartbeat_;
  std::int8_t status_ = 0;
  // Last: destroyed first, so no callback outlives the members it uses.
  std::vector<bus::Subscription> subscriptions_;
};

}  // namespace ahhs::modules
