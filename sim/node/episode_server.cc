#include "sim/node/episode_server.h"

#include <ahhs/sim_clock_t.hpp>
#include <algorithm>

#include "sim/node/sim_codec.h"

namespace ahhs::sim {

EpisodeServer::EpisodeServer(bus::Bus* bus, EpisodeServerOptions options,
                             std::function<void(const std::string&)> say)
    : bus_(bus), options_(std::move(options)), say_(std::move(say)), channels_(options_.arena) {
  subscription_ = bus::SubscribeTyped<sim_control_t>(
      *bus_, channels_.SimControl(),
      [this](const std::string&, const sim_control_t& m) { OnControl(m); }, &counters_);
}

void EpisodeServer::OnControl(const sim_control_t& m) {
  const std::string ep = "episode " + std::to_string(m.episode);
  switch (m.command) {
    case sim_control_t::CONFIRM:
      Confirm();
      return;
    case sim_control_t::RESET: {
      if (m.episode == refused_episode_) {  // refused or given up: said once
        drops_.Count("SIM/CONTROL", "RESET of a refused episode");
        return;
      }
      if (m.episode == episode_ && phase_ == Phase::kReady) {  // a repeat: answer again
        PublishTopology();
        PublishClock(sim_clock_t::RESET);
        return;
      }
      if (m.episode == episode_ && phase_ != Phase::kIdle && phase_ != Phase::kFinished) return;
      if (phase_ == Phase::kAwaitingConfirm && m.episode == pending_.episode) return;
      ScenarioConfig config;
      std::string error = ConfigFromReset(m, &config);
      if (error.empty() && m.clock_mode != sim_control_t::MODE_REALTIME)
        error = "a physical organism runs in real time only (ahhs-launch --realtime)";
      if (error.empty() && !config.envelope.none())
        error = "a physical organism cannot be given an envelope of noise (" +
                EnvelopeName(config.envelope) + "): the real world is its own";
      if (error.empty() && !config.physics.empty())
        error = "a physical organism cannot be asked for the earlier physics " + config.physics +
                ": the real world is its own";
      if (!error.empty()) {
        drops_.Count("SIM/CONTROL", "RESET refused");
        say_(ep + " refused: " + error);
        refused_episode_ = m.episode;
        return;
      }
      pending_ = m;
      config_ = config;
      shape_ = ShapeOf(config);
      if (!options_.confirm || confirmed_ahead_) {
        Accept();
        return;
      }
      phase_ = Phase::kAwaitingConfirm;
      confirm_deadline_ = Clock::now() + options_.confirm_timeout;
      say_(ep + ": put the organism at its start, then confirm (Enter, or SIM/CONTROL CONFIRM)");
      return;
    }
    case sim_control_t::START:
      if (m.episode != episode_) break;
      if (phase_ == Phase::kReady || phase_ == Phase::kPaused) {
        if (phase_ == Phase::kReady) say_(ep + " running");
        phase_ = Phase::kRunning;
        tick_deadline_ = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                            std::chrono::duration<double>(shape_.control_period));
        PublishClock(sim_clock_t::RUNNING);
      }
      return;
    case sim_control_t::PAUSE:
      if (m.episode == episode_ && phase_ == Phase::kRunning) {
        phase_ = Phase::kPaused;
        PublishClock(sim_clock_t::PAUSED);
      }
      return;
    case sim_control_t::STOP:
      if (m.episode == episode_ &&
          (phase_ == Phase::kRunning || phase_ == Phase::kPaused || phase_ == Phase::kReady))
        Finish();
      return;
    default:
      break;  // STEP (physical time cannot be stepped), unknown commands
  }
  drops_.Count("SIM/CONTROL", "STEP or unknown command");
}

void EpisodeServer::Confirm() {
  if (phase_ == Phase::kAwaitingConfirm) {
    Accept();
  } else if (phase_ == Phase::kIdle || phase_ == Phase::kFinished) {
    if (!confirmed_ahead_) say_("organism confirmed at its start: the next episode goes ahead");
    confirmed_ahead_ = true;
  }
}

void EpisodeServer::Accept() {
  episode_ = pending_.episode;
  tick_ = 0;
  confirmed_ahead_ = false;
  phase_ = Phase::kReady;
  say_("episode " + std::to_string(episode_) + " ready (" + ScenarioName(config_.kind) + ", " +
       std::to_string(shape_.compartments) + " modules, " + std::to_string(shape_.ticks) +
       " ticks)");
  PublishTopology();
  PublishClock(sim_clock_t::RESET);
}

void EpisodeServer::Poll(std::chrono::microseconds max_wait) {
  auto wait = max_wait;
  if (phase_ == Phase::kRunning)
    wait = std::clamp(
        std::chrono::duration_cast<std::chrono::microseconds>(tick_deadline_ - Clock::now()),
        std::chrono::microseconds(0), max_wait);
  bus_->Handle(wait);
  const auto now = Clock::now();
  if (phase_ == Phase::kAwaitingConfirm && now >= confirm_deadline_) {
    say_("episode " + std::to_string(pending_.episode) + ": no confirmation within " +
         std::to_string(options_.confirm_timeout.count() / 1000) + " s; given up");
    refused_episode_ = pending_.episode;
    phase_ = episode_ == 0 ? Phase::kIdle : Phase::kFinished;
    return;
  }
  if (phase_ != Phase::kRunning || now < tick_deadline_) return;
  ++tick_;
  if (tick_ >= shape_.ticks) {
    Finish();
    return;
  }
  // Keep pace with the wall clock; after a stall, do not race to catch up.
  tick_deadline_ =
      std::max(tick_deadline_ + std::chrono::duration_cast<Clock::duration>(
                                    std::chrono::duration<double>(shape_.control_period)),
               now);
  PublishClock(sim_clock_t::RUNNING);
  if (tick_ % 20 == 0) PublishTopology();  // lets a late module learn the docking
}

void EpisodeServer::Finish() {
  phase_ = Phase::kFinished;
  // Three times: one lost datagram must not leave the fitness monitor waiting.
  for (int k = 0; k < 3; ++k) PublishClock(sim_clock_t::FINISHED);
  say_("episode " + std::to_string(episode_) + " finished after " + std::to_string(tick_) +
       " ticks");
}

void EpisodeServer::PublishClock(std::int8_t run_state) {
  auto c = ClockMessage(episode_, tick_, shape_.control_period, true, run_state);
  c.utime = bus::NowUtime();
  bus::PublishTyped(*bus_, channels_.SimClock(), c);
}

void EpisodeServer::PublishTopology() {
  auto t = TopologyMessage(shape_.compartments, ChainDocking(shape_.compartments), episode_, tick_);
  t.utime = bus::NowUtime();
  bus::PublishTyped(*bus_, channels_.Topology(), t);
}

}  // namespace ahhs::sim
