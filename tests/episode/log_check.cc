// Reads an episode log written by `ahhs-launch --log` (lcm::LogFile) and checks that every tick
// of every module's SENSORS, HINGE and HORMONE packets is in it; with --trace (logs of
// ahhs-replay), SENSORS, HINGE and TRACE.
//   log_check LOG --arena A --modules N --ticks T [--trace]
//   log_check LOG --burst-channel CH --ticks T   (hinge commands with ticks 0..T-1, each once)
#include <ahhs/hinge_command_t.hpp>
#include <ahhs/hormone_packet_t.hpp>
#include <ahhs/module_sensors_t.hpp>
#include <ahhs/module_trace_t.hpp>
#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <set>

#include "base/cli.h"
#include "bus/channels.h"
#include "bus/codec.h"

namespace cli = ahhs::base::cli;

int main(int argc, char** argv) {
  cli::App app{"check an episode log"};
  std::string path, arena;
  int modules = 0;
  long ticks = 0;
  app.add_option("LOG", path)->required();
  std::string burst_channel;
  auto* burst_opt = app.add_option("--burst-channel", burst_channel);
  app.add_option("--arena", arena)->excludes(burst_opt);
  app.add_option("--modules", modules)->excludes(burst_opt);
  app.add_option("--ticks", ticks)->required();
  bool trace = false;
  app.add_flag("--trace", trace, "expect TRACE messages instead of hormone packets");
  if (const int code = ahhs::base::Parse(app, argc, argv); code >= 0) return code;

  lcm::LogFile log(path, "r");
  if (!log.good()) {
    std::fprintf(stderr, "log_check: cannot read %s\n", path.c_str());
    return 1;
  }
  if (!burst_channel.empty()) {
    std::set<long> seen;
    long duplicates = 0, events = 0;
    for (const lcm::LogEvent* e = log.readNextEvent(); e != nullptr; e = log.readNextEvent()) {
      ++events;
      ahhs::hinge_command_t h;
      if (e->channel == burst_channel &&
          ahhs::bus::Decode(e->data, static_cast<std::size_t>(e->datalen), &h))
        duplicates += seen.insert(h.tick).second ? 0 : 1;
    }
    long missing = 0;
    for (long t = 0; t < ticks; ++t) missing += seen.count(t) ? 0 : 1;
    std::printf("log_check: %ld events; %ld of %ld burst ticks missing, %ld duplicates\n", events,
                missing, ticks, duplicates);
    return missing == 0 && duplicates == 0 ? 0 : 1;
  }
  if (arena.empty() || modules <= 0) {
    std::fprintf(stderr, "log_check: --arena and --modules are needed (or --burst-channel)\n");
    return 1;
  }
  const ahhs::bus::ArenaChannels ch(arena);
  std::set<std::pair<int, long>> sensors, hinges, hormones;
  long events = 0;
  for (const lcm::LogEvent* e = log.readNextEvent(); e != nullptr; e = log.readNextEvent()) {
    ++events;
    for (int m = 0; m < modules; ++m) {
      if (e->channel == ch.Sensors(m)) {
        ahhs::module_sensors_t s;
        if (ahhs::bus::Decode(e->data, static_cast<std::size_t>(e->datalen), &s))
          sensors.insert({m, s.tick});
      } else if (e->channel == ch.Hinge(m)) {
        ahhs::hinge_command_t h;
        if (ahhs::bus::Decode(e->data, static_cast<std::size_t>(e->datalen), &h))
          hinges.insert({m, h.tick});
      } else if (trace && e->channel == ch.Trace(m)) {
        ahhs::module_trace_t t;
        if (ahhs::bus::Decode(e->data, static_cast<std::size_t>(e->datalen), &t) && t.module == m &&
            static_cast<int>(t.hormones.size()) == t.num_hormones)
          hormones.insert({m, t.tick});
      } else if (!trace && e->channel == ch.Hormone(m)) {
        ahhs::hormone_packet_t p;
        if (ahhs::bus::Decode(e->data, static_cast<std::size_t>(e->datalen), &p))
          hormones.insert({m, p.tick});
      }
    }
  }
  int bad = 0;
  for (int m = 0; m < modules; ++m) {
    for (long t = 0; t < ticks; ++t) {
      if (!sensors.count({m, t}) || !hinges.count({m, t}) || !hormones.count({m, t})) {
        if (bad++ < 5) std::fprintf(stderr, "log_check: module %d tick %ld incomplete\n", m, t);
      }
    }
  }
  std::printf(
      "log_check: %ld events; %zu sensors, %zu hinge, %zu %s (module, tick) pairs; %d "
      "incomplete\n",
      events, sensors.size(), hinges.size(), hormones.size(), trace ? "trace" : "hormone", bad);
  return bad == 0 ? 0 : 1;
}
