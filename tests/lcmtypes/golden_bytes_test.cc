// Golden bytes: the wire format of every message type is pinned. A change to a .lcm file that
// alters the bytes (and so breaks recorded logs and foreign-language peers) fails here.
// After an intended change, regenerate with AHHS_UPDATE_GOLDEN=1 and say so in docs/protocol.md.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "bus/codec.h"
#include "tests/fixtures/messages.h"

namespace {

std::string ToHex(const std::vector<std::uint8_t>& bytes) {
  static const char* digits = "0123456789abcdef";
  std::string hex;
  for (std::size_t k = 0; k < bytes.size(); ++k) {
    hex += digits[bytes[k] >> 4];
    hex += digits[bytes[k] & 15];
    hex += (k % 32 == 31) ? '\n' : ' ';
  }
  if (!hex.empty()) hex.back() = '\n';
  return hex;
}

std::string GoldenPath(const std::string& type_name) {
  const char* src = std::getenv("AHHS_SOURCE_DIR");
  return std::string(src ? src : ".") + "/tests/lcmtypes/golden/" + type_name + ".hex";
}

}  // namespace

TEMPLATE_TEST_CASE("every message type encodes to its golden bytes", "[lcmtypes]",
                   ahhs::module_sensors_t, ahhs::hinge_command_t, ahhs::hormone_packet_t,
                   ahhs::module_status_t, ahhs::topology_t, ahhs::sim_control_t, ahhs::sim_clock_t,
                   ahhs::sim_state_t, ahhs::genome_t, ahhs::fitness_t, ahhs::eval_request_t,
                   ahhs::eval_result_t, ahhs::worker_status_t, ahhs::module_trace_t,
                   ahhs::genome_chunk_t, ahhs::genome_want_t) {
  const TestType msg = ahhs::testing::Fixture<TestType>();
  const auto bytes = ahhs::bus::Encode(msg);
  REQUIRE(bytes.size() == static_cast<std::size_t>(msg.getEncodedSize()));
  const std::string hex = ToHex(bytes);
  const std::string path = GoldenPath(TestType::getTypeName());

  if (std::getenv("AHHS_UPDATE_GOLDEN") != nullptr) {
    std::ofstream(path) << hex;
  }
  std::ifstream in(path);
  REQUIRE(in.good());
  std::stringstream golden;
  golden << in.rdbuf();
  CHECK(hex == golden.str());

  // Every type is well below the 64 kB a UDP datagram (and LCM's fragment-free path) allows.
  CHECK(bytes.size() < 65000);

  // And the golden bytes decode back to the same message.
  TestType decoded;
  REQUIRE(ahhs::bus::Decode(bytes.data(), bytes.size(), &decoded));
  CHECK(ahhs::bus::Encode(decoded) == bytes);
}

TEST_CASE("wire layout of hormone_packet_t matches the LCM spec by hand", "[lcmtypes]") {
  // LCM: 8-byte big-endian fingerprint, then fields in order, big-endian, arrays inline.
  const auto msg = ahhs::testing::Fixture<ahhs::hormone_packet_t>();
  const auto b = ahhs::bus::Encode(msg);
  auto be64 = [&](std::size_t at) {
    std::uint64_t v = 0;
    for (int k = 0; k < 8; ++k) v = (v << 8) | b[at + static_cast<std::size_t>(k)];
    return v;
  };
  REQUIRE(b.size() == 8 + 8 + 8 + 8 + 4 + 2 + 2 * 4 + 2 + 3 * 8);
  CHECK(be64(0) == static_cast<std::uint64_t>(ahhs::hormone_packet_t::getHash()));
  CHECK(be64(8) == 1700000000000003ULL);  // utime
  CHECK(be64(16) == 42U);                 // episode
  CHECK(be64(24) == 7U);                  // tick
  CHECK(b[32] == 0);
  CHECK(b[35] == 1);  // from_module (int32)
  CHECK(b[36] == 0);
  CHECK(b[37] == 2);  // num_receivers (int16)
  CHECK(b[41] == 0);  // to_modules[0] (int32)
  CHECK(b[45] == 2);  // to_modules[1]
  CHECK(b[46] == 0);
  CHECK(b[47] == 3);                         // num_hormones (int16)
  CHECK(be64(48) == 0x3fc0000000000000ULL);  // 0.125 as IEEE-754 double
  CHECK(be64(56) == 0);                      // 0.0
  CHECK(be64(64) == 0x3fe0000000000000ULL);  // 0.5
}
