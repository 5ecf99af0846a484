// Test peers for external roles:
//   role_peer --role wrong-hash-module --lcm-url URL --arena A --id N --seconds S
//       a module that answers every GENOME with READY but reports another genome hash
//   role_peer --role firmware --lcm-url URL --arena A --id N --seconds S
//       a gait module's firmware: on every running SIM/CLOCK tick publishes SENSORS (4 proximity
//       slots at 0.5, its hinge at the last HINGE target: an ideal servo) with that episode and
//       tick; counts the HINGE commands it gets and the readings of others on its channel
//   role_peer --role tracker --lcm-url URL --arena A --modules N --seconds S
//       a tracker: on every running or finished SIM/CLOCK tick publishes SIM/STATE with N module
//       bodies 1 cm further along x per tick
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
#include <cmath>
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
  int id = 0, modules = 0;
  double seconds = 10;
  app.add_option("--role", role)
      ->required()
      ->check(CLI::IsMember({"wrong-hash-module", "firmware", "tracker", "button"}));
  app.add_option("--lcm-url", url)->required();
  app.add_option("--arena", arena)->required();
  app.add_option("--id", id);
  app.add_option("--modules", modules);
  app.add_option("--seconds", seconds);
  if (const int code = ahhs::cli::Parse(app, argc, argv); code >= 0) return code;
  bus::LcmBus bus(url);
  const bus::ArenaChannels ch(arena);
  int answered = 0, commands = 0, published = 0, foreign = 0;
  double hinge = 0;
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
  if (role == "firmware") {
    subs.push_back(bus::SubscribeTyped<hinge_command_t>(
        bus, ch.Hinge(id), [&](const std::string&, const hinge_command_t& h) {
          ++commands;
          if (std::isfinite(h.target_angle)) hinge = h.target_angle;
        }));
    subs.push_back(bus::SubscribeTyped<module_sensors_t>(
        bus, ch.Sensors(id), [&](const std::string&, const module_sensors_t& m) {
          if (m.values.empty() || m.values[0] != 0.5) ++foreign;  // not ours: the sim's
        }));
    subs.push_back(bus::SubscribeTyped<sim_clock_t>(
        bus, ch.SimClock(), [&](const std::string&, const sim_clock_t& c) {
          if (c.run_state != sim_clock_t::RUNNING) return;
          module_sensors_t m{};
          m.utime = bus::NowUtime();
          m.episode = c.episode;  // copied from the clock, as docs/hardware.md says
          m.tick = c.tick;
          m.module = id;
          m.sim_time = c.sim_time;
          m.num_sensors = 4;
          m.values.assign(4, 0.5);
          m.present.assign(4, true);
          m.hinge_angle = hinge;
          m.num_actuators = 1;
          m.actuator_present = {true};
          bus::PublishTyped(bus, ch.Sensors(id), m);
          ++published;
        }));
  }
  if (role == "tracker")
    subs.push_back(bus::SubscribeTyped<sim_clock_t>(
        bus, ch.SimClock(), [&](const std::string&, const sim_clock_t& c) {
          if (c.run_state != sim_clock_t::RUNNING && c.run_state != sim_clock_t::FINISHED) return;
          sim_state_t m{};
          m.utime = bus::NowUtime();
          m.episode = c.episode;
          m.tick = c.tick;
          m.sim_time = c.sim_time;
          m.num_bodies = static_cast<std::int16_t>(modules);
          for (int k = 0; k < modules; ++k) {
            m.module.push_back(k);
            m.shape.push_back(sim_state_t::SHAPE_BOX);
            m.px.push_back(0.01 * static_cast<double>(c.tick) - 0.1 * k);
            m.py.push_back(0);
            m.pz.push_back(0.05);
            m.qw.push_back(1);
            m.qx.push_back(0);
            m.qy.push_back(0);
            m.qz.push_back(0);
            m.sx.push_back(0.1);
            m.sy.push_back(0.1);
            m.sz.push_back(0.1);
            m.mass.push_back(0.2);
          }
          bus::PublishTyped(bus, ch.SimState(), m);
          ++published;
        }));
  const auto end = std::chrono::steady_clock::now() +
                   std::chrono::milliseconds(static_cast<long>(seconds * 1000));
  while (std::chrono::steady_clock::now() < end) bus.Handle(std::chrono::milliseconds(50));
  if (role == "button") {
    sim_control_t c{};
    c.utime = bus::NowUtime();
    c.command = sim_control_t::CONFIRM;
    bus::PublishTyped(bus, ch.SimControl(), c);
    ++published;
  }
  std::cout << role << ": answered " << answered << " genomes, published " << published
            << " messages, received " << commands << " hinge commands and " << foreign
            << " readings of others\n";
  return 0;
}
