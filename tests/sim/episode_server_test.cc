// The episode server of a physical organism (sim/node/episode_server.h) over memq://.
#include "sim/node/episode_server.h"

#include <ahhs/sim_clock_t.hpp>
#include <ahhs/sim_control_t.hpp>
#include <ahhs/topology_t.hpp>
#include <catch2/catch.hpp>
#include <thread>
#include <vector>

#include "bus/lcm_bus.h"
#include "sim/core/constants.h"
#include "sim/node/sim_codec.h"

using namespace ahhs;

namespace {
struct Rig {
  bus::LcmBus bus{"memq://"};
  std::vector<std::string> said;
  std::vector<sim_clock_t> clocks;
  std::vector<topology_t> topologies;
  sim::EpisodeServer server;
  bus::Subscription clock_sub, topology_sub;
  explicit Rig(bool confirm)
      : server(&bus, {"T", confirm, std::chrono::milliseconds(100)},
               [this](const std::string& line) { said.push_back(line); }) {
    clock_sub = bus::SubscribeTyped<sim_clock_t>(
        bus, "T/SIM/CLOCK",
        [this](const std::string&, const sim_clock_t& c) { clocks.push_back(c); });
    topology_sub = bus::SubscribeTyped<topology_t>(
        bus, "T/TOPOLOGY",
        [this](const std::string&, const topology_t& t) { topologies.push_back(t); });
  }
  void Send(std::int8_t command, std::int64_t episode, bool realtime = true,
            const sim::Envelope& envelope = {}, const std::string& physics = "") {
    sim_control_t c{};
    c.command = command;
    c.episode = episode;
    sim::ScenarioConfig config =
        sim::MakeScenarioConfig(sim::ScenarioKind::kGait, sim::DockingKind::kDamped, 3, 0.5);
    config.envelope = envelope;
    config.physics = physics;
    sim::ScenarioToWire(config, &c);
    c.clock_mode = realtime ? sim_control_t::MODE_REALTIME : sim_control_t::MODE_LOCKSTEP;
    bus::PublishTyped(bus, "T/SIM/CONTROL", c);
  }
  void PollFor(int ms) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
    while (std::chrono::steady_clock::now() < end) server.Poll(std::chrono::milliseconds(2));
  }
};
}  // namespace

TEST_CASE("the episode server runs an episode's ticks at wall-clock pace with the chain topology") {
  Rig rig(false);
  rig.Send(sim_control_t::RESET, 7);
  rig.PollFor(5);
  REQUIRE(rig.server.phase() == sim::EpisodeServer::Phase::kReady);
  REQUIRE(rig.topologies.size() == 1);
  CHECK(rig.topologies[0].num_modules == 3);
  CHECK(rig.topologies[0].module_a == std::vector<std::int32_t>{0, 1});
  CHECK(rig.topologies[0].module_b == std::vector<std::int32_t>{1, 2});
  REQUIRE(rig.clocks.size() == 1);
  CHECK(rig.clocks[0].run_state == sim_clock_t::RESET);
  const auto start = std::chrono::steady_clock::now();
  rig.Send(sim_control_t::START, 7);
  while (rig.server.phase() != sim::EpisodeServer::Phase::kFinished &&
         std::chrono::steady_clock::now() - start < std::chrono::seconds(3))
    rig.server.Poll(std::chrono::milliseconds(2));
  const double took =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CHECK(rig.server.phase() == sim::EpisodeServer::Phase::kFinished);
  CHECK(took >= 0.45);  // 10 ticks of 50 ms
  rig.bus.Handle(std::chrono::milliseconds(0));
  std::vector<std::int64_t> running;
  int finished = 0;
  for (const auto& c : rig.clocks) {
    CHECK(c.episode == 7);
    CHECK(c.clock_mode == sim_clock_t::MODE_REALTIME);
    if (c.run_state == sim_clock_t::RUNNING) running.push_back(c.tick);
    if (c.run_state == sim_clock_t::FINISHED) {
      ++finished;
      CHECK(c.tick == 10);
      CHECK(c.sim_time == Approx(0.5));
    }
  }
  CHECK(running == std::vector<std::int64_t>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
  CHECK(finished == 3);
}

TEST_CASE("the episode server waits for the operator, and gives an episode up without one") {
  Rig rig(true);
  rig.Send(sim_control_t::RESET, 8);
  rig.PollFor(20);
  CHECK(rig.server.phase() == sim::EpisodeServer::Phase::kAwaitingConfirm);
  CHECK(rig.clocks.empty());  // no answer to the launcher yet
  sim_control_t confirm{};
  confirm.command = sim_control_t::CONFIRM;
  bus::PublishTyped(rig.bus, "T/SIM/CONTROL", confirm);  // a button: any episode
  rig.PollFor(5);
  CHECK(rig.server.phase() == sim::EpisodeServer::Phase::kReady);
  REQUIRE(rig.clocks.size() == 1);
  rig.Send(sim_control_t::STOP, 8);
  rig.PollFor(5);
  CHECK(rig.server.phase() == sim::EpisodeServer::Phase::kFinished);

  rig.Send(sim_control_t::RESET, 9);
  rig.PollFor(150);  // past the 100 ms confirmation timeout
  CHECK(rig.server.phase() == sim::EpisodeServer::Phase::kFinished);
  CHECK(rig.server.episode() == 8);
  CHECK(rig.said.back().find("episode 9: no confirmation within") != std::string::npos);
  rig.Send(sim_control_t::RESET, 9);  // the launcher's repeats are ignored now
  rig.PollFor(5);
  CHECK(rig.server.phase() == sim::EpisodeServer::Phase::kFinished);

  rig.server.Confirm();  // confirmed ahead: the next episode goes at once
  rig.Send(sim_control_t::RESET, 10);
  rig.PollFor(5);
  CHECK(rig.server.phase() == sim::EpisodeServer::Phase::kReady);
  CHECK(rig.server.episode() == 10);
}

TEST_CASE("the episode server refuses lockstep and STEP: a physical organism runs in real time") {
  Rig rig(false);
  rig.Send(sim_control_t::RESET, 11, /*realtime=*/false);
  rig.PollFor(5);
  CHECK(rig.server.phase() == sim::EpisodeServer::Phase::kIdle);
  CHECK(rig.clocks.empty());
  REQUIRE(rig.said.size() == 1);
  CHECK(rig.said[0].find("real time only") != std::string::npos);
  rig.Send(sim_control_t::RESET, 11, false);  // said once
  rig.PollFor(5);
  CHECK(rig.said.size() == 1);
  rig.Send(sim_control_t::RESET, 12);
  rig.PollFor(5);
  const auto dropped = rig.server.dropped();
  sim_control_t step{};
  step.command = sim_control_t::STEP;
  step.episode = 12;
  step.steps = 3;
  bus::PublishTyped(rig.bus, "T/SIM/CONTROL", step);
  rig.PollFor(5);
  CHECK(rig.server.phase() == sim::EpisodeServer::Phase::kReady);
  CHECK(rig.server.dropped() == dropped + 1);
}

TEST_CASE("the episode server refuses an envelope of noise: the real world is its own",
          "[envelope]") {
  Rig rig(false);
  rig.Send(sim_control_t::RESET, 13, true, sim::EnvelopePreset("paper"));
  rig.PollFor(5);
  CHECK(rig.server.phase() == sim::EpisodeServer::Phase::kIdle);
  REQUIRE(rig.said.size() == 1);
  CHECK(rig.said[0].find("cannot be given an envelope of noise (paper)") != std::string::npos);
}

TEST_CASE("the episode server refuses an earlier physics, and takes this build's by name") {
  Rig rig(false);
  rig.Send(sim_control_t::RESET, 14, true, {}, sim::kGaitChainColdPhysicsVersion);
  rig.PollFor(5);
  CHECK(rig.server.phase() == sim::EpisodeServer::Phase::kIdle);
  REQUIRE(rig.said.size() == 1);
  CHECK(rig.said[0].find("cannot be asked for the earlier physics 2026-12-04") !=
        std::string::npos);
  rig.Send(sim_control_t::RESET, 15);  // names this build's physics
  rig.PollFor(5);
  CHECK(rig.server.phase() == sim::EpisodeServer::Phase::kReady);
}
