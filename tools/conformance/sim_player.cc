#include "tools/conformance/sim_player.h"

#include <ahhs/module_sensors_t.hpp>
#include <ahhs/sim_clock_t.hpp>
#include <ahhs/sim_control_t.hpp>
#include <ahhs/topology_t.hpp>
#include <chrono>
#include <functional>

#include "bus/channels.h"
#include "bus/typed.h"

namespace ahhs::conformance {

namespace {

using Clock = std::chrono::steady_clock;

class SimPlayer {
 public:
  SimPlayer(bus::Bus& bus, const SimPlayOptions& o) : bus_(bus), ch_(o.arena) {
    SimPlayed& p = record_.played;
    const std::int64_t base = bus::NowUtime() % 1000000000 * 10 + 1;
    p.full = base;
    p.stopped = base + 1;
    p.bad = base + 2;
    p.foreign = base + 1000;
    subs_.push_back(bus::SubscribeTyped<sim_clock_t>(
        bus_, ch_.SimClock(), [this](const std::string&, const sim_clock_t& m) {
          record_.clocks.push_back(
              {m.episode, m.tick, m.run_state, m.clock_mode, m.sim_time, m.control_period, Now()});
        }));
    subs_.push_back(bus::SubscribeTyped<topology_t>(
        bus_, ch_.Topology(), [this](const std::string&, const topology_t& m) {
          const int n = record_.played.modules;
          bool chain = m.num_modules == n && m.num_links == n - 1;
          for (int k = 0; chain && k < m.num_links; ++k) {
            const auto i = static_cast<std::size_t>(k);
            chain = m.module_a[i] == k && m.module_b[i] == k + 1 && m.port_a[i] == 2 &&
                    m.port_b[i] == 0;
          }
          record_.topologies.push_back({m.episode, Now(), chain});
        }));
    for (int k = 0; k < p.modules; ++k)
      subs_.push_back(bus::SubscribeTyped<module_sensors_t>(
          bus_, ch_.Sensors(k), [this](const std::string&, const module_sensors_t& m) {
            record_.sensors.push_back({m.episode, m.tick, m.module});
          }));
  }

  SimRecord Play() {
    SimPlayed& p = record_.played;
    // The full episode, with another episode's PAUSE and STOP at tick 10.
    if (Handshake(p.full, &p.full_reset_sent) && Start(p.full)) {
      WaitFor([&] { return Ran(p.full, 10); }, 2.0);
      p.foreign_sent = Now();
      Control(sim_control_t::PAUSE, p.foreign);
      Control(sim_control_t::STOP, p.foreign);
      WaitFor([&] { return Ended(p.full); }, p.ticks * p.period + 2.0);
    }
    // An episode stopped at tick 10.
    if (Handshake(p.stopped, &p.stopped_reset_sent) && Start(p.stopped)) {
      WaitFor([&] { return Ran(p.stopped, 10); }, 2.0);
      p.stop_sent = Now();
      Control(sim_control_t::STOP, p.stopped);
      WaitFor([&] { return Ended(p.stopped); }, 1.0);
    }
    // A RESET of an unknown scenario: nothing may answer it.
    for (int k = 0; k < 5; ++k) {
      Reset(p.bad, "juggling");
      Wait(0.1);
    }
    Wait(0.2);
    return std::move(record_);
  }

 private:
  double Now() const { return std::chrono::duration<double>(Clock::now() - t0_).count(); }
  void Wait(double seconds) { WaitFor(nullptr, seconds); }
  void WaitFor(const std::function<bool()>& done, double seconds) {
    const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(seconds));
    while (Clock::now() < end && !(done && done()))
      bus_.Handle(std::chrono::duration_cast<std::chrono::microseconds>(end - Clock::now()));
  }
  bool Seen(std::int64_t episode, std::int8_t state, std::int64_t from_tick = 0) const {
    for (const ClockSeen& c : record_.clocks)
      if (c.episode == episode && c.state == state && c.tick >= from_tick) return true;
    return false;
  }
  bool Ran(std::int64_t episode, std::int64_t tick) const {
    return Seen(episode, sim_clock_t::RUNNING, tick) || Ended(episode);
  }
  bool Ended(std::int64_t episode) const {
    return Seen(episode, sim_clock_t::FINISHED) || Seen(episode, sim_clock_t::FAILED);
  }

  // RESET every 50 ms (and the operator's CONFIRM every 0.5 s) until the clock shows RESET.
  bool Handshake(std::int64_t episode, double* first_sent) {
    *first_sent = Now();
    for (int k = 0; k < 200; ++k) {
      if (k % 10 == 0) Control(sim_control_t::CONFIRM, 0);
      Reset(episode, "gait");
      WaitFor([&] { return Seen(episode, sim_clock_t::RESET); }, 0.05);
      if (Seen(episode, sim_clock_t::RESET)) return true;
    }
    return false;
  }
  bool Start(std::int64_t episode) {
    for (int k = 0; k < 20; ++k) {
      Control(sim_control_t::START, episode);
      WaitFor([&] { return Ran(episode, 0); }, 0.1);
      if (Ran(episode, 0)) return true;
    }
    return false;
  }
  void Reset(std::int64_t episode, const std::string& scenario) {
    sim_control_t c{};
    c.utime = bus::NowUtime();
    c.command = sim_control_t::RESET;
    c.episode = episode;
    c.seed = 1;
    c.scenario = scenario;
    c.num_modules = record_.played.modules;
    c.joints = sim_control_t::JOINTS_FIXED;
    c.duration = record_.played.ticks * record_.played.period;
    c.clock_mode = sim_control_t::MODE_REALTIME;
    bus::PublishTyped(bus_, ch_.SimControl(), c);
  }
  void Control(std::int8_t command, std::int64_t episode) {
    sim_control_t c{};
    c.utime = bus::NowUtime();
    c.command = command;
    c.episode = episode;
    c.scenario = "";
    bus::PublishTyped(bus_, ch_.SimControl(), c);
  }

  bus::Bus& bus_;
  bus::ArenaChannels ch_;
  SimRecord record_;
  Clock::time_point t0_ = Clock::now();
  std::vector<bus::Subscription> subs_;  // last: gone before the record they write
};

}  // namespace

std::vector<Check> PlaySim(bus::Bus& bus, const SimPlayOptions& options, const Budget& budget) {
  SimPlayer player(bus, options);
  return JudgeSim(player.Play(), budget);
}

}  // namespace ahhs::conformance
