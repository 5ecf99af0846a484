// The sim's protocol role without physics (ahhs-sim --physics none), for a physical organism
// (docs/hardware.md, "Episode server"): obeys SIM/CONTROL, publishes SIM/CLOCK every tick at
// wall-clock pace and TOPOLOGY (the chain of the scenario's compartments) at RESET and every 20
// ticks. It publishes no SENSORS and no SIM/STATE: the modules' firmware and a tracker do.
//
// Rules:
// - Real time only: a RESET in lockstep is refused (said once per episode).
// - Before each new episode the organism must be put back at its start: the RESET waits for an
//   operator's Confirm() (stdin, or SIM/CONTROL CONFIRM, e.g. from a button) for at most
//   `confirm_timeout`, then the episode is given up (the launcher's handshake fails). A
//   confirmation that comes first lets the next RESET go ahead at once.
// - Ticks 0 .. T-1 run (T from the scenario's duration); the end is SIM/CLOCK FINISHED, three
//   times. STOP ends early, PAUSE and START hold and resume; STEP is refused.
#pragma once

#include <ahhs/sim_control_t.hpp>
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

#include "bus/bus.h"
#include "bus/channels.h"
#include "bus/drop_log.h"
#include "bus/typed.h"
#include "sim/core/scenario.h"

namespace ahhs::sim {

struct EpisodeServerOptions {
  std::string arena = bus::kDefaultArena;
  bool confirm = true;  // wait for the operator before each episode
  std::chrono::milliseconds confirm_timeout{600000};
};

class EpisodeServer {
 public:
  enum class Phase { kIdle, kAwaitingConfirm, kReady, kRunning, kPaused, kFinished };
  // `say` gets one line per event an operator should see.
  EpisodeServer(bus::Bus* bus, EpisodeServerOptions options,
                std::function<void(const std::string&)> say);
  EpisodeServer(const EpisodeServer&) = delete;
  EpisodeServer& operator=(const EpisodeServer&) = delete;

  // Dispatches messages (waiting at most max_wait) and keeps the clock.
  void Poll(std::chrono::microseconds max_wait);
  // The operator says the organism is at its start.
  void Confirm();

  Phase phase() const { return phase_; }
  std::int64_t episode() const { return episode_; }
  std::int64_t tick() const { return tick_; }
  std::int64_t dropped() const {
    return static_cast<std::int64_t>(drops_.total() + counters_.dropped);
  }
  // Per channel and reason (bus::DropLog::Summary), "" when nothing was dropped.
  std::string drops() const {
    bus::DropLog all = drops_;
    all.CountUndecodable("SIM/CONTROL", counters_);
    return all.Summary();
  }

 private:
  using Clock = std::chrono::steady_clock;
  void OnControl(const sim_control_t& m);
  void Accept();
  void PublishClock(std::int8_t run_state);
  void PublishTopology();
  void Finish();

  bus::Bus* bus_;
  EpisodeServerOptions options_;
  std::function<void(const std::string&)> say_;
  bus::ArenaChannels channels_;
  bus::DecodeCounters counters_;
  bus::Subscription subscription_;
  Phase phase_ = Phase::kIdle;
  sim_control_t pending_{};  // the RESET waiting for the operator
  ScenarioConfig config_;
  ScenarioShape shape_;
  std::int64_t episode_ = 0;
  std::int64_t refused_episode_ = 0;  // refused or given up: its RESETs are ignored
  std::int64_t tick_ = 0;
  bool confirmed_ahead_ = false;
  Clock::time_point confirm_deadline_, tick_deadline_;
  bus::DropLog drops_;
};

}  // namespace ahhs::sim
