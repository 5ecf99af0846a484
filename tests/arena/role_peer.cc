// Test peers for external roles:
//   role_peer --role wrong-hash-module --lcm-url URL --arena A --id N --seconds S
//       a module that answers every GENOME with READY but reports another genome hash
//   role_peer --role drifting-firmware --lcm-url URL --arena A --id N --seconds S
//       a faulty firmware (ahhs-conformance must fail it): readings on its own 19 Hz timer with
//       its own tick count, and it follows every HINGE whatever its episode
//   role_peer --role stale-tracker --lcm-url URL --arena A --modules N --seconds S
//       a faulty tracker: states on every clock tick but with episode 0 (not copied)
// (Correct firmware and tracker: examples/firmware-c, examples/tracker-c.)
//   role_peer --role button --lcm-url URL --arena A --seconds S
//       an operator's button: SIM/CONTROL CONFIRM once, after S seconds
#include <CLI/CLI.hpp>
#include <ahhs/genome_t.hpp>
#include <ahhs/hinge_command_t.hpp>
#include <ahhs/module_sensors_t.hpp>
#include <ahhs/module_status_t.hpp>
#include <ahhs/sim_clock_t.hpp>
#include <ahhs/sim_control_t.hpp>
#include <ahhs/sim_state_t.hpp>
#include <chrono>
#include <iostream>
#include <vector>

#include "bus/channels.h"
#include "bus/cli.h"
#include "bus/lcm_bus.h"
#include "bus/typed.h"

using namespace ahhs;

int main(int argc, char** argv) {
  CLI::App app{"external-role test peer"};
  std::string role, url, arena;
  int id = 0;
  double seconds = 10;
  app.add_option("--role", role)
      ->required()
      ->check(CLI::IsMember({"wrong-hash-module", "button", "drifting-firmware", "stale-tracker"}));
  app.add_option("--lcm-url", url)->required();
  app.add_option("--arena", arena)->required();
  app.add_option("--id", id);
  int modules = 3;
  app.add_option("--modules", modules);
  app.add_option("--seconds", seconds);
  if (const int code = ahhs::cli::Parse(app, argc, argv); code >= 0) return code;
  bus::LcmBus bus(url);
  const bus::ArenaChannels ch(arena);
  int answered = 0, published = 0;
  std::vector<bus::Subscription> subs;
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
    bus.Handle(std::chrono::milliseconds(5));
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
