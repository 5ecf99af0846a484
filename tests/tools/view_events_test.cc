// ahhs-view's translation of arena messages into what its page draws: recordings built from a
// log's messages put each module's data and the running fitness on the frame of their tick.
#include "tools/view/view_events.h"

#include <catch2/catch.hpp>
#include <limits>

using ahhs::fitness_t;
using ahhs::module_trace_t;
using ahhs::sim_state_t;
using ahhs::view::ArenaChannel;
using ahhs::view::ClassifyChannel;
using ahhs::view::RecordingBuilder;
using ahhs::view::Round;

namespace {

template <class Msg>
std::vector<std::uint8_t> Encode(const Msg& m) {
  std::vector<std::uint8_t> b(static_cast<std::size_t>(m.getEncodedSize()));
  m.encode(b.data(), 0, static_cast<int>(b.size()));
  return b;
}

sim_state_t State(std::int64_t tick, double x) {
  sim_state_t s{};
  s.episode = 7;
  s.tick = tick;
  s.sim_time = 0.05 * static_cast<double>(tick);
  s.num_bodies = 1;
  s.module = {0};
  s.shape = {sim_state_t::SHAPE_BOX};
  s.px = {x};
  s.py = {0};
  s.pz = {0.025};
  s.qw = {1};
  s.qx = s.qy = s.qz = {0};
  s.sx = {0.05};
  s.sy = s.sz = {0.1};
  s.mass = {0.5};
  return s;
}

module_trace_t Trace(std::int64_t tick, double hormone) {
  module_trace_t t{};
  t.episode = 7;
  t.tick = tick;
  t.module = 0;
  t.num_hormones = 2;
  t.hormones = {hormone, 0};
  t.num_actuators = 1;
  t.actuators = {-0.5};
  t.hinge_angle = 0.25;
  return t;
}

}  // namespace

TEST_CASE("values sent to the page keep six significant digits") {
  CHECK(Round(0.123456789) == 0.123457);
  CHECK(Round(-1234567.8) == -1234570);
  CHECK(Round(0) == 0);
  CHECK(Round(std::numeric_limits<double>::quiet_NaN()) == 0);
}

TEST_CASE("arena channels are told apart by arena, kind and module") {
  CHECK(ClassifyChannel("A", "A/SIM/STATE").kind == ArenaChannel::kState);
  CHECK(ClassifyChannel("A", "B/SIM/STATE").kind == ArenaChannel::kOther);
  const ArenaChannel t = ClassifyChannel("A", "A/MODULE12/TRACE");
  CHECK(t.kind == ArenaChannel::kTrace);
  CHECK(t.module == 12);
  CHECK(ClassifyChannel("A", "A/MODULE1/HORMONE").kind == ArenaChannel::kOther);
  CHECK(ahhs::view::ArenaOfStateChannel("arena-1/SIM/STATE") == "arena-1");
  CHECK(ahhs::view::ArenaOfStateChannel("SIM/STATE").empty());
}

TEST_CASE("a recording puts each tick's module data and fitness on the frame of that tick") {
  RecordingBuilder b("A");
  fitness_t f{};
  f.episode = 7;
  f.status = fitness_t::OK;
  for (std::int64_t tick = 0; tick < 3; ++tick) {
    b.Add("A/MODULE0/TRACE", Encode(Trace(tick, 0.1 * static_cast<double>(tick))));
    b.Add("A/SIM/STATE", Encode(State(tick + 1, 0.01 * static_cast<double>(tick))));
    f.tick = tick + 1;
    f.fitness = 0.5 * static_cast<double>(tick);
    f.is_final = tick == 2;
    b.Add("A/FITNESS", Encode(f));
  }
  b.Add("OTHER/SIM/STATE", Encode(State(9, 9)));          // another arena: ignored
  b.Add("A/SIM/STATE", std::vector<std::uint8_t>(5, 0));  // garbage: counted
  const auto recordings = b.Finish();
  CHECK(b.undecodable() == 1);
  REQUIRE(recordings.size() == 1);
  const auto& r = recordings[0];
  CHECK(r["episode"] == 7);
  CHECK(r["period"] == 0.05);
  CHECK(r["bodies"]["size"] == ahhs::view::Json::array({0.05, 0.1, 0.1}));
  REQUIRE(r["frames"].size() == 3);
  const auto& f2 = r["frames"][2];
  CHECK(f2["tick"] == 3);
  CHECK(f2["pose"][0] == 0.02);
  CHECK(f2["fitness"] == 1.0);
  CHECK(f2["mods"][0]["h"][0] == 0.2);
  CHECK(f2["mods"][0]["a"][0] == -0.5);
  CHECK(f2["mods"][0]["g"] == 0.25);
  CHECK(r["final"]["fitness"] == 1.0);
  CHECK(r["final"]["ok"] == true);
}
