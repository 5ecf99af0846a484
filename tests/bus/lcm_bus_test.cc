// The behaviour every in-process bus must share, run on LCM's memq:// (LcmBus) and on inproc://
// (InProcessBus): the fused arena may run on either and must not notice the difference.
#include "bus/lcm_bus.h"

#include <catch2/catch.hpp>
#include <chrono>
#include <memory>
#include <stdexcept>

#include "bus/open_bus.h"
#include "bus/typed.h"
#include "tests/fixtures/messages.h"

using namespace std::chrono_literals;
using ahhs::bus::LcmBus;

namespace {
const char* const kInProcessUrls[] = {"memq://", "inproc://"};
}  // namespace

TEST_CASE("typed round trip in one process", "[bus]") {
  for (const char* url : kInProcessUrls) {
    DYNAMIC_SECTION(url) {
      auto owner = ahhs::bus::OpenBus(url);
      auto& bus = *owner;
      ahhs::bus::DecodeCounters counters;
      std::vector<ahhs::hormone_packet_t> got;
      std::vector<std::string> channels;
      auto subscription_29 = ahhs::bus::SubscribeTyped<ahhs::hormone_packet_t>(
          bus, "AHHS/MODULE[0-9]+/HORMONE",
          [&](const std::string& channel, const ahhs::hormone_packet_t& msg) {
            channels.push_back(channel);
            got.push_back(msg);
          },
          &counters);

      auto sent = ahhs::testing::Fixture<ahhs::hormone_packet_t>();
      REQUIRE(ahhs::bus::PublishTyped(bus, "AHHS/MODULE1/HORMONE", sent));
      sent.tick = 8;
      REQUIRE(ahhs::bus::PublishTyped(bus, "AHHS/MODULE2/HORMONE", sent));
      REQUIRE(ahhs::bus::PublishTyped(bus, "AHHS/OTHER", sent));  // not subscribed

      CHECK(bus.Handle(100ms) == 2);
      REQUIRE(got.size() == 2);
      CHECK(channels == std::vector<std::string>{"AHHS/MODULE1/HORMONE", "AHHS/MODULE2/HORMONE"});
      CHECK(got[0].tick == 7);
      CHECK(got[1].tick == 8);
      CHECK(got[1].amounts == sent.amounts);
      CHECK(counters.decoded == 2);
      CHECK(counters.dropped == 0);
      CHECK(bus.Handle(0us) == 0);
    }
  }
}

TEST_CASE("garbage on a typed channel is counted and dropped", "[bus]") {
  for (const char* url : kInProcessUrls) {
    DYNAMIC_SECTION(url) {
      auto owner = ahhs::bus::OpenBus(url);
      auto& bus = *owner;
      ahhs::bus::DecodeCounters counters;
      int delivered = 0;
      auto subscription_63 = ahhs::bus::SubscribeTyped<ahhs::module_sensors_t>(
          bus, "S", [&](const std::string&, const ahhs::module_sensors_t&) { ++delivered; },
          &counters);
      const char garbage[] = "definitely not an LCM message";
      bus.Publish("S", garbage, sizeof garbage);
      bus.Publish("S", garbage, 3);
      const auto wrong_type = ahhs::bus::Encode(ahhs::testing::Fixture<ahhs::hinge_command_t>());
      bus.Publish("S", wrong_type.data(), wrong_type.size());
      ahhs::bus::PublishTyped(bus, "S", ahhs::testing::Fixture<ahhs::module_sensors_t>());
      bus.Handle(100ms);
      CHECK(delivered == 1);
      CHECK(counters.dropped == 3);
      CHECK(counters.decoded == 1);
    }
  }
}

TEST_CASE("a throwing handler is contained and counted", "[bus]") {
  for (const char* url : kInProcessUrls) {
    DYNAMIC_SECTION(url) {
      auto owner = ahhs::bus::OpenBus(url);
      auto& bus = *owner;
      int after = 0;
      bus.Subscribe("X", [](const std::string&, const std::uint8_t*, std::size_t) {
        throw std::runtime_error("handler bug");
      });
      bus.Subscribe("X", [&](const std::string&, const std::uint8_t*, std::size_t) { ++after; });
      bus.Publish("X", "a", 1);
      bus.Publish("X", "b", 1);
      REQUIRE_NOTHROW(bus.Handle(100ms));
      CHECK(bus.stats().handler_errors == 2);
      CHECK(after == 2);
      CHECK(bus.stats().published == 2);
    }
  }
}

TEST_CASE("unsubscribe stops delivery, handle times out when idle", "[bus]") {
  for (const char* url : kInProcessUrls) {
    DYNAMIC_SECTION(url) {
      auto owner = ahhs::bus::OpenBus(url);
      auto& bus = *owner;
      int n = 0;
      const int id =
          bus.Subscribe("Y", [&](const std::string&, const std::uint8_t*, std::size_t) { ++n; });
      bus.Publish("Y", "1", 1);
      bus.Handle(100ms);
      bus.Unsubscribe(id);
      bus.Publish("Y", "2", 1);
      bus.Handle(1ms);
      CHECK(n == 1);
      CHECK(bus.Handle(1ms) == 0);
    }
  }
}

TEST_CASE("a bad URL is a clear error", "[bus]") {
  CHECK_THROWS_AS(LcmBus("nosuchprovider://x"), ahhs::bus::BusError);
}

TEST_CASE("what handlers publish is handled in the same call, nothing is left behind", "[bus]") {
  // LcmBus over memq:// counts what it published instead of asking select() per message; a
  // chain of replies and messages nobody hears must neither block Handle() nor stay queued.
  for (const char* url : kInProcessUrls) {
    DYNAMIC_SECTION(url) {
      auto owner = ahhs::bus::OpenBus(url);
      auto& bus = *owner;
      int pings = 0, pongs = 0;
      bus.Subscribe("PING", [&](const std::string&, const std::uint8_t*, std::size_t) {
        ++pings;
        bus.Publish("NOBODY", "x", 1);
        bus.Publish("PONG", "y", 1);
      });
      bus.Subscribe("PONG", [&](const std::string&, const std::uint8_t*, std::size_t) { ++pongs; });
      for (int k = 0; k < 100; ++k) bus.Publish("PING", "p", 1);
      CHECK(bus.Handle(0us) == 200);  // 100 pings + 100 pongs; NOBODY's are not dispatches
      CHECK(pings == 100);
      CHECK(pongs == 100);
      CHECK(bus.Handle(0us) == 0);
      bus.Publish("PONG", "z", 1);
      CHECK(bus.Handle(0us) == 1);
      CHECK(pongs == 101);
    }
  }
}
