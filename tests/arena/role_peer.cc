// Test peers for external roles:
//   role_peer --role wrong-hash-module --lcm-url URL --arena A --id N --seconds S
//       a module that answers every GENOME with READY but reports another genome hash
// (Firmware and a tracker: examples/firmware-c, examples/tracker-c.)
//   role_peer --role button --lcm-url URL --arena A --seconds S
//       an operator's button: SIM/CONTROL CONFIRM once, after S seconds
#include <CLI/CLI.hpp>
#include <ahhs/genome_t.hpp>
#include <ahhs/module_status_t.hpp>
#include <ahhs/sim_control_t.hpp>
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
  app.add_option("--role", role)->required()->check(CLI::IsMember({"wrong-hash-module", "button"}));
  app.add_option("--lcm-url", url)->required();
  app.add_option("--arena", arena)->required();
  app.add_option("--id", id);
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
            << " messages\n";
  return 0;
}
