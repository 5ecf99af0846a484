// Text on the wire (bus/wire_text.h): every string field is valid UTF-8 without NUL and at most
// kMaxWireText bytes, checked at decode and at encode, and counted when a send fails.
#include "bus/wire_text.h"

#include <ahhs/genome_t.hpp>
#include <ahhs/hinge_command_t.hpp>
#include <ahhs/hormone_packet_t.hpp>
#include <ahhs/module_sensors_t.hpp>
#include <ahhs/module_trace_t.hpp>
#include <ahhs/sim_clock_t.hpp>
#include <ahhs/sim_state_t.hpp>
#include <ahhs/topology_t.hpp>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "bus/codec.h"
#include "bus/in_process_bus.h"
#include "bus/typed.h"
#include "tests/fixtures/messages.h"

using ahhs::bus::Decode;
using ahhs::bus::Encode;
using ahhs::bus::IsWireText;
using ahhs::bus::kMaxWireText;
using ahhs::bus::ToWireText;

namespace {

// The encoded bytes of `msg` with its string fields' bytes as given, bypassing Encode's check;
// the text "r\x01n" becomes "r\0n" afterwards (lcm-gen's encoder cannot write a NUL inside a
// string: it measures with strlen).
template <class Msg>
std::vector<std::uint8_t> RawEncode(const Msg& msg) {
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(msg.getEncodedSize()));
  REQUIRE(msg.encode(bytes.data(), 0, static_cast<int>(bytes.size())) ==
          static_cast<int>(bytes.size()));
  for (std::size_t k = 1; k + 1 < bytes.size(); ++k)
    if (bytes[k - 1] == 'r' && bytes[k] == 0x01 && bytes[k + 1] == 'n') bytes[k] = 0;
  return bytes;
}

// The number of `string` fields the type's .lcm file declares.
int StringFieldsInLcmFile(const std::string& type) {
  const char* src = std::getenv("AHHS_SOURCE_DIR");
  REQUIRE(src != nullptr);
  std::ifstream in(std::string(src) + "/lcmtypes/" + type + ".lcm");
  REQUIRE(in.good());
  int n = 0;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line.substr(0, line.find("//")));
    std::string first;
    if (words >> first && first == "string") ++n;
  }
  return n;
}

}  // namespace

TEST_CASE("wire text is UTF-8 without NUL and at most 1024 bytes", "[wire_text]") {
  CHECK(IsWireText(""));
  CHECK(IsWireText("gait"));
  CHECK(IsWireText("Kraftübertragung ∑ 😀"));
  CHECK(IsWireText(std::string(kMaxWireText, 'a')));
  CHECK_FALSE(IsWireText(std::string(kMaxWireText + 1, 'a')));
  CHECK_FALSE(IsWireText(std::string("ab\0cd", 5)));
  CHECK_FALSE(IsWireText("\xff"));
  CHECK_FALSE(IsWireText("\xc3"));              // cut short
  CHECK_FALSE(IsWireText("\xc0\xaf"));          // overlong '/'
  CHECK_FALSE(IsWireText("\xed\xa0\x80"));      // a UTF-16 surrogate
  CHECK_FALSE(IsWireText("\xf4\x90\x80\x80"));  // above U+10FFFF
}

TEST_CASE("ToWireText makes any bytes wire text and leaves text alone", "[wire_text]") {
  CHECK(ToWireText("episode failed: no state") == "episode failed: no state");
  CHECK(ToWireText(std::string("a\0b", 3)) == "a?b");
  CHECK(ToWireText("x\xffy") == "x\xef\xbf\xbdy");  // U+FFFD
  // Too long: cut at a character boundary (a 2-byte character straddles byte 1021), "...".
  const std::string long_text = std::string(1020, 'a') + std::string(20, '\xc3');
  std::string umlauts(1020, 'a');
  for (int k = 0; k < 10; ++k) umlauts += "ü";
  const std::string cut = ToWireText(umlauts);
  CHECK(IsWireText(cut));
  CHECK(cut == std::string(1020, 'a') + "...");
  CHECK(IsWireText(ToWireText(long_text)));
  CHECK(IsWireText(ToWireText(std::string(5000, '\0'))));
}

TEMPLATE_TEST_CASE("TextFields lists every string field of the type's .lcm file", "[wire_text]",
                   ahhs::module_sensors_t, ahhs::hinge_command_t, ahhs::hormone_packet_t,
                   ahhs::module_status_t, ahhs::module_trace_t, ahhs::topology_t,
                   ahhs::sim_control_t, ahhs::sim_clock_t, ahhs::sim_state_t, ahhs::genome_t,
                   ahhs::fitness_t, ahhs::eval_request_t, ahhs::eval_result_t,
                   ahhs::worker_status_t, ahhs::genome_chunk_t, ahhs::genome_want_t) {
  const TestType msg{};
  CHECK(static_cast<int>(ahhs::bus::TextFields(msg).size()) ==
        StringFieldsInLcmFile(TestType::getTypeName()));
}

TEST_CASE("a string with NUL, invalid UTF-8 or over 1024 bytes is rejected at decode",
          "[wire_text]") {
  auto request = ahhs::testing::Fixture<ahhs::eval_request_t>();
  ahhs::eval_request_t out;
  const auto good = RawEncode(request);
  REQUIRE(Decode(good.data(), good.size(), &out));
  for (const std::string& bad :
       {std::string("r\x01n"), std::string("r\xffn"), std::string(kMaxWireText + 1, 'r')}) {
    using Set = void (*)(ahhs::eval_request_t&, const std::string&);
    for (Set set : {+[](ahhs::eval_request_t&m, const std::string&t) { m.run = t; },
                    +[](ahhs::eval_request_t&m, const std::string&t) { m.worker = t; },
                    +[](ahhs::eval_request_t&m, const std::string&t) { m.scenario = t; }}) {
      auto copy = request;
      set(copy, bad);
      const auto bytes = RawEncode(copy);
      CHECK_FALSE(Decode(bytes.data(), bytes.size(), &out));
      if (bad[1] == '\x01') set(copy, std::string("r\0n", 3));
      CHECK(Encode(copy).empty());  // nor can it be encoded
    }
  }
  // The longest valid text passes both ways.
  request.run = std::string(kMaxWireText, 'r');
  const auto bytes = Encode(request);
  REQUIRE_FALSE(bytes.empty());
  REQUIRE(Decode(bytes.data(), bytes.size(), &out));
  CHECK(out.run == request.run);
}

TEST_CASE("a send that cannot be encoded fails, is counted, and is not published", "[wire_text]") {
  ahhs::bus::InProcessBus bus;
  int heard = 0;
  auto sub = bus.Subscribe("FITNESS",
                           [&](const std::string&, const std::uint8_t*, std::size_t) { ++heard; });
  auto fitness = ahhs::testing::Fixture<ahhs::fitness_t>();
  fitness.message = std::string("bad\0text", 8);
  CHECK_FALSE(ahhs::bus::PublishTyped(bus, "FITNESS", fitness));
  CHECK(bus.stats().publish_failures == 1);
  fitness.message = ToWireText(fitness.message);
  CHECK(ahhs::bus::PublishTyped(bus, "FITNESS", fitness));
  bus.Handle(std::chrono::microseconds(0));
  CHECK(heard == 1);
  CHECK(bus.stats().publish_failures == 1);
  bus.Unsubscribe(sub);
}
