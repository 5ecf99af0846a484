#include "episode/fitness/fitness_node.h"

#include <algorithm>
#include <cmath>

#include "bus/wire_text.h"
#include "sim/node/sim_codec.h"

namespace ahhs::episode {

FitnessNode::FitnessNode(bus::Bus* bus, std::string arena,
                         std::chrono::milliseconds final_state_wait)
    : bus_(bus), channels_(std::move(arena)), final_state_wait_(final_state_wait) {
  subscriptions_.push_back(bus::SubscribeTyped<sim_control_t>(
      *bus_, channels_.SimControl(),
      [this](const std::string&, const sim_control_t& m) { OnControl(m); }, &control_counters_));
  subscriptions_.push_back(bus::SubscribeTyped<sim_state_t>(
      *bus_, channels_.SimState(), [this](const std::string&, const sim_state_t& m) { OnState(m); },
      &state_counters_));
  subscriptions_.push_back(bus::SubscribeTyped<sim_clock_t>(
      *bus_, channels_.SimClock(), [this](const std::string&, const sim_clock_t& m) { OnClock(m); },
      &clock_counters_));
}

void FitnessNode::OnControl(const sim_control_t& m) {
  if (m.command != sim_control_t::RESET) return;
  if (m.episode == episode_ && monitor_) {  // a repeated RESET: acknowledge again
    if (!final_) bus::PublishTyped(*bus_, channels_.Fitness(), Message(false, fitness_t::OK, ""));
    return;
  }
  sim::ScenarioConfig config;
  if (!sim::ConfigFromReset(m, &config).empty()) {
    drops_.Count("SIM/CONTROL", "invalid RESET");
    return;
  }
  episode_ = m.episode;
  shape_ = sim::ShapeOf(config);
  monitor_ = std::make_unique<FitnessMonitor>(config.kind, shape_.control_period, shape_.ticks);
  final_.reset();
  finish_deadline_.reset();
  next_report_ = 1.0;
  last_tick_ = 0;
  // Acknowledge the episode: a running result at tick 0 tells the launcher the monitor is ready.
  bus::PublishTyped(*bus_, channels_.Fitness(), Message(false, fitness_t::OK, ""));
}

void FitnessNode::OnState(const sim_state_t& m) {
  if (!monitor_ || m.episode != episode_ || final_ || !monitor_->Add(m)) {
    drops_.Count("SIM/STATE", !monitor_ || m.episode != episode_ ? "another episode"
                              : final_                           ? "after the result"
                                                                 : "invalid or repeated");
    return;
  }
  last_tick_ = m.tick;
  if (finish_deadline_ && monitor_->complete()) {  // the final tick's state, after FINISHED
    Finish(Message(true, fitness_t::OK, ""));
    return;
  }
  if (m.sim_time + 1e-9 >= next_report_) {
    bus::PublishTyped(*bus_, channels_.Fitness(), Message(false, fitness_t::OK, ""));
    next_report_ += 1.0;
  }
}

void FitnessNode::OnClock(const sim_clock_t& m) {
  if (!monitor_ || m.episode != episode_ || final_ || finish_deadline_) return;
  if (m.run_state == sim_clock_t::FINISHED && monitor_->states_seen() == 0) {
    // Nothing was measured: fitness 0 would be a silent wrong answer.
    final_ = Message(true, fitness_t::ERROR,
                     "no valid SIM/STATE arrived for episode " + std::to_string(episode_) + " (" +
                         std::to_string(m.tick) +
                         " ticks): a tracker must send one state per tick with the episode and "
                         "tick of SIM/CLOCK (docs/hardware.md, \"Timing rules\")");
  } else if (m.run_state == sim_clock_t::FINISHED && !monitor_->complete()) {
    finish_deadline_ = std::chrono::steady_clock::now() + final_state_wait_;
    return;
  } else if (m.run_state == sim_clock_t::FINISHED) {
    final_ = Message(true, fitness_t::OK, "");
  } else if (m.run_state == sim_clock_t::FAILED) {
    final_ = Message(true, fitness_t::ERROR, "the simulation failed (physics blew up)");
  } else {
    return;
  }
  Finish(*final_);
}

void FitnessNode::Finish(fitness_t final_message) {
  final_ = std::move(final_message);
  finish_deadline_.reset();
  for (int k = 0; k < 3; ++k)
    bus::PublishTyped(*bus_, channels_.Fitness(), *final_);  // see SimNode::Finish
}

void FitnessNode::Maintain() {
  if (finish_deadline_ && !final_ && std::chrono::steady_clock::now() >= *finish_deadline_)
    Finish(Message(true, fitness_t::OK, ""));  // without the final state: states_missed says so
}

fitness_t FitnessNode::Message(bool is_final, std::int8_t status, const std::string& text) const {
  fitness_t f{};
  f.utime = bus::NowUtime();
  f.episode = episode_;
  f.tick = last_tick_;
  f.sim_time = static_cast<double>(monitor_->ticks_seen()) * shape_.control_period;
  f.fitness = monitor_->fitness();
  f.cost = monitor_->cost();
  f.descriptor = monitor_->descriptor();
  f.descriptor_size = static_cast<std::int8_t>(f.descriptor.size());
  f.is_final = is_final;
  f.status = status;
  f.states_seen = static_cast<std::int32_t>(monitor_->states_seen());
  f.states_missed = static_cast<std::int32_t>(is_final ? monitor_->ticks_missed() : 0);
  // A final OK result says what the monitor dropped, per channel and reason.
  const std::string dropped = is_final && status == fitness_t::OK ? drops() : "";
  f.message = bus::ToWireText(dropped.empty() ? text : "dropped: " + dropped);
  return f;
}

void FitnessNode::Poll(std::chrono::microseconds max_wait) {
  if (finish_deadline_) {  // wake for the deadline
    const auto left = std::chrono::duration_cast<std::chrono::microseconds>(
        *finish_deadline_ - std::chrono::steady_clock::now());
    max_wait = std::max(std::chrono::microseconds(0), std::min(max_wait, left));
  }
  bus_->Handle(max_wait);
  Maintain();
}

}  // namespace ahhs::episode
