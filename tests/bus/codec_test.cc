#include "bus/codec.h"

#include <catch2/catch.hpp>
#include <random>

#include "bus/typed.h"
#include "tests/fixtures/messages.h"

using ahhs::bus::Decode;
using ahhs::bus::Encode;

TEMPLATE_TEST_CASE("decode rejects truncated, extended and wrong-type bytes", "[codec]",
                   ahhs::module_sensors_t, ahhs::hinge_command_t, ahhs::hormone_packet_t,
                   ahhs::module_status_t, ahhs::topology_t, ahhs::sim_control_t, ahhs::sim_clock_t,
                   ahhs::sim_state_t, ahhs::genome_t, ahhs::fitness_t, ahhs::eval_request_t,
                   ahhs::eval_result_t, ahhs::worker_status_t, ahhs::genome_chunk_t,
                   ahhs::genome_want_t) {
  const auto bytes = Encode(ahhs::testing::Fixture<TestType>());
  TestType out;
  REQUIRE(Decode(bytes.data(), bytes.size(), &out));

  // Every proper prefix is rejected.
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    INFO("prefix of " << n << " bytes");
    CHECK_FALSE(Decode(bytes.data(), n, &out));
  }
  // Trailing garbage is rejected: one datagram is exactly one message.
  auto longer = bytes;
  longer.push_back(0x55);
  CHECK_FALSE(Decode(longer.data(), longer.size(), &out));
  // A flipped fingerprint bit is another type.
  auto wrong = bytes;
  wrong[3] ^= 0x10;
  CHECK_FALSE(Decode(wrong.data(), wrong.size(), &out));
  CHECK_FALSE(Decode(nullptr, 100, &out));
}

TEST_CASE("another type's bytes do not decode", "[codec]") {
  const auto hinge = Encode(ahhs::testing::Fixture<ahhs::hinge_command_t>());
  ahhs::module_sensors_t sensors;
  CHECK_FALSE(Decode(hinge.data(), hinge.size(), &sensors));
}

TEST_CASE("hostile array lengths neither crash nor allocate wildly", "[codec]") {
  auto bytes = Encode(ahhs::testing::Fixture<ahhs::hormone_packet_t>());
  ahhs::hormone_packet_t out;
  // num_receivers sits at offset 36 and num_hormones at 46 (see the layout test): make each
  // negative, then huge.
  for (std::size_t at : {36, 46}) {
    auto copy = bytes;
    copy[at] = 0xff;
    copy[at + 1] = 0xfe;
    CHECK_FALSE(Decode(copy.data(), copy.size(), &out));
    copy[at] = 0x7f;
    copy[at + 1] = 0xff;
    CHECK_FALSE(Decode(copy.data(), copy.size(), &out));
  }

  // A string length field that lies (module_status_t.message is the last field).
  auto status = Encode(ahhs::testing::Fixture<ahhs::module_status_t>());
  ahhs::module_status_t s;
  const std::size_t len_at = status.size() - 3 - 4;  // "ok\0" preceded by int32 length
  for (std::uint32_t lie : {0u, 0x7fffffffu, 0x80000000u, 0xffffffffu, 100u}) {
    auto copy = status;
    for (int k = 0; k < 4; ++k) copy[len_at + k] = static_cast<std::uint8_t>(lie >> (24 - 8 * k));
    INFO("string length " << lie);
    CHECK_FALSE(Decode(copy.data(), copy.size(), &s));
  }
}

TEST_CASE("random garbage never decodes and never crashes", "[codec]") {
  std::mt19937_64 rng(20101001);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<int> length(0, 600);
  const auto header = Encode(ahhs::testing::Fixture<ahhs::genome_t>());
  int decoded = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    std::vector<std::uint8_t> junk(static_cast<std::size_t>(length(rng)));
    for (auto& b : junk) b = static_cast<std::uint8_t>(byte(rng));
    // Half of the trials keep the right fingerprint so the payload decoder is exercised.
    if (trial % 2 == 0 && junk.size() >= 8)
      std::copy(header.begin(), header.begin() + 8, junk.begin());
    ahhs::genome_t g;
    decoded += Decode(junk.data(), junk.size(), &g) ? 1 : 0;
  }
  // Exactly-consumed random payloads are astronomically unlikely.
  CHECK(decoded == 0);
}

namespace {
// Decodes `full` and then `empty` into one object, as a typed subscription does.
template <class Msg>
Msg DecodeTwiceIntoOne(const Msg& full, const Msg& empty) {
  Msg reused;
  const auto a = Encode(full), b = Encode(empty);
  ahhs::bus::ClearForDecode(&reused);
  REQUIRE(Decode(a.data(), a.size(), &reused));
  ahhs::bus::ClearForDecode(&reused);
  REQUIRE(Decode(b.data(), b.size(), &reused));
  return reused;
}
}  // namespace

TEST_CASE("a reused message keeps nothing of the previous one (zero-length arrays)", "[codec]") {
  // lcm-gen's decoder does not touch an array whose length is 0: ClearForDecode must empty
  // every array of the per-tick types, or a receiver would see the last message's elements.
  auto hormone = ahhs::testing::Fixture<ahhs::hormone_packet_t>();
  auto no_hormone = hormone;
  no_hormone.num_receivers = 0;
  no_hormone.to_modules.clear();
  no_hormone.num_hormones = 0;
  no_hormone.amounts.clear();
  const auto h = DecodeTwiceIntoOne(hormone, no_hormone);
  CHECK(h.to_modules.empty());
  CHECK(h.amounts.empty());

  auto hinge = ahhs::testing::Fixture<ahhs::hinge_command_t>();
  auto no_hinge = hinge;
  no_hinge.num_actuators = 0;
  no_hinge.values.clear();
  no_hinge.present.clear();
  const auto c = DecodeTwiceIntoOne(hinge, no_hinge);
  CHECK(c.values.empty());
  CHECK(c.present.empty());

  auto sensors = ahhs::testing::Fixture<ahhs::module_sensors_t>();
  auto no_sensors = sensors;
  no_sensors.num_sensors = 0;
  no_sensors.values.clear();
  no_sensors.present.clear();
  no_sensors.num_actuators = 0;
  no_sensors.actuator_present.clear();
  const auto s = DecodeTwiceIntoOne(sensors, no_sensors);
  CHECK(s.values.empty());
  CHECK(s.present.empty());
  CHECK(s.actuator_present.empty());

  auto state = ahhs::testing::Fixture<ahhs::sim_state_t>();
  REQUIRE(state.num_bodies > 0);
  ahhs::sim_state_t no_state = state;
  no_state.num_bodies = 0;
  for (auto* v :
       {&no_state.px, &no_state.py, &no_state.pz, &no_state.qw, &no_state.qx, &no_state.qy,
        &no_state.qz, &no_state.sx, &no_state.sy, &no_state.sz, &no_state.mass})
    v->clear();
  no_state.module.clear();
  no_state.shape.clear();
  const auto st = DecodeTwiceIntoOne(state, no_state);
  for (const auto* v :
       {&st.px, &st.py, &st.pz, &st.qw, &st.qx, &st.qy, &st.qz, &st.sx, &st.sy, &st.sz, &st.mass})
    CHECK(v->empty());
  CHECK(st.module.empty());
  CHECK(st.shape.empty());
}
