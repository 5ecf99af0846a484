// The sim node and one module node per compartment, all in one process on one bus (LCM's
// memq:// and our inproc://), run an episode in lockstep; the result equals the plain in-process
// loop (Scenario + Organism) to the bit. This is the fused arena's promise: the nodes add
// transport, never arithmetic.
#include <ahhs/module_status_t.hpp>
#include <catch2/catch.hpp>
#include <thread>

#include "bus/lcm_bus.h"
#include "bus/open_bus.h"
#include "episode/arena/launcher_role.h"
#include "episode/fitness/fitness_node.h"
#include "modules/core/organism.h"
#include "modules/core/variation.h"
#include "modules/node/genome_codec.h"
#include "modules/node/module_node.h"
#include "sim/node/sim_node.h"
#include "tests/episode/direct_loop.h"

using namespace ahhs;
using namespace std::chrono_literals;
using ahhs::testing::ConfigOf;
using ahhs::testing::DirectFitness;
using ahhs::testing::Episode;

namespace {

// Late copies of the handshake, published once the sim is at tick `late_tick` (none if < 0):
// RESET and GENOME again, and a GENOME with other rules for the same episode.
struct LateRepeats {
  int late_tick = -1;
  const modules::Genome* other_genome = nullptr;
};

// A module that stops (is not polled) for `wall` at the sim's tick `at_tick` (none if < 0), as a
// descheduled or SIGSTOPped process would; and the timeouts (0 = exact lockstep).
struct Stall {
  int module = 1;
  int at_tick = -1;
  std::chrono::milliseconds wall{0};
  std::chrono::milliseconds lockstep_timeout{2000};
  std::chrono::milliseconds hormone_timeout{500};
};

double FusedFitness(const std::string& url, const Episode& e, const modules::Genome& genome,
                    sim::SimNodeStats* sim_stats, const LateRepeats& late = {},
                    const Stall& stall = {}, std::uint64_t* missing_packets = nullptr) {
  auto bus_owner = bus::OpenBus(url);
  bus::Bus& bus = *bus_owner;
  sim::SimNodeOptions sim_options;
  sim_options.lockstep_timeout = stall.lockstep_timeout;
  sim::SimNode sim_node(&bus, sim_options);
  std::vector<std::unique_ptr<modules::ModuleNode>> nodes;
  for (int m = 0; m < e.modules; ++m) {
    modules::ModuleNodeOptions o;
    o.id = m;
    o.hormone_timeout = stall.hormone_timeout;
    nodes.push_back(std::make_unique<modules::ModuleNode>(&bus, o));
  }
  std::chrono::steady_clock::time_point stall_end{};
  auto poll_all = [&] {
    sim_node.Poll(0us);
    if (stall.at_tick >= 0 && stall_end == std::chrono::steady_clock::time_point{} &&
        sim_node.scenario() && sim_node.scenario()->tick() == stall.at_tick)
      stall_end = std::chrono::steady_clock::now() + stall.wall;
    const bool stalled = std::chrono::steady_clock::now() < stall_end;
    for (int m = 0; m < e.modules; ++m)
      if (!(stalled && m == stall.module)) nodes[static_cast<std::size_t>(m)]->Poll(0us);
  };
  const std::int64_t episode = 1000 + e.seed;
  sim_control_t c{};
  c.episode = episode;
  c.seed = e.seed;
  c.scenario = e.scenario;
  c.num_modules = e.modules;
  c.duration = e.duration;
  c.command = sim_control_t::RESET;
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", c);
  bus::PublishTyped(bus, "AHHS/GENOME", modules::GenomeMessage(genome, episode));
  // Handshake: every module READY before START.
  for (int k = 0; k < 100; ++k) {
    poll_all();
    if (std::all_of(nodes.begin(), nodes.end(), [](const auto& n) { return n->ready(); })) break;
  }
  REQUIRE(std::all_of(nodes.begin(), nodes.end(), [](const auto& n) { return n->ready(); }));
  c.command = sim_control_t::START;
  bus::PublishTyped(bus, "AHHS/SIM/CONTROL", c);
  bool repeated = false;
  for (int k = 0; k < 10000000 && sim_node.phase() != sim::SimNode::Phase::kFinished &&
                  sim_node.phase() != sim::SimNode::Phase::kFailed;
       ++k) {
    if (!repeated && late.late_tick >= 0 && sim_node.scenario()->tick() == late.late_tick) {
      repeated = true;
      c.command = sim_control_t::RESET;
      bus::PublishTyped(bus, "AHHS/SIM/CONTROL", c);
      bus::PublishTyped(bus, "AHHS/GENOME", modules::GenomeMessage(genome, episode));
      if (late.other_genome)
        bus::PublishTyped(bus, "AHHS/GENOME", modules::GenomeMessage(*late.other_genome, episode));
    }
    poll_all();
  }
  REQUIRE(sim_node.phase() == sim::SimNode::Phase::kFinished);
  if (missing_packets) *missing_packets = 0;
  for (auto& n : nodes) {
    if (missing_packets) {
      *missing_packets += n->stats().missing_packets;
      continue;
    }
    CHECK(n->stats().missing_packets == 0);
    // A different genome for a running episode is ignored and counted; a repeat is not an error.
    CHECK(n->stats().dropped_messages == (late.other_genome ? 1u : 0u));
  }
  *sim_stats = sim_node.stats();
  return sim_node.scenario()->Fitness();
}

}  // namespace

TEST_CASE("fused arena equals the in-process loop, bit for bit", "[arena]") {
  const Episode episodes[] = {{"pendulum", 2, 30.0, 1},
                              {"pendulum", 2, 30.0, 2},
                              {"gait", 5, 10.0, 3},
                              {"gait", 3, 10.0, 4}};
  for (const auto& e : episodes) {
    for (auto variant : {modules::Variant::kAhhs2, modules::Variant::kAhhs1}) {
      auto scenario = sim::MakeScenario(ConfigOf(e));
      modules::Rng rng(static_cast<std::uint64_t>(e.seed) * 10 + static_cast<int>(variant));
      const modules::Genome genome =
          modules::RandomGenome({variant, 5, variant == modules::Variant::kAhhs2 ? 15 : 40,
                                 scenario->num_sensors(), scenario->num_actuators()},
                                rng);
      const double direct = DirectFitness(e, genome);
      for (const char* url : {"inproc://", "memq://"}) {
        INFO(e.scenario << " seed " << e.seed << " " << modules::VariantName(variant) << " on "
                        << url);
        sim::SimNodeStats stats;
        CHECK(FusedFitness(url, e, genome, &stats) == direct);
        CHECK(stats.missed_commands == 0);
        CHECK(stats.dropped_messages == 0);
      }
    }
  }
}

TEST_CASE("exact lockstep: a module stopped longer than any timeout changes nothing",
          "[arena][wall]") {
  // A process that is descheduled (or SIGSTOPped) for longer than the lockstep timeout: with
  // timeouts the sim goes on without its command and the result changes; exact lockstep waits.
  const Episode e{"gait", 4, 3.0, 8};
  modules::Rng rng(88);
  const modules::Genome genome =
      modules::RandomGenome({modules::Variant::kAhhs2, 3, 12, 4, 1}, rng);
  const double direct = DirectFitness(e, genome);
  for (const char* url : {"inproc://", "memq://"}) {
    INFO(url);
    sim::SimNodeStats stats;
    std::uint64_t missing = 0;
    // 600 ms: a stop far beyond the timeouts below even when this process itself gets no CPU
    // for a while (100 ms once went unnoticed under a sanitizer build beside other tests).
    Stall exact{1, 10, 600ms, 0ms, 0ms};
    CHECK(FusedFitness(url, e, genome, &stats, {}, exact, &missing) == direct);
    CHECK(stats.missed_commands == 0);
    CHECK(missing == 0);
    Stall timeouts{1, 10, 600ms, 20ms, 5ms};  // the same stop with timeouts far below it
    CHECK(FusedFitness(url, e, genome, &stats, {}, timeouts, &missing) != direct);
    CHECK(stats.missed_commands > 0);
  }
}

TEST_CASE("an exact lockstep episode that stalls fails after the stall timeout, naming the tick",
          "[arena][wall]") {
  // The launcher's side: module 1 stops for good at tick 10 (a lost datagram in exact lockstep
  // has the same effect). The episode must fail as an arena error, not hang, not score.
  bus::LcmBus bus("memq://");
  sim::SimNodeOptions sim_options;
  sim_options.lockstep_timeout = 0ms;
  sim::SimNode sim_node(&bus, sim_options);
  episode::FitnessNode fitness_node(&bus, "AHHS");
  std::vector<std::unique_ptr<modules::ModuleNode>> nodes;
  for (int m = 0; m < 3; ++m) {
    modules::ModuleNodeOptions o;
    o.id = m;
    o.hormone_timeout = 0ms;
    nodes.push_back(std::make_unique<modules::ModuleNode>(&bus, o));
  }
  episode::EpisodeSpec spec;
  spec.config = ConfigOf({"gait", 3, 5.0, 1});
  modules::Rng rng(9);
  spec.genome = modules::RandomGenome({modules::Variant::kAhhs2, 3, 8, 4, 1}, rng);
  spec.stall_timeout = 1s;
  auto pump = [&](std::chrono::microseconds) {
    bus.Handle(0us);
    sim_node.Process();
    fitness_node.Poll(0us);
    for (int m = 0; m < 3; ++m)
      if (m != 1 || !sim_node.scenario() || sim_node.scenario()->tick() < 10)
        nodes[static_cast<std::size_t>(m)]->Process();
    std::this_thread::sleep_for(1ms);
  };
  const auto start = std::chrono::steady_clock::now();
  const episode::EpisodeResult r =
      episode::RunEpisode(bus, spec, pump, [](std::string*) { return true; });
  const auto waited = std::chrono::steady_clock::now() - start;
  CHECK_FALSE(r.ok);
  CHECK_FALSE(r.episode_failed);  // the arena's failure, not the genome's
  CHECK(r.error.find("stalled: no progress for 1 s") != std::string::npos);
  CHECK(waited >= 1s);
  CHECK(waited < 10s);
  CHECK(sim_node.stats().missed_commands == 0);
}

TEST_CASE("late copies of RESET and GENOME change nothing in a running episode", "[arena]") {
  // The launcher repeats RESET and GENOME until everyone answered; over a network a repeat can
  // arrive after START. Rebuilding the controller from it would wipe the module's hormones
  // mid-episode.
  const Episode e{"gait", 4, 5.0, 6};
  auto scenario = sim::MakeScenario(ConfigOf(e));
  modules::Rng rng(66);
  const modules::Genome genome =
      modules::RandomGenome({modules::Variant::kAhhs2, 5, 20, 4, 1}, rng);
  const modules::Genome other = modules::RandomGenome({modules::Variant::kAhhs2, 5, 20, 4, 1}, rng);
  const double direct = DirectFitness(e, genome);
  for (const char* url : {"inproc://", "memq://"}) {
    INFO(url);
    sim::SimNodeStats stats;
    CHECK(FusedFitness(url, e, genome, &stats, {7, &other}) == direct);
    CHECK(stats.ticks == 100);
    CHECK(stats.dropped_messages == 1);  // the late RESET
  }
}

TEST_CASE("genome messages round-trip and bad ones are refused", "[arena]") {
  modules::Rng rng(5);
  for (auto variant : {modules::Variant::kAhhs1, modules::Variant::kAhhs2}) {
    const auto g = modules::RandomGenome({variant, 5, 20, 4, 1}, rng);
    auto msg = modules::GenomeMessage(g, 1);
    modules::Genome back;
    REQUIRE(modules::GenomeFromMessage(msg, &back).empty());
    CHECK(modules::GenomeHash(back) == modules::GenomeHash(g));
    msg.rule_values[3] += 0.5;  // breaks the weights (AHHS2) or the tau range / hash (AHHS1)
    CHECK_FALSE(modules::GenomeFromMessage(msg, &back).empty());
    msg = modules::GenomeMessage(g, 1);
    msg.fields_per_rule = 6;
    CHECK_THAT(modules::GenomeFromMessage(msg, &back), Catch::Contains("wrong size"));
  }
}
