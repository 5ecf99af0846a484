// ahhs-module: one module's hormone controller as its own process on the bus.
#include <atomic>
#include <csignal>
#include <cstdio>
#include <iostream>

#include "base/cli.h"
#include "bus/fault_bus.h"
#include "bus/lcm_bus.h"
#include "bus/wire_version.h"
#include "modules/core/genome_json.h"
#include "modules/node/module_node.h"

namespace cli = ahhs::base::cli;

namespace {
std::atomic<bool> g_stop{false};
void OnSignal(int) { g_stop = true; }
}  // namespace

int main(int argc, char** argv) {
  cli::App app{"ahhs-module: one module's AHHS controller on the bus (docs/protocol.md)"};
  ahhs::modules::ModuleNodeOptions options;
  std::string url = ahhs::bus::kDefaultLcmUrl;
  int timeout_ms = 500;
  app.add_option("--id", options.id, "module id (0-based)")->required()->check(cli::Range(0, 9999));
  app.add_option("--lcm-url", url, "LCM URL")->capture_default_str();
  app.add_option("--arena", options.arena, "arena name: channel prefix")->capture_default_str();
  app.add_option("--hormone-timeout-ms", timeout_ms,
                 "longest wait for neighbours' hormone packets (keep it well below the sim's "
                 "lockstep timeout; 0: wait for every packet, exact lockstep)")
      ->check(cli::Range(0, 600000))
      ->capture_default_str();
  ahhs::base::SetVersion(app, {ahhs::bus::WireVersionLine(), ahhs::modules::GenomeFormatLine()});
  if (const int code = ahhs::base::Parse(app, argc, argv); code >= 0) return code;
  options.hormone_timeout = std::chrono::milliseconds(timeout_ms);
  try {
    auto bus = ahhs::bus::OpenBusWithFaultInjection(url);
    ahhs::modules::ModuleNode node(bus.get(), options);
    std::signal(SIGINT, OnSignal);
    std::signal(SIGTERM, OnSignal);
    while (!g_stop) node.Poll(std::chrono::milliseconds(100));
    const auto s = node.stats();
    std::fprintf(stderr,
                 "ahhs-module %d: %llu ticks, %llu missing packets, %llu late, %llu dropped\n",
                 options.id, static_cast<unsigned long long>(s.ticks),
                 static_cast<unsigned long long>(s.missing_packets),
                 static_cast<unsigned long long>(s.late_messages),
                 static_cast<unsigned long long>(s.dropped_messages));
    if (!s.drops.empty())
      std::fprintf(stderr, "ahhs-module %d: dropped %s\n", options.id, s.drops.c_str());
  } catch (const std::exception& e) {
    std::cerr << "ahhs-module: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
