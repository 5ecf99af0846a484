#include "sim/node/sim_node.h"

#include <ahhs/sim_clock_t.hpp>
#include <algorithm>
#include <cmath>

#include "sim/node/sim_codec.h"

namespace ahhs::sim {

const char* PhaseName(SimNode::Phase phase) {
  switch (phase) {
    case SimNode::Phase::kIdle:
      return "idle";
    case SimNode::Phase::kReady:
      return "ready";
    case SimNode::Phase::kRunning:
      return "running";
    case SimNode::Phase::kPaused:
      return "paused";
    case SimNode::Phase::kFinished:
      return "finished";
    case SimNode::Phase::kFailed:
      return "failed";
  }
  return "?";
}

SimNode::SimNode(bus::Bus* bus, SimNodeOptions options)
    : bus_(bus),
      options_(std::move(options)),
      channels_(options_.arena),
      clock_channel_(channels_.SimClock()),
      state_channel_(channels_.SimState()),
      scene_channel_(channels_.SimScene()) {
  control_subscription_ = bus::SubscribeTyped<sim_control_t>(
      *bus_, channels_.SimControl(),
      [this](const std::string&, const sim_control_t& m) { OnControl(m); }, &control_counters_);
}

void SimNode::SyncHingeSubscriptions(int n) {
  while (static_cast<int>(sensors_channels_.size()) < n) {
    const int module = static_cast<int>(sensors_channels_.size());
    sensors_channels_.push_back(channels_.Sensors(module));
    hinge_channels_.push_back(channels_.Hinge(module));
  }
  while (static_cast<int>(hinge_subscriptions_.size()) > n) {
    hinge_subscriptions_.pop_back();  // unsubscribes
  }
  while (static_cast<int>(hinge_subscriptions_.size()) < n) {
    const int module = static_cast<int>(hinge_subscriptions_.size());
    hinge_subscriptions_.push_back(bus::SubscribeTyped<hinge_command_t>(
        *bus_, hinge_channels_[static_cast<std::size_t>(module)],
        [this](const std::string& channel, const hinge_command_t& m) { OnHinge(channel, m); },
        &hinge_counters_));
  }
}

void SimNode::OnControl(const sim_control_t& m) {
  switch (m.command) {
    case sim_control_t::RESET:
      Reset(m);
      return;
    case sim_control_t::START:
      if (m.episode != episode_ || !scenario_) break;
      if (phase_ == Phase::kReady) {
        steps_left_ = -1;
        Start();
      } else if (phase_ == Phase::kPaused) {
        steps_left_ = -1;
        Resume();
      }
      return;
    case sim_control_t::PAUSE:
      if (m.episode == episode_ && phase_ == Phase::kRunning) {
        phase_ = Phase::kPaused;
        PublishClock(sim_clock_t::PAUSED);
      }
      return;
    case sim_control_t::STEP:
      if (m.episode != episode_ || m.steps <= 0) break;
      if (phase_ == Phase::kReady || phase_ == Phase::kPaused) {
        steps_left_ = m.steps;
        if (phase_ == Phase::kReady)
          Start();
        else
          Resume();
      }
      return;
    case sim_control_t::STOP:
      if (m.episode == episode_ &&
          (phase_ == Phase::kRunning || phase_ == Phase::kPaused || phase_ == Phase::kReady))
        Finish(StepStatus::kFinished);
      return;
    default:
      break;
  }
  Drop("SIM/CONTROL", "unknown command, or another episode");
}

void SimNode::Reset(const sim_control_t& m) {
  if (m.episode == episode_ && phase_ != Phase::kIdle && phase_ != Phase::kReady) {
    // The launcher repeats RESET until the sim answers; a repeat that arrives after START
    // (datagrams can overtake each other) must not restart the running episode.
    Drop("SIM/CONTROL", "RESET of the running episode");
    return;
  }
  ScenarioConfig config;
  std::string error = ConfigFromReset(m, &config);
  if (error.empty() && !options_.hardware_modules.empty()) {
    const int modules = ShapeOf(config).compartments;
    if (config.kind != ScenarioKind::kGait)
      error = "hardware modules: only the gait's modules have bodies to hand over";
    else if (m.clock_mode != sim_control_t::MODE_REALTIME)
      error = "hardware modules need real time (ahhs-launch --realtime)";
    else if (*options_.hardware_modules.rbegin() >= modules ||
             *options_.hardware_modules.begin() < 0)
      error = "hardware module " + std::to_string(*options_.hardware_modules.rbegin()) +
              " is not one of the " + std::to_string(modules) + " modules";
  }
  if (!error.empty()) {
    ++stats_.refused_resets;
    stats_.last_error = "reset refused: " + error;
    return;
  }
  // Reuse the world when the config is unchanged (building an ODE world is the slow part).
  if (!scenario_ || config.kind != config_.kind || config.num_modules != config_.num_modules ||
      config.docking != config_.docking || config.duration != config_.duration) {
    scenario_ = MakeScenario(config);
    config_ = config;
  }
  scenario_->Reset(static_cast<std::uint64_t>(m.seed));
  episode_ = m.episode;
  realtime_ = m.clock_mode == sim_control_t::MODE_REALTIME;
  steps_left_ = -1;
  const int n = scenario_->num_compartments();
  SyncHingeSubscriptions(n);  // before TOPOLOGY and CLOCK go out: no module commands earlier
  twin_angle_.clear();
  for (int h : options_.hardware_modules)
    if (!hardware_subscriptions_.count(h))
      hardware_subscriptions_[h] = bus::SubscribeTyped<module_sensors_t>(
          *bus_, channels_.Sensors(h),
          [this, h](const std::string&, const module_sensors_t& s) { OnHardwareSensors(h, s); },
          &hardware_counters_);
  commands_.assign(static_cast<std::size_t>(n),
                   std::vector<double>(static_cast<std::size_t>(scenario_->num_actuators()), 0.0));
  command_tick_.assign(static_cast<std::size_t>(n), -1);
  commands_this_tick_ = 0;
  state_period_ = options_.state_rate > 0 ? 1.0 / options_.state_rate
                  : realtime_             ? 1.0 / 40.0
                                          : scenario_->control_period();
  next_state_time_ = state_period_;  // the state at time 0 goes out below
  phase_ = Phase::kReady;
  ++stats_.episodes;
  bus::PublishTyped(*bus_, channels_.Topology(), [&] {
    auto t = TopologyMessage(*scenario_, episode_);
    t.utime = bus::NowUtime();
    return t;
  }());
  PublishScene();
  PublishClock(sim_clock_t::RESET);
  PublishState(0.0);
}

void SimNode::Start() {
  phase_ = Phase::kRunning;
  PublishTickStart();
}

void SimNode::Resume() {
  // The paused tick's sensors are already out; restart its clock from now.
  phase_ = Phase::kRunning;
  tick_deadline_ =
      realtime_ ? Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                     std::chrono::duration<double>(scenario_->control_period()))
                : LockstepDeadline(Clock::now());
  PublishClock(sim_clock_t::RUNNING);
}

void SimNode::OnHinge(const std::string& channel, const hinge_command_t& m) {
  // The channel must be the module's own: m.module indexes the channels subscribed for this
  // episode's modules only (anything else is dropped before it is used as an index).
  if (!scenario_ || m.episode != episode_ || m.module < 0 ||
      m.module >= scenario_->num_compartments() ||
      channel != hinge_channels_[static_cast<std::size_t>(m.module)]) {
    Drop("HINGE",
         !scenario_ || m.episode != episode_ ? "another episode" : "a module speaking for another");
    return;
  }
  if (!CheckHinge(m, *scenario_).empty()) {
    Drop("HINGE", "NaN, out of range or wrong size");  // never reaches the physics
    return;
  }
  const auto i = static_cast<std::size_t>(m.module);
  if (!realtime_) {
    if (m.tick < scenario_->tick()) {
      ++stats_.late_commands;
      return;
    }
    if (m.tick > scenario_->tick()) {
      Drop("HINGE", "a tick that has not started");
      return;
    }
    if (command_tick_[i] != m.tick) ++commands_this_tick_;
  }
  commands_[i] = m.values;
  command_tick_[i] = m.tick;
}

void SimNode::OnHardwareSensors(int module, const module_sensors_t& m) {
  if (!scenario_ || m.episode != episode_ || m.module != module || !std::isfinite(m.hinge_angle)) {
    Drop("SENSORS", !scenario_ || m.episode != episode_ ? "another episode"
                    : m.module != module                ? "another module's"
                                                        : "hinge angle not finite");
    return;
  }
  twin_angle_[module] = m.hinge_angle;
  ++stats_.twin_readings;
}

bool SimNode::ReadyToAdvance(Clock::time_point now) const {
  if (phase_ != Phase::kRunning) return false;
  if (realtime_) return now >= tick_deadline_;
  if (now < tick_start_ + options_.min_tick_period) return false;
  return commands_this_tick_ == scenario_->num_compartments() || now >= tick_deadline_;
}

void SimNode::Poll(std::chrono::microseconds max_wait) {
  auto wait = max_wait;
  if (phase_ == Phase::kRunning) {
    const auto to_deadline =
        std::chrono::duration_cast<std::chrono::microseconds>(tick_deadline_ - Clock::now());
    wait = std::clamp(to_deadline, std::chrono::microseconds(0), max_wait);
    if (!realtime_ && commands_this_tick_ == scenario_->num_compartments())
      wait = std::chrono::microseconds(0);
  }
  bus_->Handle(wait);
  Process();
}

SimNode::Clock::time_point SimNode::LockstepDeadline(Clock::time_point now) const {
  if (options_.lockstep_timeout.count() == 0) return Clock::time_point::max();  // exact
  return now + options_.lockstep_timeout;
}

void SimNode::Process() {
  if (ReadyToAdvance(Clock::now())) Advance();
}

void SimNode::Advance() {
  const int n = scenario_->num_compartments();
  for (int c = 0; c < n; ++c) {
    const auto i = static_cast<std::size_t>(c);
    if (options_.hardware_modules.count(c)) {  // the body follows its hardware, not commands
      const auto twin = twin_angle_.find(c);
      if (twin != twin_angle_.end()) scenario_->FollowHinge(c, twin->second);
      continue;
    }
    if (!realtime_ && command_tick_[i] != scenario_->tick())
      ++stats_.missed_commands;  // keeps the last one
    if (command_tick_[i] >= 0) {
      scenario_->SetActuators(c, commands_[i].data());
      ++stats_.commands;
    }
  }
  const StepStatus status = scenario_->Step([&](double t) {
    if (t + 1e-9 >= next_state_time_) {
      PublishState(t);
      next_state_time_ += state_period_;
    }
  });
  ++stats_.ticks;
  commands_this_tick_ = 0;
  if (status != StepStatus::kRunning) {
    Finish(status);
    return;
  }
  if (steps_left_ > 0 && --steps_left_ == 0) {
    phase_ = Phase::kPaused;
    steps_left_ = -1;
    PublishClock(sim_clock_t::PAUSED);
  }
  PublishTickStart();
}

void SimNode::PublishTickStart() {
  const auto now = Clock::now();
  tick_start_ = now;
  if (realtime_) {
    const auto period = std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(scenario_->control_period()));
    // Keep pace with the wall clock; after a stall, do not race to catch up.
    tick_deadline_ = scenario_->tick() == 0 ? now + period : std::max(tick_deadline_ + period, now);
  } else {
    tick_deadline_ = LockstepDeadline(now);
  }
  for (int c = 0; c < scenario_->num_compartments(); ++c) {
    if (options_.hardware_modules.count(c)) continue;  // its firmware publishes its readings
    FillSensorsMessage(*scenario_, c, episode_, &sensors_msg_);
    sensors_msg_.utime = bus::NowUtime();
    bus::PublishTyped(*bus_, sensors_channels_[static_cast<std::size_t>(c)], sensors_msg_);
  }
  // Lockstep: modules take the tick from SENSORS and the monitor from STATE, so the clock goes
  // out when the run state changes and once per simulated second (every datagram wakes every
  // listening process). Real time: every tick, the pace a late joiner follows.
  const std::int8_t run_state =
      phase_ == Phase::kPaused ? sim_clock_t::PAUSED : sim_clock_t::RUNNING;
  if (realtime_ || run_state != last_run_state_ || scenario_->tick() % 20 == 0)
    PublishClock(run_state);
  if (scenario_->tick() > 0 && SceneDue(scenario_->tick())) PublishScene();  // RESET sent tick 0's
  if (realtime_ && scenario_->tick() % 20 == 0) {  // lets a late module learn the docking
    auto t = TopologyMessage(*scenario_, episode_);
    t.utime = bus::NowUtime();
    bus::PublishTyped(*bus_, channels_.Topology(), t);
  }
}

void SimNode::PublishClock(std::int8_t run_state) {
  last_run_state_ = run_state;
  bus::PublishTyped(
      *bus_, clock_channel_,
      ClockMessage(episode_, scenario_ ? scenario_->tick() : 0,
                   scenario_ ? scenario_->control_period() : 0, realtime_, run_state));
}

void SimNode::PublishState(double sim_time) {
  scenario_->Bodies(&bodies_);
  KeepMovingBodies(&bodies_);
  // `tick`: control periods done at the snapshot (the state after tick t has t + 1; during a
  // step, scenario_->tick() still counts the step in progress as not done).
  const auto done =
      static_cast<std::int64_t>(std::floor(sim_time / scenario_->control_period() + 1e-9));
  FillStateMessage(bodies_, episode_, done, sim_time, &state_msg_);
  state_msg_.utime = bus::NowUtime();
  bus::PublishTyped(*bus_, state_channel_, state_msg_);
}

void SimNode::PublishScene() {
  std::vector<BodyState> bodies;
  scenario_->Bodies(&bodies);
  KeepStaticBodies(&bodies);
  auto m = StateMessage(bodies, episode_, scenario_->tick(), scenario_->sim_time());
  m.utime = bus::NowUtime();
  bus::PublishTyped(*bus_, scene_channel_, m);
}

void SimNode::Finish(StepStatus status) {
  if (status == StepStatus::kFailed) {
    phase_ = Phase::kFailed;
    stats_.last_error = scenario_->error();
    for (int k = 0; k < 3; ++k) PublishClock(sim_clock_t::FAILED);
    return;
  }
  phase_ = Phase::kFinished;
  PublishState(scenario_->sim_time());
  // The end is announced three times: on a lossy link one lost datagram must not leave the
  // fitness monitor waiting forever (receivers ignore the repeats).
  for (int k = 0; k < 3; ++k) PublishClock(sim_clock_t::FINISHED);
}

}  // namespace ahhs::sim
