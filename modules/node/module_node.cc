#include "modules/node/module_node.h"

#include <ahhs/hinge_command_t.hpp>
#include <ahhs/module_status_t.hpp>
#include <algorithm>
#include <cmath>

#include "bus/wire_text.h"
#include "modules/node/genome_codec.h"

namespace ahhs::modules {

ModuleNode::ModuleNode(bus::Bus* bus, ModuleNodeOptions options)
    : bus_(bus),
      options_(std::move(options)),
      channels_(options_.arena),
      hormone_channel_(channels_.Hormone(options_.id)),
      hinge_channel_(channels_.Hinge(options_.id)),
      status_channel_(channels_.Status(options_.id)) {
  subscriptions_.push_back(bus::SubscribeTyped<genome_t>(
      *bus_, channels_.Genome(), [this](const std::string&, const genome_t& m) { OnGenome(m); },
      &genome_counters_));
  subscriptions_.push_back(bus::SubscribeTyped<topology_t>(
      *bus_, channels_.Topology(),
      [this](const std::string&, const topology_t& m) { OnTopology(m); }, &topology_counters_));
  subscriptions_.push_back(bus::SubscribeTyped<module_sensors_t>(
      *bus_, channels_.Sensors(options_.id),
      [this](const std::string&, const module_sensors_t& m) { OnSensors(m); }, &sensors_counters_));
  subscriptions_.push_back(bus::SubscribeTyped<sim_clock_t>(
      *bus_, channels_.SimClock(), [this](const std::string&, const sim_clock_t& m) { OnClock(m); },
      &clock_counters_));
  next_heartbeat_ = Clock::now();
}

void ModuleNode::OnClock(const sim_clock_t& m) {
  if (m.episode == episode_) realtime_ = m.clock_mode == sim_clock_t::MODE_REALTIME;
}

ModuleNodeStats ModuleNode::stats() const {
  ModuleNodeStats s = stats_;
  bus::DropLog all = drops_;
  for (const auto& [channel, counters] :
       {std::pair<const char*, const bus::DecodeCounters*>{"GENOME", &genome_counters_},
        {"TOPOLOGY", &topology_counters_},
        {"SENSORS", &sensors_counters_},
        {"SIM/CLOCK", &clock_counters_},
        {"HORMONE", &hormone_counters_}}) {
    s.dropped_messages += counters->dropped;
    all.CountUndecodable(channel, *counters);
  }
  s.drops = all.Summary();
  return s;
}

void ModuleNode::Drop(const char* channel, const char* reason) {
  ++stats_.dropped_messages;
  drops_.Count(channel, reason);
}

void ModuleNode::NewEpisode(std::int64_t episode) {
  episode_ = episode;
  controller_.reset();
  state_.reset();
  have_topology_ = false;
  neighbours_.clear();
  next_tick_ = 0;
  sensors_.reset();
  packets_.clear();
}

void ModuleNode::OnGenome(const genome_t& m) {
  if (m.episode != episode_) {
    NewEpisode(m.episode);
  } else if (controller_) {
    // A repeat: the launcher sends GENOME until every module is READY, and in real time every
    // second for late joiners; datagrams from two senders can also overtake each other, so a
    // repeat may arrive after the episode started. Rebuilding the controller would wipe its
    // hormones mid-episode: keep it, and only answer READY again before the first tick.
    if (static_cast<std::uint64_t>(m.genome_hash) != genome_hash_) {
      Drop("GENOME", "another genome for the running episode");
      stats_.last_error = "a second, different genome for this episode was ignored";
    } else if (ready() && next_tick_ == 0) {
      announce_ready_ = true;
    }
    return;
  }
  Genome g;
  const std::string error = GenomeFromMessage(m, &g);
  if (!error.empty()) {
    Drop("GENOME", "invalid");
    stats_.last_error = "genome refused: " + error;
    PublishStatus(module_status_t::ERROR);
    return;
  }
  controller_ = std::make_unique<Controller>(std::move(g));
  genome_hash_ = static_cast<std::uint64_t>(m.genome_hash);
  state_ = MakeState(*controller_);
  sensor_present_ = std::make_unique<bool[]>(static_cast<std::size_t>(controller_->num_sensors()));
  actuator_present_ =
      std::make_unique<bool[]>(static_cast<std::size_t>(controller_->num_actuators()));
  if (ready()) announce_ready_ = true;
}

void ModuleNode::OnTopology(const topology_t& m) {
  if (m.episode != episode_) NewEpisode(m.episode);
  neighbours_.clear();
  for (int k = 0; k < m.num_links; ++k) {
    const auto i = static_cast<std::size_t>(k);
    if (m.module_a[i] == options_.id) neighbours_.push_back(m.module_b[i]);
    if (m.module_b[i] == options_.id) neighbours_.push_back(m.module_a[i]);
  }
  std::sort(neighbours_.begin(), neighbours_.end());
  neighbours_.erase(std::unique(neighbours_.begin(), neighbours_.end()), neighbours_.end());
  if (static_cast<int>(neighbours_.size()) > kDefaultPorts) neighbours_.resize(kDefaultPorts);
  have_topology_ = true;
  // READY answers the handshake; the sim repeats TOPOLOGY during a real-time episode, which
  // must not make a running module report READY again.
  if (ready() && next_tick_ == 0) announce_ready_ = true;
}

void ModuleNode::OnSensors(const module_sensors_t& m) {
  if (m.episode != episode_ || m.module != options_.id || !ready()) {
    Drop("SENSORS", m.episode != episode_     ? "another episode"
                    : m.module != options_.id ? "another module's"
                                              : "before GENOME and TOPOLOGY");
    return;
  }
  if (m.num_sensors != controller_->num_sensors() ||
      m.num_actuators != controller_->num_actuators()) {
    Drop("SENSORS", "shape differs from the genome's");
    stats_.last_error = "sensor/actuator shape does not match the genome";
    return;
  }
  for (std::size_t j = 0; j < m.values.size(); ++j) {
    if (m.present[j] && (!std::isfinite(m.values[j]) || m.values[j] < 0 || m.values[j] > 1)) {
      Drop("SENSORS", "NaN or out of [0, 1]");
      return;
    }
  }
  if (m.tick < next_tick_) {
    ++stats_.late_messages;
    return;
  }
  if (m.tick > next_tick_) {
    // The sim went on without us (we missed a tick): jump to its tick.
    stats_.late_messages += static_cast<std::uint64_t>(m.tick - next_tick_);
    next_tick_ = m.tick;
  }
  sensors_ = m;
  sensors_arrival_ = Clock::now();
}

void ModuleNode::OnHormone(const hormone_packet_t& m) {
  if (m.episode != episode_ || !ready() || m.num_hormones != controller_->num_hormones() ||
      !std::binary_search(neighbours_.begin(), neighbours_.end(), m.from_module)) {
    Drop("HORMONE", m.episode != episode_                           ? "another episode"
                    : !ready()                                      ? "before GENOME and TOPOLOGY"
                    : m.num_hormones != controller_->num_hormones() ? "wrong number of hormones"
                                                                    : "not a docked neighbour");
    return;
  }
  for (double a : m.amounts) {
    if (!std::isfinite(a) || a < 0 || a > 1) {
      Drop("HORMONE", "NaN or out of [0, 1]");
      return;
    }
  }
  if (m.tick < next_tick_ - 1 && !realtime_) {
    ++stats_.late_messages;
    return;
  }
  packets_[{m.tick, m.from_module}] = m.amounts;
}

bool ModuleNode::TryStep(Clock::time_point now) {
  if (!ready() || !sensors_ || sensors_->tick != next_tick_) return false;
  const std::int64_t t = next_tick_;
  int have = 0;
  if (t > 0)
    for (int n : neighbours_) have += packets_.count({t - 1, n}) ? 1 : 0;
  const bool all_in = t == 0 || have == static_cast<int>(neighbours_.size());
  const bool exact = options_.hormone_timeout.count() == 0;
  if (!realtime_ && !all_in && (exact || now < sensors_arrival_ + options_.hormone_timeout))
    return false;

  // 1. Received hormone, in increasing sender id.
  if (realtime_) {  // every packet not yet added, oldest tick first
    for (auto it = packets_.begin(); it != packets_.end() && it->first.first < t;) {
      ReceiveHormones(it->second.data(), &*state_);
      it = packets_.erase(it);
    }
  } else if (t > 0) {
    for (int n : neighbours_) {
      auto it = packets_.find({t - 1, n});
      if (it == packets_.end()) {
        ++stats_.missing_packets;
        continue;
      }
      ReceiveHormones(it->second.data(), &*state_);
    }
  }
  // 2-6. Step on this tick's sensors.
  for (int j = 0; j < controller_->num_sensors(); ++j)
    sensor_present_[j] = sensors_->present[static_cast<std::size_t>(j)];
  for (int a = 0; a < controller_->num_actuators(); ++a)
    actuator_present_[a] = sensors_->actuator_present[static_cast<std::size_t>(a)];
  TickInput in;
  in.sensors = sensors_->values.data();
  in.sensor_present = sensor_present_.get();
  in.actuator_present = actuator_present_.get();
  in.num_neighbours = static_cast<int>(neighbours_.size());
  Step(*controller_, in, &*state_);

  const std::int64_t utime = bus::NowUtime();
  if (!neighbours_.empty()) {  // one packet for all neighbours: each gets the same outflow
    hormone_packet_.utime = utime;
    hormone_packet_.episode = episode_;
    hormone_packet_.tick = t;
    hormone_packet_.from_module = options_.id;
    hormone_packet_.num_receivers = static_cast<std::int16_t>(neighbours_.size());
    hormone_packet_.to_modules.assign(neighbours_.begin(), neighbours_.end());
    hormone_packet_.num_hormones = static_cast<std::int16_t>(controller_->num_hormones());
    hormone_packet_.amounts.assign(state_->outflow.begin(), state_->outflow.end());
    bus::PublishTyped(*bus_, hormone_channel_, hormone_packet_);
  }
  hinge_command_t& h = hinge_command_;
  h.utime = utime;
  h.episode = episode_;
  h.tick = t;
  h.module = options_.id;
  h.num_actuators = static_cast<std::int16_t>(controller_->num_actuators());
  h.values.assign(state_->actuators.data(), state_->actuators.data() + state_->actuators.size());
  h.present.assign(sensors_->actuator_present.begin(), sensors_->actuator_present.end());
  h.target_angle = M_PI / 2 * h.values[0];
  bus::PublishTyped(*bus_, hinge_channel_, h);

  ++stats_.ticks;
  ++next_tick_;
  if (!realtime_)
    packets_.erase(packets_.begin(), packets_.lower_bound({t, -1}));  // keep tick t onwards
  if (status_ != module_status_t::RUNNING) PublishStatus(module_status_t::RUNNING);
  return true;
}

void ModuleNode::Poll(std::chrono::microseconds max_wait) {
  auto wait = max_wait;
  if (sensors_ && sensors_->tick == next_tick_ && options_.hormone_timeout.count() > 0) {
    const auto left = std::chrono::duration_cast<std::chrono::microseconds>(
        sensors_arrival_ + options_.hormone_timeout - Clock::now());
    wait = std::clamp(left, std::chrono::microseconds(0), max_wait);
  }
  bus_->Handle(wait);
  Process();
}

void ModuleNode::SyncHormoneSubscriptions() {
  // Only the docked neighbours' HORMONE channels: in one process (memq) every subscription sees
  // every packet, and decoding all of them cost more than the controllers. Done here, outside
  // any bus callback, because TOPOLOGY arrives in one.
  for (auto it = hormone_subscriptions_.begin(); it != hormone_subscriptions_.end();) {
    if (std::binary_search(neighbours_.begin(), neighbours_.end(), it->first)) {
      ++it;
    } else {
      it = hormone_subscriptions_.erase(it);  // unsubscribes
    }
  }
  for (int n : neighbours_) {
    if (hormone_subscriptions_.count(n)) continue;
    hormone_subscriptions_[n] = bus::SubscribeTyped<hormone_packet_t>(
        *bus_, channels_.Hormone(n),
        [this, n](const std::string&, const hormone_packet_t& m) {
          if (m.from_module != n) {
            Drop("HORMONE", "a module speaking for another");
            return;
          }
          if (std::find(m.to_modules.begin(), m.to_modules.end(), options_.id) !=
              m.to_modules.end())
            OnHormone(m);
        },
        &hormone_counters_);
  }
}

void ModuleNode::Process() {
  // Listen to the neighbours before telling anyone we are ready: the first packets follow the
  // START that our READY allows.
  SyncHormoneSubscriptions();
  if (announce_ready_) {
    announce_ready_ = false;
    if (ready()) PublishStatus(module_status_t::READY);
  }
  while (TryStep(Clock::now())) {
  }
  if (Clock::now() >= next_heartbeat_) PublishStatus(status_);
}

void ModuleNode::PublishStatus(std::int8_t state) {
  status_ = state;
  module_status_t s{};
  s.utime = bus::NowUtime();
  s.episode = episode_;
  s.tick = next_tick_ - 1;
  s.module = options_.id;
  s.state = state;
  s.genome_hash = static_cast<std::int64_t>(genome_hash_);
  const auto st = stats();
  s.missed_ticks = static_cast<std::int32_t>(st.missing_packets);
  s.late_messages = static_cast<std::int32_t>(st.late_messages);
  s.dropped_messages = static_cast<std::int32_t>(st.dropped_messages);
  // The error, and what was dropped (per channel and reason), for whoever watches STATUS.
  std::string message = st.last_error;
  if (!st.drops.empty()) message += (message.empty() ? "dropped: " : "; dropped: ") + st.drops;
  s.message = bus::ToWireText(message);
  bus::PublishTyped(*bus_, status_channel_, s);
  next_heartbeat_ = Clock::now() + options_.heartbeat;
}

}  // namespace ahhs::modules
