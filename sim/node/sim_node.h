// The simulator's protocol role (docs/protocol.md): obeys SIM/CONTROL, publishes SENSORS,
// TOPOLOGY, CLOCK and STATE, applies HINGE commands, in lockstep or at wall-clock pace.
// It sees only a Bus, so it runs as its own process (udpm://) or inside the fused arena (memq://).
#pragma once

#include <ahhs/hinge_command_t.hpp>
#include <ahhs/module_sensors_t.hpp>
#include <ahhs/sim_control_t.hpp>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "bus/bus.h"
#include "bus/channels.h"
#include "bus/drop_log.h"
#include "bus/typed.h"
#include "sim/core/scenario.h"

namespace ahhs::sim {

struct SimNodeOptions {
  std::string arena = bus::kDefaultArena;
  // Lockstep: how long the sim waits for every module's HINGE(t) before it goes on with the
  // last command of the missing ones (counted in stats().missed_commands). 0: exact lockstep,
  // it waits for every command (a lost one stalls the episode; its launcher aborts it).
  std::chrono::milliseconds lockstep_timeout{2000};
  // SIM/STATE messages per simulated second; 0: once per tick in lockstep (all the fitness
  // monitor uses) and 40 in real time (smooth for a viewer at wall-clock pace).
  double state_rate = 0;
  // Lockstep: at least this much wall time per tick (0 = as fast as the modules answer). Gives a
  // passive listener such as lcm-logger time to keep up; results do not depend on it.
  std::chrono::microseconds min_tick_period{0};
  // Modules whose bodies are hardware (ahhs-sim --hardware-modules, docs/hardware.md): the sim
  // publishes no SENSORS for them, and their simulated bodies follow the hinge_angle their
  // firmware reports on SENSORS (a digital twin), so that the other modules still feel them.
  // Real time and the gait only.
  std::set<int> hardware_modules;
};

struct SimNodeStats {
  std::uint64_t episodes = 0;
  std::uint64_t ticks = 0;
  std::uint64_t commands = 0;          // HINGE commands applied
  std::uint64_t missed_commands = 0;   // lockstep: a module's HINGE(t) missing at the timeout
  std::uint64_t late_commands = 0;     // lockstep: HINGE for a tick already stepped
  std::uint64_t dropped_messages = 0;  // undecodable, foreign episode, invalid values
  std::string drops;                   // per channel and reason (bus::DropLog::Summary), "" if none
  std::uint64_t refused_resets = 0;
  std::uint64_t twin_readings = 0;  // hardware modules' SENSORS whose hinge_angle was followed
  std::string last_error;           // why the last reset was refused or the episode failed
};

class SimNode {
 public:
  enum class Phase { kIdle, kReady, kRunning, kPaused, kFinished, kFailed };

  SimNode(bus::Bus* bus, SimNodeOptions options);
  SimNode(const SimNode&) = delete;
  SimNode& operator=(const SimNode&) = delete;

  // Dispatches messages (waiting at most max_wait for one) and advances the episode as far as
  // its clock allows. Never blocks longer than max_wait.
  void Poll(std::chrono::microseconds max_wait);
  // Poll() without touching the bus: acts on the messages already dispatched. For a caller that
  // handles one shared bus for several nodes (the fused arena).
  void Process();

  Phase phase() const { return phase_; }
  std::int64_t episode() const { return episode_; }
  const Scenario* scenario() const { return scenario_.get(); }
  // Counters, including messages that failed to decode.
  SimNodeStats stats() const {
    SimNodeStats s = stats_;
    s.dropped_messages +=
        control_counters_.dropped + hinge_counters_.dropped + hardware_counters_.dropped;
    bus::DropLog all = drops_;
    all.CountUndecodable("SIM/CONTROL", control_counters_);
    all.CountUndecodable("HINGE", hinge_counters_);
    all.CountUndecodable("SENSORS", hardware_counters_);
    s.drops = all.Summary();
    return s;
  }
  bool realtime() const { return realtime_; }

 private:
  using Clock = std::chrono::steady_clock;
  void OnControl(const sim_control_t& msg);
  void OnHinge(const std::string& channel, const hinge_command_t& msg);
  void OnHardwareSensors(int module, const module_sensors_t& msg);
  // Listens to the HINGE channel of modules 0..n-1 exactly (no regex), so that over udpm:// the
  // bus's socket filter keeps the other modules' traffic out of this process.
  void SyncHingeSubscriptions(int n);
  void Reset(const sim_control_t& msg);
  void Start();
  void Resume();
  bool ReadyToAdvance(Clock::time_point now) const;
  Clock::time_point LockstepDeadline(Clock::time_point now) const;  // max() when exact
  void Advance();
  void PublishTickStart();
  void PublishClock(std::int8_t run_state);
  void PublishState(double sim_time);
  void PublishScene();
  void Finish(StepStatus status);

  bus::Bus* bus_;
  SimNodeOptions options_;
  bus::ArenaChannels channels_;
  void Drop(const char* channel, const char* reason) {
    ++stats_.dropped_messages;
    drops_.Count(channel, reason);
  }
  bus::DropLog drops_;
  bus::DecodeCounters control_counters_, hinge_counters_, hardware_counters_;
  bus::Subscription control_subscription_;
  std::vector<bus::Subscription> hinge_subscriptions_;  // one per module
  std::map<int, bus::Subscription> hardware_subscriptions_;
  std::map<int, double> twin_angle_;  // latest hinge_angle reported by each hardware module
  // Channel names used every tick, built once (a name built per message costs an allocation).
  std::vector<std::string> sensors_channels_, hinge_channels_;
  std::string clock_channel_, state_channel_, scene_channel_;
  SimNodeStats stats_;

  Phase phase_ = Phase::kIdle;
  std::unique_ptr<Scenario> scenario_;
  ScenarioConfig config_;
  std::int64_t episode_ = 0;
  bool realtime_ = false;
  std::int64_t steps_left_ = -1;  // STEP N: ticks to go before pausing; -1 = run freely

  // Latest command per module and the tick it answered; whether HINGE(current tick) arrived.
  std::vector<std::vector<double>> commands_;
  std::vector<std::int64_t> command_tick_;
  int commands_this_tick_ = 0;
  Clock::time_point tick_deadline_;  // lockstep timeout / real-time tick end
  Clock::time_point tick_start_;     // when the current tick's SENSORS went out
  module_sensors_t sensors_msg_;     // reused every tick (no allocation once warm)
  sim_state_t state_msg_;
  double state_period_ = 0;  // simulated seconds between two SIM/STATE messages
  double next_state_time_ = 0;
  std::int8_t last_run_state_ = -1;  // of the last SIM/CLOCK published
  std::vector<BodyState> bodies_;    // scratch
};

const char* PhaseName(SimNode::Phase phase);

}  // namespace ahhs::sim
