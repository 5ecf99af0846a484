// The fitness monitor's protocol role: learns the episode from SIM/CONTROL RESET, follows
// SIM/STATE, and publishes FITNESS (running, about once per simulated second, and final when
// SIM/CLOCK says the episode finished or failed). The final tick's state may come after
// FINISHED (a tracker hears FINISHED, then sends the state of that tick): when it is missing at
// FINISHED the monitor waits for it up to `final_state_wait`, then ends without it
// (docs/protocol.md, "End").
#pragma once

#include <ahhs/fitness_t.hpp>
#include <ahhs/sim_clock_t.hpp>
#include <ahhs/sim_control_t.hpp>
#include <chrono>
#include <memory>
#include <optional>

#include "bus/bus.h"
#include "bus/channels.h"
#include "bus/drop_log.h"
#include "bus/typed.h"
#include "episode/fitness/fitness_monitor.h"

namespace ahhs::episode {

class FitnessNode {
 public:
  static constexpr std::chrono::milliseconds kFinalStateWait{1000};

  FitnessNode(bus::Bus* bus, std::string arena = bus::kDefaultArena,
              std::chrono::milliseconds final_state_wait = kFinalStateWait);
  // Handles what arrived (waiting up to max_wait), then Maintain().
  void Poll(std::chrono::microseconds max_wait);
  // Ends an episode whose final tick's state did not come within the wait after FINISHED.
  // Whoever dispatches the bus without Poll() calls it.
  void Maintain();

  // The final result of the current episode, once published.
  const std::optional<fitness_t>& final_result() const { return final_; }
  std::int64_t episode() const { return episode_; }
  std::uint64_t dropped_messages() const {
    return control_counters_.dropped + state_counters_.dropped + clock_counters_.dropped +
           drops_.total();
  }
  // Per channel and reason (bus::DropLog::Summary), "" when nothing was dropped.
  std::string drops() const {
    bus::DropLog all = drops_;
    all.CountUndecodable("SIM/CONTROL", control_counters_);
    all.CountUndecodable("SIM/STATE", state_counters_);
    all.CountUndecodable("SIM/CLOCK", clock_counters_);
    return all.Summary();
  }

 private:
  void OnControl(const sim_control_t& m);
  void OnState(const sim_state_t& m);
  void OnClock(const sim_clock_t& m);
  fitness_t Message(bool is_final, std::int8_t status, const std::string& text) const;
  void Finish(fitness_t final_message);

  bus::Bus* bus_;
  bus::ArenaChannels channels_;
  bus::DecodeCounters control_counters_, state_counters_, clock_counters_;
  bus::DropLog drops_;
  std::int64_t episode_ = 0;
  sim::ScenarioShape shape_;
  std::unique_ptr<FitnessMonitor> monitor_;
  std::optional<fitness_t> final_;
  double next_report_ = 1.0;
  std::int64_t last_tick_ = 0;
  std::chrono::milliseconds final_state_wait_;
  // FINISHED came before the final tick's state: wait for it until then.
  std::optional<std::chrono::steady_clock::time_point> finish_deadline_;
  std::vector<bus::Subscription> subscriptions_;  // last: destroyed first
};

}  // namespace ahhs::episode
