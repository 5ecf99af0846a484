#include "tools/conformance/module_player.h"

#include <ahhs/genome_t.hpp>
#include <ahhs/hinge_command_t.hpp>
#include <ahhs/hormone_packet_t.hpp>
#include <ahhs/module_sensors_t.hpp>
#include <ahhs/module_status_t.hpp>
#include <ahhs/sim_clock_t.hpp>
#include <ahhs/topology_t.hpp>
#include <algorithm>
#include <chrono>
#include <functional>

#include "bus/channels.h"
#include "bus/typed.h"
#include "modules/core/random.h"
#include "modules/core/variation.h"
#include "modules/node/genome_codec.h"
#include "sim/node/sim_codec.h"

namespace ahhs::conformance {

namespace {

using Clock = std::chrono::steady_clock;
constexpr int kSensors = 4, kActuators = 1;  // the gait's slots
constexpr double kPeriod = 0.05;

enum Segment : int { kPlain, kRepeat, kForeign, kLost, kAfterLost };

class ModulePlayer {
 public:
  ModulePlayer(bus::Bus& bus, const ModulePlayOptions& o)
      : bus_(bus), o_(o), ch_(o.arena), rng_(o.seed) {
    record_.id = o.id;
    neighbours_ = {o.id + 1, o.id + 2};
    subs_.push_back(bus::SubscribeTyped<hinge_command_t>(
        bus_, ch_.Hinge(o.id), [this](const std::string&, const hinge_command_t& m) {
          ModuleOutput h;
          h.episode = m.episode;
          h.tick = m.tick;
          h.module = m.module;
          h.arrival = Now();
          h.values = m.values;
          h.present.assign(m.present.begin(), m.present.end());
          h.target_angle = m.target_angle;
          record_.hinges.push_back(std::move(h));
        }));
    subs_.push_back(bus::SubscribeTyped<hormone_packet_t>(
        bus_, ch_.Hormone(o.id), [this](const std::string&, const hormone_packet_t& m) {
          ModuleOutput p;
          p.episode = m.episode;
          p.tick = m.tick;
          p.module = m.from_module;
          p.arrival = Now();
          p.values = m.amounts;
          p.to_modules.assign(m.to_modules.begin(), m.to_modules.end());
          record_.hormones.push_back(std::move(p));
        }));
    subs_.push_back(bus::SubscribeTyped<module_status_t>(
        bus_, ch_.Status(o.id), [this](const std::string&, const module_status_t& m) {
          record_.statuses.push_back({m.module, m.state, m.episode});
          if (current_ == nullptr || m.episode != current_->episode ||
              m.state != module_status_t::READY)
            return;
          if (current_->ready_at < 0) {
            current_->ready_at = Now();
            current_->ready_hash = m.genome_hash;
          } else if (current_->repeat_asked && Now() > repeat_sent_) {
            current_->repeat_answered = true;
          }
        }));
  }

  ModuleRecord Play() {
    const std::int64_t base = bus::NowUtime() % 1000000000 * 10 + 1;
    record_.foreign_episodes = {base + 1000};
    modules::Shape ahhs2{modules::Variant::kAhhs2, 5, 30, kSensors, kActuators};
    modules::Shape ahhs1{modules::Variant::kAhhs1, 5, 20, kSensors, kActuators};
    Episode(base, ahhs2, false, 0, 50,
            {"lockstep, AHHS2", "after a repeated GENOME and TOPOLOGY",
             "a foreign episode's SENSORS and HORMONE ignored", "a lost neighbour packet",
             "after the lost packet"});
    Episode(base + 1, ahhs1, false, 0, 30, {"a new episode (RESET): AHHS1, from rest"});
    Episode(base + 2, ahhs2, true, 100, 30, {"real time, joined at tick 100"});
    return std::move(record_);
  }

 private:
  double Now() const { return std::chrono::duration<double>(Clock::now() - t0_).count(); }
  void Wait(double seconds, const std::function<bool()>& done = nullptr) {
    const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(seconds));
    while (Clock::now() < end && !(done && done()))
      bus_.Handle(std::chrono::duration_cast<std::chrono::microseconds>(end - Clock::now()));
  }

  void Episode(std::int64_t episode, const modules::Shape& shape, bool realtime, int first,
               int ticks, std::vector<std::string> segments) {
    record_.episodes.emplace_back();
    PlayedEpisode& e = record_.episodes.back();
    current_ = &e;
    e.episode = episode;
    e.genome = modules::RandomGenome(shape, rng_);
    e.neighbours = neighbours_;
    e.segments = std::move(segments);
    const auto mode = realtime ? sim_clock_t::MODE_REALTIME : sim_clock_t::MODE_LOCKSTEP;

    // Handshake: RESET clock, TOPOLOGY and GENOME every 50 ms until READY (at most 5 s).
    for (int k = 0; k < 100 && e.ready_at < 0; ++k) {
      PublishClock(episode, 0, sim_clock_t::RESET, mode);
      PublishTopology(episode);
      PublishGenome(e);
      Wait(0.05, [&] { return e.ready_at >= 0; });
    }
    if (e.ready_at < 0) return;
    Wait(0.1);
    repeat_sent_ = Now();
    e.repeat_asked = true;
    PublishGenome(e);
    Wait(0.5, [&] { return e.repeat_answered; });

    int silent = 0;
    for (int t = first; t < first + ticks && silent < 3; ++t) {
      const int step = t - first;
      PlayedTick tick;
      tick.tick = t;
      if (e.segments.size() > 1)
        tick.segment = step < 20    ? kPlain
                       : step < 30  ? kRepeat
                       : step < 40  ? kForeign
                       : step == 40 ? kLost
                                    : kAfterLost;
      tick.lost_packet = tick.segment == kLost;
      for (int j = 0; j < kSensors; ++j) tick.sensors.push_back(rng_.Uniform());
      std::vector<std::pair<int, std::vector<double>>> sent;
      if (t > first || realtime)
        for (int n : neighbours_) {
          std::vector<double> amounts;
          for (int h = 0; h < e.genome.num_hormones(); ++h)
            amounts.push_back(rng_.Uniform(0, 0.05));
          sent.emplace_back(n, amounts);
        }
      // The module adds packets in increasing sender id; the kit sends them the other way round.
      std::reverse(sent.begin(), sent.end());
      if (tick.lost_packet) sent.erase(sent.begin());  // the highest id's packet is lost
      for (auto it = sent.rbegin(); it != sent.rend(); ++it) tick.packets.push_back(*it);

      if (realtime || step % 20 == 0) PublishClock(episode, t, sim_clock_t::RUNNING, mode);
      if (tick.segment == kRepeat && step == 20) {
        PublishGenome(e);
        PublishTopology(episode);
      }
      if (tick.segment == kForeign) {  // another episode's inputs first: to be ignored
        std::vector<double> noise(kSensors, 1.0);
        PublishSensors(record_.foreign_episodes[0], t, noise);
        for (const auto& [n, amounts] : sent)
          PublishPacket(record_.foreign_episodes[0], t - 1, n,
                        std::vector<double>(amounts.size(), 0.5));
      }
      if (realtime) {  // packets of t-1, then SENSORS(t): a real-time module steps on SENSORS
        for (const auto& [n, amounts] : sent) PublishPacket(episode, t - 1, n, amounts);
        Wait(0.001);
        PublishSensors(episode, t, tick.sensors);
      } else {  // SENSORS(t) first: a lockstep module must wait for the packets of t-1
        PublishSensors(episode, t, tick.sensors);
        Wait(0.002);
        for (const auto& [n, amounts] : sent) PublishPacket(episode, t - 1, n, amounts);
      }
      tick.last_input = Now();
      e.ticks.push_back(tick);
      const auto answered = [&] {
        bool hinge = false, hormone = false;
        for (auto it = record_.hinges.rbegin(); it != record_.hinges.rend() && !hinge; ++it)
          hinge = it->episode == episode && it->tick == t;
        for (auto it = record_.hormones.rbegin(); it != record_.hormones.rend() && !hormone; ++it)
          hormone = it->episode == episode && it->tick == t;
        return hinge && hormone;
      };
      Wait(tick.lost_packet ? 3.0 : realtime ? kPeriod : 1.0, answered);
      silent = answered() ? 0 : silent + 1;
      if (realtime) Wait(std::max(0.0, tick.last_input + kPeriod - Now()));
    }
    Wait(0.05);  // a late answer still counts as seen
    for (int k = 0; k < 3; ++k) PublishClock(episode, first + ticks, sim_clock_t::FINISHED, mode);
    current_ = nullptr;
  }

  void PublishClock(std::int64_t episode, std::int64_t tick, std::int8_t state, std::int8_t mode) {
    auto c = sim::ClockMessage(episode, tick, kPeriod, mode == sim_clock_t::MODE_REALTIME, state);
    c.utime = bus::NowUtime();
    bus::PublishTyped(bus_, ch_.SimClock(), c);
  }
  void PublishTopology(std::int64_t episode) {
    topology_t m{};
    m.utime = bus::NowUtime();
    m.episode = episode;
    m.num_modules = o_.id + 3;
    m.ports_per_module = 4;
    m.num_links = 2;
    m.module_a = {o_.id, o_.id + 2};
    m.port_a = {2, 2};
    m.module_b = {o_.id + 1, o_.id};
    m.port_b = {0, 0};
    bus::PublishTyped(bus_, ch_.Topology(), m);
  }
  void PublishGenome(const PlayedEpisode& e) {
    auto m = modules::GenomeMessage(e.genome, e.episode);
    m.utime = bus::NowUtime();
    bus::PublishTyped(bus_, ch_.Genome(), m);
  }
  void PublishSensors(std::int64_t episode, std::int64_t tick, const std::vector<double>& values) {
    module_sensors_t m{};
    m.utime = bus::NowUtime();
    m.episode = episode;
    m.tick = tick;
    m.module = o_.id;
    m.sim_time = static_cast<double>(tick) * kPeriod;
    m.num_sensors = kSensors;
    m.values = values;
    m.present.assign(kSensors, true);
    m.num_actuators = kActuators;
    m.actuator_present.assign(kActuators, true);
    bus::PublishTyped(bus_, ch_.Sensors(o_.id), m);
  }
  void PublishPacket(std::int64_t episode, std::int64_t tick, int from,
                     const std::vector<double>& amounts) {
    hormone_packet_t m{};
    m.utime = bus::NowUtime();
    m.episode = episode;
    m.tick = tick;
    m.from_module = from;
    m.num_receivers = 1;
    m.to_modules = {o_.id};
    m.num_hormones = static_cast<std::int16_t>(amounts.size());
    m.amounts = amounts;
    bus::PublishTyped(bus_, ch_.Hormone(from), m);
  }

  bus::Bus& bus_;
  ModulePlayOptions o_;
  bus::ArenaChannels ch_;
  modules::Rng rng_;
  std::vector<int> neighbours_;
  ModuleRecord record_;
  PlayedEpisode* current_ = nullptr;
  double repeat_sent_ = 0;
  Clock::time_point t0_ = Clock::now();
  std::vector<bus::Subscription> subs_;  // last: gone before the members they write
};

}  // namespace

std::vector<Check> PlayModule(bus::Bus& bus, const ModulePlayOptions& options,
                              const Budget& budget) {
  ModulePlayer player(bus, options);
  const ModuleRecord record = player.Play();
  return JudgeModule(record, budget, options.lost_packet_limit);
}

}  // namespace ahhs::conformance
