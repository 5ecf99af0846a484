// The kernel channel filter (bus/channel_filter.h), run by the kernel itself: the program is
// attached to one end of a Unix datagram socket pair (payload at offset 0) and LCM-framed
// datagrams are sent through it.
#include "bus/channel_filter.h"

#include <sys/socket.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <string>
#include <vector>

using ahhs::bus::BuildChannelFilter;
using ahhs::bus::ChannelPrefix;

namespace {

std::string Short(const std::string& channel, const std::string& payload) {
  return std::string("LC02") + std::string("\0\0\0\x07", 4) + channel + std::string(1, '\0') +
         payload;
}

// Sends each datagram through a socket pair whose receiving end carries `program` (or none,
// when empty) and returns the ones that came out, in order.
std::vector<std::string> PassThrough(std::vector<sock_filter> program,
                                     const std::vector<std::string>& datagrams) {
  int fds[2];
  REQUIRE(socketpair(AF_UNIX, SOCK_DGRAM, 0, fds) == 0);
  if (!program.empty()) {
    sock_fprog fprog{static_cast<unsigned short>(program.size()), program.data()};
    REQUIRE(setsockopt(fds[1], SOL_SOCKET, SO_ATTACH_FILTER, &fprog, sizeof(fprog)) == 0);
  }
  for (const auto& d : datagrams) REQUIRE(send(fds[0], d.data(), d.size(), 0) >= 0);
  std::vector<std::string> got;
  char buf[512];
  ssize_t n;
  while ((n = recv(fds[1], buf, sizeof(buf), MSG_DONTWAIT)) >= 0)
    got.emplace_back(buf, static_cast<std::size_t>(n));
  close(fds[0]);
  close(fds[1]);
  return got;
}

}  // namespace

TEST_CASE("channel prefix of a subscription", "[bus][filter]") {
  CHECK(ChannelPrefix("ARENA/MODULE1/HINGE") == std::string("ARENA/MODULE1/HINGE\0", 20));
  CHECK(ChannelPrefix("EVAL/REQUEST") == std::string("EVAL/REQUEST\0", 13));
  CHECK(ChannelPrefix("ARENA/MODULE[0-9]+/HINGE") == "ARENA/MODULE");
  CHECK(ChannelPrefix("ARENA/SIM.*") == "ARENA/SIM");
  CHECK(ChannelPrefix("ARENA/X?") == "ARENA/");  // the X is optional
  CHECK(ChannelPrefix("ARENA/X*") == "ARENA/");
  CHECK(ChannelPrefix(".*").empty());
  CHECK(ChannelPrefix("A|B").empty());
  CHECK(ChannelPrefix("AB(C|D)").empty());  // an alternation anywhere: no prefix
  CHECK(ChannelPrefix("^A").empty());
}

TEST_CASE("the filter passes exactly the subscribed channels", "[bus][filter]") {
  const std::vector<std::string> subscriptions = {"A/MODULE1/HINGE", "A/MODULE2/HORMONE",
                                                  "A/SIM/CLOCK"};
  std::vector<std::string> prefixes;
  for (const auto& s : subscriptions) prefixes.push_back(ChannelPrefix(s));
  const auto program = BuildChannelFilter(prefixes, 0);
  REQUIRE(!program.empty());

  const std::vector<std::string> sent = {
      Short("A/MODULE1/HINGE", "xyz"),        // subscribed
      Short("A/MODULE1/HINGES", "xyz"),       // longer name: not the same channel
      Short("A/MODULE1/HINGE", ""),           // subscribed, empty payload
      Short("A/MODULE3/HINGE", "xyz"),        // another module
      Short("A/MODULE2/HORMONE", "p"),        // subscribed
      Short("A/MODULE2/HORMON", "Ep"),        // the same bytes, but the channel ends earlier
      Short("A/SIM/CLOCK", "0123456789"),     // subscribed
      Short("B", ""),                         // short datagram, shorter than every prefix
      std::string("LC03\0\0\0\x01rest", 12),  // a fragment: always passes
      std::string("not LCM"),                 // not LCM at all: passes (LCM drops it)
      std::string("xy"),                      // shorter than any LCM header: dropped
  };
  const auto got = PassThrough(program, sent);
  const std::vector<std::string> expected = {sent[0], sent[2], sent[4], sent[6], sent[8], sent[9]};
  CHECK(got == expected);
}

TEST_CASE("regex subscriptions pass everything under their prefix", "[bus][filter]") {
  const auto program =
      BuildChannelFilter({ChannelPrefix("A/MODULE[0-9]+/HINGE"), ChannelPrefix("B/X")}, 0);
  const std::vector<std::string> sent = {Short("A/MODULE1/HINGE", "1"),
                                         Short("A/MODULE7/STATUS", ""), Short("A/SIM/CLOCK", ""),
                                         Short("B/X", ""), Short("B/XY", "")};
  CHECK(PassThrough(program, sent) == std::vector<std::string>{sent[0], sent[1], sent[3]});
}

TEST_CASE("no filter where one subscription needs every channel", "[bus][filter]") {
  CHECK(BuildChannelFilter({ChannelPrefix("A/B"), ChannelPrefix(".*")}, 8).empty());
  // Nothing subscribed: every LCM short message is dropped, other datagrams still pass.
  const auto none = BuildChannelFilter({}, 0);
  REQUIRE(!none.empty());
  CHECK(PassThrough(none, {Short("A", "1"), "zzzz"}) == std::vector<std::string>{"zzzz"});
  // A channel name longer than one jump can cover is not filtered rather than filtered wrong.
  CHECK(BuildChannelFilter({std::string(600, 'A')}, 8).empty());
}
