#include "tools/conformance/player.h"

#include <ahhs/hinge_command_t.hpp>
#include <ahhs/module_sensors_t.hpp>
#include <ahhs/sim_clock_t.hpp>
#include <ahhs/sim_state_t.hpp>
#include <chrono>
#include <cmath>
#include <functional>

#include "bus/channels.h"
#include "bus/typed.h"
#include "sim/node/sim_codec.h"

namespace ahhs::conformance {

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kHalfPi = 1.5707963267948966;

class Player {
 public:
  Player(bus::Bus& bus, const PlayOptions& o) : bus_(bus), o_(o), ch_(o.arena) {
    clock_.period = o.period;
    clock_.ticks = o.ticks;
    clock_.episode = bus::NowUtime() % 1000000000 * 10 + 1;
    clock_.late_episode = clock_.episode + 1;
    clock_.late_from = 100;
  }
  double Now() const { return std::chrono::duration<double>(Clock::now() - t0_).count(); }

  // RESET for a while (nothing may come), the ticks of phase 1, the end, then phase 2 joined at
  // tick late_from. `on_tick(episode, tick)` runs after each RUNNING clock.
  void Play(const std::function<void(std::int64_t, std::int64_t)>& on_tick) {
    for (int k = 0; k < 6; ++k) {
      Publish(clock_.episode, 0, sim_clock_t::RESET);
      Wait(0.05);
    }
    clock_.started = Now();
    for (int t = 0; t < o_.ticks; ++t) Tick(clock_.episode, t, on_tick);
    for (int k = 0; k < 3; ++k) Publish(clock_.episode, o_.ticks, sim_clock_t::FINISHED);
    Wait(0.2);
    for (int t = clock_.late_from; t < clock_.late_from + o_.ticks / 2; ++t)
      Tick(clock_.late_episode, t, on_tick);
    for (int k = 0; k < 3; ++k)
      Publish(clock_.late_episode, clock_.late_from + o_.ticks / 2, sim_clock_t::FINISHED);
    Wait(0.2);
  }
  const PlayedClock& clock() const { return clock_; }
  bus::Bus& bus() { return bus_; }
  const bus::ArenaChannels& channels() const { return ch_; }

 private:
  void Tick(std::int64_t episode, std::int64_t tick,
            const std::function<void(std::int64_t, std::int64_t)>& on_tick) {
    clock_.sent.emplace_back(PlayedClock::Key(episode, tick), Now());
    Publish(episode, tick, sim_clock_t::RUNNING);
    on_tick(episode, tick);
    Wait(o_.period);
  }
  void Publish(std::int64_t episode, std::int64_t tick, std::int8_t state) {
    auto c = sim::ClockMessage(episode, tick, o_.period, true, state);
    c.utime = bus::NowUtime();
    bus::PublishTyped(bus_, ch_.SimClock(), c);
  }
  void Wait(double seconds) {
    const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(seconds));
    while (Clock::now() < end)
      bus_.Handle(std::chrono::duration_cast<std::chrono::microseconds>(end - Clock::now()));
  }

  bus::Bus& bus_;
  PlayOptions o_;
  bus::ArenaChannels ch_;
  PlayedClock clock_;
  Clock::time_point t0_ = Clock::now();
};

std::string SensorsProblem(const module_sensors_t& m) {
  if (m.num_sensors != 4 || m.values.size() != 4 || m.present.size() != 4)
    return "num_sensors " + std::to_string(m.num_sensors) + " (the gait has 4)";
  for (double v : m.values)
    if (!std::isfinite(v) || v < 0 || v > 1) return "a value outside [0, 1]";
  if (m.num_actuators != 1 || m.actuator_present.size() != 1)
    return "num_actuators " + std::to_string(m.num_actuators) + " (the gait has 1)";
  if (!std::isfinite(m.hinge_angle) || std::abs(m.hinge_angle) > kHalfPi + 0.05)
    return "hinge_angle outside +-pi/2";
  if (!std::isfinite(m.sim_time)) return "sim_time not finite";
  return "";
}

std::string StateProblem(const sim_state_t& m, int modules) {
  std::vector<bool> seen(static_cast<std::size_t>(modules), false);
  for (int k = 0; k < m.num_bodies; ++k) {
    const auto i = static_cast<std::size_t>(k);
    const double q = m.qw[i] * m.qw[i] + m.qx[i] * m.qx[i] + m.qy[i] * m.qy[i] + m.qz[i] * m.qz[i];
    if (!std::isfinite(m.px[i]) || !std::isfinite(m.py[i]) || !std::isfinite(m.pz[i]) ||
        !(std::abs(q - 1) < 1e-3))
      return "body " + std::to_string(k) + ": a pose that is not finite or not a unit quaternion";
    if (m.module[i] >= 0 && m.module[i] < modules && m.mass[i] > 0)
      seen[static_cast<std::size_t>(m.module[i])] = true;
  }
  for (int k = 0; k < modules; ++k)
    if (!seen[static_cast<std::size_t>(k)])
      return "no moving body (mass > 0) of module " + std::to_string(k);
  if (!std::isfinite(m.sim_time)) return "sim_time not finite";
  return "";
}

}  // namespace

std::vector<Check> PlayFirmware(bus::Bus& bus, const PlayOptions& options, const Budget& budget) {
  Player player(bus, options);
  std::vector<Observed> seen;
  auto sub = bus::SubscribeTyped<module_sensors_t>(
      bus, player.channels().Sensors(options.id),
      [&](const std::string&, const module_sensors_t& m) {
        seen.push_back(
            {m.episode, m.tick, m.module, player.Now(), SensorsProblem(m), m.hinge_angle});
      });
  auto hinge = [&](std::int64_t episode, std::int64_t tick, double target) {
    hinge_command_t h{};
    h.utime = bus::NowUtime();
    h.episode = episode;
    h.tick = tick;
    h.module = options.id;
    h.num_actuators = 1;
    h.values = {target / kHalfPi};
    h.present = {true};
    h.target_angle = target;
    bus::PublishTyped(bus, player.channels().Hinge(options.id), h);
  };
  player.Play([&](std::int64_t episode, std::int64_t tick) {
    const std::int64_t first = episode == player.clock().episode ? 0 : player.clock().late_from;
    const bool second_half = tick - first >= options.ticks / 4;
    hinge(episode, tick, second_half ? options.commanded : 0.0);
    if (second_half) hinge(episode + 1000, tick, options.foreign_target);  // must be ignored
  });
  return JudgeFirmware(player.clock(), seen, options.id, options.commanded, options.foreign_target,
                       budget);
}

std::vector<Check> PlayTracker(bus::Bus& bus, const PlayOptions& options, const Budget& budget) {
  Player player(bus, options);
  std::vector<Observed> seen;
  auto sub = bus::SubscribeTyped<sim_state_t>(
      bus, player.channels().SimState(), [&](const std::string&, const sim_state_t& m) {
        seen.push_back({m.episode, m.tick, 0, player.Now(), StateProblem(m, options.modules), 0});
      });
  player.Play([](std::int64_t, std::int64_t) {});
  // A tracker answers the clock's FINISHED too: those states are of the played episodes but of
  // no RUNNING tick; leave them out.
  std::vector<Observed> running;
  for (const Observed& o : seen)
    if (!(o.episode == player.clock().episode && o.tick == options.ticks) &&
        !(o.episode == player.clock().late_episode &&
          o.tick == player.clock().late_from + options.ticks / 2))
      running.push_back(o);
  return JudgeTracker(player.clock(), running, budget);
}

}  // namespace ahhs::conformance
