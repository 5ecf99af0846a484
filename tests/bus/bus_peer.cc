// Two-process bus exchange for the multiprocess test (tests/bus/multiprocess_exchange.sh).
//   bus_peer --role responder --lcm-url URL
//   bus_peer --role initiator --lcm-url URL [--pings N] [--burst N]
//   bus_peer --role spam --lcm-url URL --channels A,B,... --seconds S   (garbage, for fault tests)
//   bus_peer --role burst --lcm-url URL --burst N   (N hinge commands on TEST/BURST, ticks 0..N-1,
//                                                    as fast as possible; for recorder tests)
// The initiator waits for the responder's READY, does N typed ping-pongs (checking every
// reply's content), then sends a burst of hinge commands as fast as it can and asks the
// responder how many arrived. Exit 0 only when every reply was right and nothing was lost, and
// (udpm://) the bus had its kernel channel filter attached.
#include <ahhs/hinge_command_t.hpp>
#include <ahhs/hormone_packet_t.hpp>
#include <ahhs/module_status_t.hpp>
#include <ahhs/sim_control_t.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>
#include <sstream>

#include "base/cli.h"
#include "bus/lcm_bus.h"
#include "bus/typed.h"

namespace cli = ahhs::base::cli;

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

namespace {

constexpr const char* kReady = "TEST/READY";
constexpr const char* kPing = "TEST/PING";
constexpr const char* kPong = "TEST/PONG";
constexpr const char* kBurst = "TEST/BURST";
constexpr const char* kBurstEnd = "TEST/BURST_END";
constexpr const char* kSummary = "TEST/SUMMARY";

ahhs::hinge_command_t Command(std::int64_t tick) {
  ahhs::hinge_command_t m{};
  m.utime = 0;
  m.episode = 1;
  m.tick = tick;
  m.module = static_cast<std::int32_t>(tick % 5);
  m.num_actuators = 1;
  m.values = {std::sin(static_cast<double>(tick))};
  m.present = {true};
  m.target_angle = 0;
  return m;
}

// Handles the bus until `done()` or the deadline. Returns done().
template <class Pred>
bool HandleUntil(ahhs::bus::Bus& bus, Pred done, std::chrono::milliseconds limit) {
  const auto deadline = Clock::now() + limit;
  while (!done() && Clock::now() < deadline) bus.Handle(20ms);
  return done();
}

int Responder(ahhs::bus::Bus& bus, int burst) {
  bool got_ping = false;
  bool finished = false;
  std::set<std::int64_t> burst_ticks;
  int burst_bad = 0;
  auto subscription_64 = ahhs::bus::SubscribeTyped<ahhs::hinge_command_t>(
      bus, kPing, [&](const std::string&, const ahhs::hinge_command_t& m) {
        got_ping = true;
        ahhs::hormone_packet_t pong{};
        pong.episode = m.episode;
        pong.tick = m.tick;
        pong.from_module = 1;
        pong.num_receivers = 1;
        pong.to_modules = {0};
        pong.num_hormones = 2;
        pong.amounts = {m.values[0] * 2.0, static_cast<double>(m.module)};
        ahhs::bus::PublishTyped(bus, kPong, pong);
      });
  auto subscription_77 = ahhs::bus::SubscribeTyped<ahhs::hinge_command_t>(
      bus, kBurst,
      [&](const std::string&, const ahhs::hinge_command_t& m) {
        if (m.values.size() != 1 || m.values[0] != Command(m.tick).values[0]) ++burst_bad;
        if (!burst_ticks.insert(m.tick).second) ++burst_bad;  // duplicate
      },
      nullptr, burst + 100);
  auto subscription_84 = ahhs::bus::SubscribeTyped<ahhs::sim_control_t>(
      bus, kBurstEnd, [&](const std::string&, const ahhs::sim_control_t&) {
        ahhs::module_status_t s{};
        s.tick = static_cast<std::int64_t>(burst_ticks.size());
        s.dropped_messages = burst_bad;
        s.message = "burst summary";
        ahhs::bus::PublishTyped(bus, kSummary, s);
        finished = true;
      });

  const auto deadline = Clock::now() + 30s;
  auto next_ready = Clock::now();
  while (!finished && Clock::now() < deadline) {
    if (!got_ping && Clock::now() >= next_ready) {
      ahhs::module_status_t ready{};
      ready.state = ahhs::module_status_t::READY;
      ahhs::bus::PublishTyped(bus, kReady, ready);
      next_ready = Clock::now() + 50ms;
    }
    bus.Handle(10ms);
  }
  // Answer repeated BURST_END requests a little longer, in case the first summary was lost.
  HandleUntil(
      bus, [] { return false; }, 300ms);
  std::printf("responder: %zu burst messages, %d bad\n", burst_ticks.size(), burst_bad);
  return finished ? 0 : 1;
}

int Initiator(ahhs::bus::Bus& bus, int pings, int burst) {
  bool ready = false;
  auto subscription_114 = ahhs::bus::SubscribeTyped<ahhs::module_status_t>(
      bus, kReady, [&](const std::string&, const ahhs::module_status_t&) { ready = true; });
  std::vector<ahhs::hormone_packet_t> pongs;
  auto subscription_117 = ahhs::bus::SubscribeTyped<ahhs::hormone_packet_t>(
      bus, kPong, [&](const std::string&, const ahhs::hormone_packet_t& m) { pongs.push_back(m); });
  bool have_summary = false;
  ahhs::module_status_t summary{};
  auto subscription_121 = ahhs::bus::SubscribeTyped<ahhs::module_status_t>(
      bus, kSummary, [&](const std::string&, const ahhs::module_status_t& m) {
        summary = m;
        have_summary = true;
      });

  if (!HandleUntil(
          bus, [&] { return ready; }, 10s)) {
    std::fprintf(stderr, "initiator: responder never reported READY\n");
    return 1;
  }
  for (int k = 0; k < pings; ++k) {
    const auto ping = Command(k);
    ahhs::bus::PublishTyped(bus, kPing, ping);
    if (!HandleUntil(
            bus, [&] { return pongs.size() == static_cast<std::size_t>(k + 1); }, 2s)) {
      std::fprintf(stderr, "initiator: no reply to ping %d\n", k);
      return 1;
    }
    const auto& pong = pongs.back();
    if (pong.tick != k || pong.amounts.size() != 2 || pong.amounts[0] != 2.0 * ping.values[0] ||
        pong.amounts[1] != ping.module) {
      std::fprintf(stderr, "initiator: wrong reply to ping %d\n", k);
      return 1;
    }
  }
  std::printf("initiator: %d ping-pongs correct\n", pings);

  for (int k = 0; k < burst; ++k) ahhs::bus::PublishTyped(bus, kBurst, Command(k));
  for (int attempt = 0; attempt < 20 && !have_summary; ++attempt) {
    ahhs::bus::PublishTyped(bus, kBurstEnd, ahhs::sim_control_t{});
    HandleUntil(
        bus, [&] { return have_summary; }, 250ms);
  }
  if (!have_summary) {
    std::fprintf(stderr, "initiator: no burst summary\n");
    return 1;
  }
  std::printf("initiator: burst of %d sent, %lld received, %d bad\n", burst,
              static_cast<long long>(summary.tick), summary.dropped_messages);
  return (summary.tick == burst && summary.dropped_messages == 0) ? 0 : 1;
}

// Publishes random bytes on each channel (comma-separated) about every millisecond.
int Spammer(ahhs::bus::Bus& bus, const std::string& channels, double seconds) {
  std::vector<std::string> list;
  std::string item;
  std::stringstream in(channels);
  while (std::getline(in, item, ',')) list.push_back(item);
  std::mt19937_64 rng(12345);
  const auto end = Clock::now() + std::chrono::duration<double>(seconds);
  long sent = 0;
  while (Clock::now() < end) {
    for (const auto& ch : list) {
      std::vector<std::uint8_t> junk(8 + rng() % 200);
      for (auto& b : junk) b = static_cast<std::uint8_t>(rng());
      bus.Publish(ch, junk.data(), junk.size());
      ++sent;
    }
    bus.Handle(1ms);
  }
  std::printf("spammer: %ld garbage messages\n", sent);
  return 0;
}

// Publishes `burst` hinge commands (ticks 0..burst-1) on TEST/BURST back to back.
int Burster(ahhs::bus::Bus& bus, int burst) {
  for (int k = 0; k < burst; ++k) ahhs::bus::PublishTyped(bus, kBurst, Command(k));
  std::printf("burst: %d messages on %s\n", burst, kBurst);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  cli::App app{"Two-process LCM exchange used by the multiprocess bus test"};
  std::string role;
  std::string url;
  int pings = 100;
  int burst = 2000;
  app.add_option("--role", role, "responder or initiator")
      ->required()
      ->check(cli::IsMember({"responder", "initiator", "spam", "burst"}));
  std::string channels;
  double seconds = 1;
  app.add_option("--channels", channels, "spam: comma-separated channels");
  app.add_option("--seconds", seconds, "spam: how long");
  app.add_option("--lcm-url", url, "LCM URL")->required();
  app.add_option("--pings", pings, "ping-pong round trips")->check(cli::NonNegativeNumber);
  app.add_option("--burst", burst, "messages in the burst")->check(cli::NonNegativeNumber);
  if (const int code = ahhs::base::Parse(app, argc, argv); code >= 0) return code;
  try {
    ahhs::bus::LcmBus bus(url);
    if (role == "spam") return Spammer(bus, channels, seconds);
    if (role == "burst") return Burster(bus, burst);
    const int rc = role == "responder" ? Responder(bus, burst) : Initiator(bus, pings, burst);
    // Over udpm:// the kernel should filter our channels (bus/channel_filter.h); without it
    // everything still works, only slower, so it is checked here explicitly.
    if (url.rfind("udpm://", 0) == 0 && !bus.channel_filter_attached()) {
      std::fprintf(stderr, "bus_peer: no channel filter on LCM's receive socket\n");
      return 1;
    }
    return rc;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bus_peer: %s\n", e.what());
    return 1;
  }
}
