// InProcessBus beyond what it shares with LCM's memq:// (lcm_bus_test.cc): order, whole-name
// matching, queue capacity, unsubscribing and publishing from inside handlers.
#include "bus/in_process_bus.h"

#include <catch2/catch.hpp>
#include <chrono>
#include <string>
#include <vector>

#include "bus/open_bus.h"

using namespace std::chrono_literals;
using ahhs::bus::InProcessBus;

namespace {

void PublishText(InProcessBus& bus, const std::string& channel, const std::string& text) {
  bus.Publish(channel, text.data(), text.size());
}

std::string Text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

}  // namespace

TEST_CASE("inproc: first in, first out across channels, the whole name must match",
          "[bus][inproc]") {
  InProcessBus bus;
  std::vector<std::string> got;
  auto record = [&](const std::string& channel, const std::uint8_t* data, std::size_t size) {
    got.push_back(channel + "=" + Text(data, size));
  };
  bus.Subscribe("A/MODULE[0-9]+/HORMONE", record);
  bus.Subscribe("B", record);
  PublishText(bus, "A/MODULE1/HORMONE", "1");
  PublishText(bus, "B", "2");
  PublishText(bus, "A/MODULE12/HORMONE", "3");
  PublishText(bus, "XA/MODULE1/HORMONE", "no");  // a match inside the name is not a match
  PublishText(bus, "A/MODULE1/HORMONEX", "no");
  PublishText(bus, "BB", "no");
  CHECK(bus.queued() == 3);
  CHECK(bus.Handle(0us) == 3);
  CHECK(got == std::vector<std::string>{"A/MODULE1/HORMONE=1", "B=2", "A/MODULE12/HORMONE=3"});
  CHECK(bus.stats().published == 6);
  CHECK(bus.stats().dispatched == 3);
}

TEST_CASE("inproc: every matching subscription gets the message, in subscription order",
          "[bus][inproc]") {
  InProcessBus bus;
  std::string order;
  bus.Subscribe(".*", [&](const std::string&, const std::uint8_t*, std::size_t) { order += "a"; });
  bus.Subscribe("X", [&](const std::string&, const std::uint8_t*, std::size_t) { order += "b"; });
  bus.Subscribe("X|Y", [&](const std::string&, const std::uint8_t*, std::size_t) { order += "c"; });
  PublishText(bus, "X", "");
  PublishText(bus, "Y", "");
  CHECK(bus.Handle(0us) == 2);
  CHECK(order == "abcac");
  // A subscription made later takes later messages on a channel already seen.
  bus.Subscribe("Y", [&](const std::string&, const std::uint8_t*, std::size_t) { order += "d"; });
  PublishText(bus, "Y", "");
  bus.Handle(0us);
  CHECK(order == "abcacacd");
}

TEST_CASE("inproc: a full subscription drops further messages until the next Handle",
          "[bus][inproc]") {
  InProcessBus bus;
  std::vector<std::string> small, large;
  bus.Subscribe(
      "C",
      [&](const std::string&, const std::uint8_t* d, std::size_t n) {
        small.push_back(Text(d, n));
      },
      2);
  bus.Subscribe("C", [&](const std::string&, const std::uint8_t* d, std::size_t n) {
    large.push_back(Text(d, n));
  });
  for (const char* t : {"1", "2", "3", "4"}) PublishText(bus, "C", t);
  CHECK(bus.Handle(0us) == 4);
  CHECK(small == std::vector<std::string>{"1", "2"});
  CHECK(large == std::vector<std::string>{"1", "2", "3", "4"});
  PublishText(bus, "C", "5");
  bus.Handle(0us);
  CHECK(small.back() == "5");
}

TEST_CASE("inproc: unsubscribing inside a handler takes effect at once", "[bus][inproc]") {
  InProcessBus bus;
  int first = 0, second = 0;
  int second_id = 0;
  bus.Subscribe("U", [&](const std::string&, const std::uint8_t*, std::size_t) {
    ++first;
    bus.Unsubscribe(second_id);
  });
  second_id =
      bus.Subscribe("U", [&](const std::string&, const std::uint8_t*, std::size_t) { ++second; });
  PublishText(bus, "U", "1");
  PublishText(bus, "U", "2");
  CHECK(bus.Handle(0us) == 2);
  CHECK(first == 2);
  CHECK(second == 0);      // unsubscribed before its turn on the first message
  bus.Unsubscribe(12345);  // unknown id: nothing happens
}

TEST_CASE("inproc: messages published by handlers keep their bytes while the queue grows",
          "[bus][inproc]") {
  // The first handler publishes far more than the queue holds, which grows it while a message
  // is being dispatched; every message must arrive whole and in order.
  InProcessBus bus;
  std::vector<std::string> got;
  bool fanned_out = false;
  bus.Subscribe("FAN", [&](const std::string&, const std::uint8_t* d, std::size_t n) {
    const std::string before = Text(d, n);
    if (!fanned_out) {
      fanned_out = true;
      for (int k = 0; k < 1000; ++k) PublishText(bus, "OUT", "message " + std::to_string(k));
    }
    CHECK(Text(d, n) == before);  // still valid after the queue grew
  });
  bus.Subscribe("OUT", [&](const std::string&, const std::uint8_t* d, std::size_t n) {
    got.push_back(Text(d, n));
    CHECK(bus.Handle(0us) == 0);  // no nested dispatch
  });
  PublishText(bus, "FAN", std::string(300, 'f'));
  CHECK(bus.Handle(0us) == 1001);
  REQUIRE(got.size() == 1000);
  for (int k = 0; k < 1000; ++k)
    CHECK(got[static_cast<std::size_t>(k)] == "message " + std::to_string(k));
  CHECK(bus.queued() == 0);
}

TEST_CASE("inproc: bad expressions and URLs are clear errors", "[bus][inproc]") {
  InProcessBus bus;
  CHECK_THROWS_AS(bus.Subscribe("(", [](const std::string&, const std::uint8_t*, std::size_t) {}),
                  ahhs::bus::BusError);
  CHECK_THROWS_AS(ahhs::bus::OpenBus("inproc://somewhere"), ahhs::bus::BusError);
  CHECK(ahhs::bus::IsInProcessUrl("inproc://"));
  CHECK(ahhs::bus::IsInProcessUrl("memq://"));
  CHECK_FALSE(ahhs::bus::IsInProcessUrl("udpm://239.255.76.67:7667?ttl=0"));
  CHECK(bus.Handle(1ms) == 0);  // idle: waits, then returns nothing
}

TEST_CASE("a Subscription handle unsubscribes when destroyed or reset, and moves without loss",
          "[bus][inproc]") {
  InProcessBus bus;
  int calls = 0;
  auto count = [&](const std::string&, const std::uint8_t*, std::size_t) { ++calls; };
  {
    ahhs::bus::Subscription scoped(&bus, bus.Subscribe("A", count));
    PublishText(bus, "A", "x");
    bus.Handle(0us);
    CHECK(calls == 1);
  }
  PublishText(bus, "A", "x");
  bus.Handle(0us);
  CHECK(calls == 1);  // the handle is gone: so is the subscription

  ahhs::bus::Subscription first(&bus, bus.Subscribe("A", count));
  ahhs::bus::Subscription moved = std::move(first);
  CHECK_FALSE(first.active());
  CHECK(moved.active());
  PublishText(bus, "A", "x");
  bus.Handle(0us);
  CHECK(calls == 2);  // the move kept it, exactly once
  moved.reset();
  PublishText(bus, "A", "x");
  bus.Handle(0us);
  CHECK(calls == 2);
}
