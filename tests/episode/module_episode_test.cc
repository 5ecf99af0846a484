// What "a message of a new episode resets the module" means (docs/protocol.md, "The module's
// side"): a GENOME or TOPOLOGY whose episode is any other id than the current one -- larger or
// smaller -- starts that episode from rest; SENSORS and HORMONE of another episode never do (they
// are dropped and counted).
#include <ahhs/module_status_t.hpp>
#include <catch2/catch.hpp>
#include <cmath>

#include "bus/open_bus.h"
#include "bus/typed.h"
#include "modules/core/variation.h"
#include "modules/node/genome_codec.h"
#include "modules/node/module_node.h"
#include "tests/fixtures/messages.h"

using namespace ahhs;
using namespace std::chrono_literals;

namespace {

struct OneModule {
  OneModule() : owner(bus::OpenBus("inproc://")), node(owner.get(), Options()) {
    modules::Rng rng(3);
    genome = modules::RandomGenome({modules::Variant::kAhhs2, 3, 5, 4, 1}, rng);
  }
  static modules::ModuleNodeOptions Options() {
    modules::ModuleNodeOptions o;
    o.id = 0;
    return o;
  }
  void Genome(std::int64_t episode) {
    bus::PublishTyped(*owner, "AHHS/GENOME", modules::GenomeMessage(genome, episode));
    Poll();
  }
  void Topology(std::int64_t episode) {
    topology_t t = testing::Fixture<topology_t>();
    t.episode = episode;
    t.num_modules = 1;
    t.num_links = 0;  // alone: a tick needs its SENSORS only
    t.module_a.clear();
    t.port_a.clear();
    t.module_b.clear();
    t.port_b.clear();
    bus::PublishTyped(*owner, "AHHS/TOPOLOGY", t);
    Poll();
  }
  void Sensors(std::int64_t episode, std::int32_t tick) {
    module_sensors_t s = testing::Fixture<module_sensors_t>();
    s.episode = episode;
    s.tick = tick;
    s.module = 0;
    s.num_actuators = 1;
    s.actuator_present = {true};
    bus::PublishTyped(*owner, "AHHS/MODULE0/SENSORS", s);
    Poll();
  }
  void Poll() {
    for (int k = 0; k < 5; ++k) node.Poll(0us);
  }
  std::unique_ptr<bus::Bus> owner;
  modules::ModuleNode node;
  modules::Genome genome;
};

}  // namespace

TEST_CASE("any other episode id in GENOME or TOPOLOGY resets the module, a smaller one too") {
  OneModule m;
  m.Genome(10);
  m.Topology(10);
  REQUIRE(m.node.ready());
  m.Sensors(10, 0);
  m.Sensors(10, 1);
  CHECK(m.node.next_tick() == 2);
  // SENSORS of another episode, earlier or later, are dropped and change nothing.
  const auto dropped = m.node.stats().dropped_messages;
  m.Sensors(9, 2);
  m.Sensors(11, 2);
  CHECK(m.node.episode() == 10);
  CHECK(m.node.next_tick() == 2);
  CHECK(m.node.stats().dropped_messages == dropped + 2);
  // A GENOME of a smaller id is a new episode: from rest, waiting for its TOPOLOGY.
  m.Genome(7);
  CHECK(m.node.episode() == 7);
  CHECK_FALSE(m.node.ready());
  CHECK(m.node.next_tick() == 0);
  m.Topology(7);
  REQUIRE(m.node.ready());
  m.Sensors(7, 0);
  CHECK(m.node.next_tick() == 1);
  CHECK(m.node.state()->ticks == 1);  // a fresh state: its first tick
  // A TOPOLOGY of a larger id starts that episode even before its GENOME: no controller yet.
  m.Topology(12);
  CHECK(m.node.episode() == 12);
  CHECK_FALSE(m.node.ready());
  CHECK(m.node.state() == nullptr);
  m.Genome(12);
  CHECK(m.node.ready());
  // The same episode again is a repeat, not a reset.
  m.Sensors(12, 0);
  m.Genome(12);
  m.Topology(12);
  CHECK(m.node.episode() == 12);
  CHECK(m.node.next_tick() == 1);
}

TEST_CASE("a module says what it dropped, per channel and reason, in its stats and STATUS") {
  OneModule m;
  std::string status;
  auto sub = bus::SubscribeTyped<module_status_t>(
      *m.owner, "AHHS/MODULE0/STATUS",
      [&](const std::string&, const module_status_t& s) { status = s.message; });
  m.Genome(4);
  m.Topology(4);
  module_sensors_t s = testing::Fixture<module_sensors_t>();
  s.episode = 4;
  s.tick = 0;
  s.module = 0;
  s.num_actuators = 1;
  s.actuator_present = {true};
  s.values[1] = std::nan("");
  for (int k = 0; k < 3; ++k) bus::PublishTyped(*m.owner, "AHHS/MODULE0/SENSORS", s);
  m.Sensors(3, 0);
  const std::uint8_t junk[5] = {1, 2, 3, 4, 5};
  m.owner->Publish("AHHS/MODULE0/SENSORS", junk, sizeof junk);
  m.Poll();
  CHECK(m.node.stats().drops ==
        "3 SENSORS (NaN or out of [0, 1]), 1 SENSORS (another episode), 1 SENSORS (undecodable)");
  m.Sensors(4, 0);  // a tick: the module reports RUNNING with its drops
  m.Poll();
  CHECK_THAT(status,
             Catch::Contains("dropped: 3 SENSORS (NaN or out of [0, 1]), 1 SENSORS (another"));
}
