// Test peers for external roles:
//   role_peer --role wrong-hash-module --lcm-url URL --arena A --id N --seconds S
//       a module that answers every GENOME with READY but reports another genome hash
//   role_peer --role drifting-firmware --lcm-url URL --arena A --id N --seconds S
//       a faulty firmware (ahhs-conformance must fail it): readings on its own 19 Hz timer with
//       its own tick count, and it follows every HINGE whatever its episode
//   role_peer --role stale-tracker --lcm-url URL --arena A --modules N --seconds S
//       a faulty tracker: states on every clock tick but with episode 0 (not copied)
//   role_peer --role faulty-module --fault F --lcm-url URL --arena A --id N --seconds S
//       a module controller that breaks one rule (ahhs-conformance module must fail it):
//       reset-on-genome (a repeated GENOME rebuilds the controller), no-wait (steps on SENSORS
//       without waiting for the neighbours' packets), any-episode (takes SENSORS and HORMONE of
//       any episode)
//   role_peer --role faulty-server --lcm-url URL --arena A --seconds S
//       an episode server (ahhs-conformance sim must fail it): its clock runs on its own 15 Hz
//       timer (by tick 10, where the kit's foreign STOP ends it, 167 ms behind a 20 Hz schedule),
//       any episode's STOP ends the episode, FINISHED goes out once, and it answers a RESET of any
//       scenario
// (Correct ones: ahhs-module, examples/controller-lua, examples/firmware-c, examples/tracker-c.)
//   role_peer --role button --lcm-url URL --arena A --seconds S
//       an operator's button: SIM/CONTROL CONFIRM once, after S seconds
#include <ahhs/genome_t.hpp>
#include <ahhs/hinge_command_t.hpp>
#include <ahhs/hormone_packet_t.hpp>
#include <ahhs/module_sensors_t.hpp>
#include <ahhs/module_status_t.hpp>
#include <ahhs/sim_clock_t.hpp>
#include <ahhs/sim_control_t.hpp>
#include <ahhs/sim_state_t.hpp>
#include <ahhs/topology_t.hpp>
#include <algorithm>
#include <chrono>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "base/cli.h"
#include "bus/channels.h"
#include "bus/lcm_bus.h"
#include "bus/typed.h"
#include "modules/core/hormone_system.h"
#include "modules/node/genome_codec.h"

namespace cli = ahhs::base::cli;

using namespace ahhs;

namespace {

// An episode server with the faults listed at the top.
class FaultyServer {
 public:
  FaultyServer(bus::Bus& bus, const bus::ArenaChannels& ch) : bus_(bus), ch_(ch) {
    sub_ = bus::SubscribeTyped<sim_control_t>(
        bus_, ch_.SimControl(), [this](const std::string&, const sim_control_t& m) {
          if (m.command == sim_control_t::RESET && !(running_ && m.episode == episode_)) {
            episode_ = m.episode;
            ticks_ = static_cast<std::int64_t>(m.duration / 0.05 + 0.5);
            modules_ = m.num_modules;
            running_ = false;
            tick_ = 0;
            Clock(sim_clock_t::RESET);
            topology_t t{};
            t.utime = bus::NowUtime();
            t.episode = episode_;
            t.num_modules = modules_;
            t.ports_per_module = 4;
            t.num_links = static_cast<std::int16_t>(modules_ - 1);
            for (int k = 0; k + 1 < modules_; ++k) {
              t.module_a.push_back(k);
              t.port_a.push_back(2);
              t.module_b.push_back(k + 1);
              t.port_b.push_back(0);
            }
            bus::PublishTyped(bus_, ch_.Topology(), t);
          } else if (m.command == sim_control_t::START && m.episode == episode_ && !running_ &&
                     tick_ == 0) {
            running_ = true;
            next_ = std::chrono::steady_clock::now();
          } else if (m.command == sim_control_t::STOP && running_) {  // any episode's
            running_ = false;
            Clock(sim_clock_t::FINISHED);
          }
        });
  }
  void Tick() {
    if (!running_ || std::chrono::steady_clock::now() < next_) return;
    next_ += std::chrono::microseconds(1000000 / 15);  // its own timer
    if (tick_ == ticks_) {
      running_ = false;
      Clock(sim_clock_t::FINISHED);  // once
      return;
    }
    Clock(sim_clock_t::RUNNING);
    ++tick_;
  }

 private:
  void Clock(std::int8_t state) {
    sim_clock_t c{};
    c.utime = bus::NowUtime();
    c.episode = episode_;
    c.tick = tick_;
    c.sim_time = static_cast<double>(tick_) * 0.05;
    c.control_period = 0.05;
    c.clock_mode = sim_clock_t::MODE_REALTIME;
    c.run_state = state;
    bus::PublishTyped(bus_, ch_.SimClock(), c);
  }
  bus::Bus& bus_;
  const bus::ArenaChannels& ch_;
  std::int64_t episode_ = 0, tick_ = 0, ticks_ = 0;
  int modules_ = 0;
  bool running_ = false;
  std::chrono::steady_clock::time_point next_;
  bus::Subscription sub_;
};

// A lockstep module controller with one planted fault (see the comment at the top).
class FaultyModule {
 public:
  FaultyModule(bus::Bus& bus, const bus::ArenaChannels& ch, int id, std::string fault)
      : bus_(bus), ch_(ch), id_(id), fault_(std::move(fault)) {
    subs_.push_back(bus::SubscribeTyped<genome_t>(
        bus_, ch_.Genome(), [this](const std::string&, const genome_t& m) { OnGenome(m); }));
    subs_.push_back(bus::SubscribeTyped<topology_t>(
        bus_, ch_.Topology(), [this](const std::string&, const topology_t& m) { OnTopology(m); }));
    subs_.push_back(bus::SubscribeTyped<module_sensors_t>(
        bus_, ch_.Sensors(id_), [this](const std::string&, const module_sensors_t& m) {
          if (m.episode != episode_ && fault_ != "any-episode") return;
          sensors_ = m;
          TryStep();
        }));
  }

 private:
  void OnGenome(const genome_t& m) {
    if (m.episode == episode_ && controller_ && fault_ != "reset-on-genome") {
      if (step_ == 0) Ready();
      return;
    }
    if (m.episode != episode_) NewEpisode(m.episode);
    modules::Genome g;
    if (!modules::GenomeFromMessage(m, &g).empty()) return;
    controller_ = std::make_unique<modules::Controller>(std::move(g));
    state_ = modules::MakeState(*controller_);
    hash_ = m.genome_hash;
    Ready();
  }
  void OnTopology(const topology_t& m) {
    if (m.episode != episode_) NewEpisode(m.episode);
    std::vector<int> neighbours;
    for (int k = 0; k < m.num_links; ++k) {
      const auto i = static_cast<std::size_t>(k);
      if (m.module_a[i] == id_) neighbours.push_back(m.module_b[i]);
      if (m.module_b[i] == id_) neighbours.push_back(m.module_a[i]);
    }
    std::sort(neighbours.begin(), neighbours.end());
    topology_ = true;
    if (neighbours == neighbours_ && !hormone_subs_.empty()) return Ready();
    neighbours_ = neighbours;
    hormone_subs_.clear();
    for (int n : neighbours_)
      hormone_subs_.push_back(bus::SubscribeTyped<hormone_packet_t>(
          bus_, ch_.Hormone(n), [this](const std::string&, const hormone_packet_t& p) {
            if (p.episode != episode_ && fault_ != "any-episode") return;
            packets_[{p.tick, p.from_module}] = p.amounts;
            TryStep();
          }));
    Ready();
  }
  void NewEpisode(std::int64_t episode) {
    episode_ = episode;
    controller_.reset();
    topology_ = false;
    step_ = 0;
    sensors_.reset();
    packets_.clear();
  }
  void Ready() {
    if (!controller_ || !topology_) return;
    module_status_t s{};
    s.utime = bus::NowUtime();
    s.episode = episode_;
    s.tick = -1;
    s.module = id_;
    s.state = module_status_t::READY;
    s.genome_hash = hash_;
    bus::PublishTyped(bus_, ch_.Status(id_), s);
  }
  void TryStep() {
    if (!controller_ || !topology_ || !sensors_) return;
    const std::int64_t t = sensors_->tick;
    std::size_t have = 0;
    for (int n : neighbours_) have += packets_.count({t - 1, n});
    if (t > 0 && have < neighbours_.size() && fault_ != "no-wait") return;
    for (auto it = packets_.begin(); it != packets_.end() && it->first.first < t;) {
      modules::ReceiveHormones(it->second.data(), &*state_);
      it = packets_.erase(it);
    }
    modules::TickInput in;
    in.sensors = sensors_->values.data();
    in.num_neighbours = static_cast<int>(neighbours_.size());
    modules::Step(*controller_, in, &*state_);
    hinge_command_t h{};
    h.utime = bus::NowUtime();
    h.episode = sensors_->episode;
    h.tick = t;
    h.module = id_;
    h.num_actuators = static_cast<std::int16_t>(controller_->num_actuators());
    h.values.assign(state_->actuators.data(), state_->actuators.data() + h.num_actuators);
    h.present.assign(static_cast<std::size_t>(h.num_actuators), true);
    h.target_angle = M_PI / 2 * h.values[0];
    bus::PublishTyped(bus_, ch_.Hinge(id_), h);
    hormone_packet_t p{};
    p.utime = h.utime;
    p.episode = sensors_->episode;
    p.tick = t;
    p.from_module = id_;
    p.num_receivers = static_cast<std::int16_t>(neighbours_.size());
    p.to_modules.assign(neighbours_.begin(), neighbours_.end());
    p.num_hormones = static_cast<std::int16_t>(controller_->num_hormones());
    p.amounts.assign(state_->outflow.begin(), state_->outflow.end());
    bus::PublishTyped(bus_, ch_.Hormone(id_), p);
    sensors_.reset();
    ++step_;
  }

  bus::Bus& bus_;
  const bus::ArenaChannels& ch_;
  int id_;
  std::string fault_;
  std::int64_t episode_ = -1, hash_ = 0;
  int step_ = 0;
  std::unique_ptr<modules::Controller> controller_;
  std::optional<modules::CompartmentState> state_;
  bool topology_ = false;
  std::vector<int> neighbours_;
  std::optional<module_sensors_t> sensors_;
  std::map<std::pair<std::int64_t, int>, std::vector<double>> packets_;
  std::vector<bus::Subscription> hormone_subs_, subs_;
};

}  // namespace

int main(int argc, char** argv) {
  cli::App app{"external-role test peer"};
  std::string role, url, arena;
  int id = 0;
  double seconds = 10;
  app.add_option("--role", role)
      ->required()
      ->check(cli::IsMember({"wrong-hash-module", "button", "drifting-firmware", "stale-tracker",
                             "faulty-module", "faulty-server"}));
  std::string fault;
  app.add_option("--fault", fault)
      ->check(cli::IsMember({"reset-on-genome", "no-wait", "any-episode"}));
  app.add_option("--lcm-url", url)->required();
  app.add_option("--arena", arena)->required();
  app.add_option("--id", id);
  int modules = 3;
  app.add_option("--modules", modules);
  app.add_option("--seconds", seconds);
  if (const int code = ahhs::base::Parse(app, argc, argv); code >= 0) return code;
  bus::LcmBus bus(url);
  const bus::ArenaChannels ch(arena);
  int answered = 0, published = 0;
  std::vector<bus::Subscription> subs;
  std::optional<FaultyModule> faulty;
  if (role == "faulty-module") faulty.emplace(bus, ch, id, fault);
  std::optional<FaultyServer> server;
  if (role == "faulty-server") server.emplace(bus, ch);
  if (role == "wrong-hash-module")
    subs.push_back(
        bus::SubscribeTyped<genome_t>(bus, ch.Genome(), [&](const std::string&, const genome_t& g) {
          module_status_t s{};
          s.utime = bus::NowUtime();
          s.episode = g.episode;
          s.tick = -1;
          s.module = id;
          s.state = module_status_t::READY;
          s.genome_hash = g.genome_hash ^ (std::int64_t{1} << 40);  // seen also in a double
          bus::PublishTyped(bus, ch.Status(id), s);
          ++answered;
        }));
  std::int64_t episode = -1, tick = 0;
  double hinge = 0;
  if (role == "drifting-firmware") {
    subs.push_back(bus::SubscribeTyped<sim_clock_t>(
        bus, ch.SimClock(), [&](const std::string&, const sim_clock_t& c) {
          if (c.run_state == sim_clock_t::RUNNING && episode < 0) episode = c.episode;
        }));
    subs.push_back(bus::SubscribeTyped<hinge_command_t>(
        bus, ch.Hinge(id), [&](const std::string&, const hinge_command_t& h) {
          hinge = h.target_angle;  // whatever the episode: the fault
        }));
  }
  if (role == "stale-tracker")
    subs.push_back(bus::SubscribeTyped<sim_clock_t>(
        bus, ch.SimClock(), [&](const std::string&, const sim_clock_t& c) {
          if (c.run_state != sim_clock_t::RUNNING) return;
          sim_state_t m{};
          m.utime = bus::NowUtime();
          m.episode = 0;  // the fault: not copied from the clock
          m.tick = c.tick;
          m.sim_time = c.sim_time;
          m.num_bodies = static_cast<std::int16_t>(modules);
          for (int k = 0; k < modules; ++k) {
            m.module.push_back(k);
            m.shape.push_back(sim_state_t::SHAPE_BOX);
            for (auto* v : {&m.px, &m.py, &m.pz, &m.qx, &m.qy, &m.qz}) v->push_back(0);
            m.qw.push_back(1);
            for (auto* v : {&m.sx, &m.sy, &m.sz}) v->push_back(0.1);
            m.mass.push_back(0.2);
          }
          bus::PublishTyped(bus, ch.SimState(), m);
          ++published;
        }));
  auto next_reading = std::chrono::steady_clock::now();
  const auto end = std::chrono::steady_clock::now() +
                   std::chrono::milliseconds(static_cast<long>(seconds * 1000));
  while (std::chrono::steady_clock::now() < end) {
    bus.Handle(std::chrono::milliseconds(server ? 1 : 5));
    if (server) server->Tick();
    if (role != "drifting-firmware" || episode < 0 ||
        std::chrono::steady_clock::now() < next_reading)
      continue;
    next_reading += std::chrono::microseconds(1000000 / 19);  // its own timer
    module_sensors_t m{};
    m.utime = bus::NowUtime();
    m.episode = episode;
    m.tick = tick++;
    m.module = id;
    m.num_sensors = 4;
    m.values.assign(4, 0.0);
    m.present.assign(4, true);
    m.hinge_angle = hinge;
    m.num_actuators = 1;
    m.actuator_present = {true};
    bus::PublishTyped(bus, ch.Sensors(id), m);
    ++published;
  }
  if (role == "button") {
    sim_control_t c{};
    c.utime = bus::NowUtime();
    c.command = sim_control_t::CONFIRM;
    bus::PublishTyped(bus, ch.SimControl(), c);
    ++published;
  }
  std::cout << role << ": answered " << answered << " genomes, published " << published
            << " messages\n";
  return 0;
}
