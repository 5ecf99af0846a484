// ahhs-worker: serves evaluation jobs of any ahhs-evolve on the bus (docs/evolution.md,
// docs/protocol.md "Evaluation farm"). One evaluation at a time per process; --slots N starts N
// worker processes on this host. Runs until SIGTERM or Ctrl-C.
//
// Fault injection for tests (docs/development.md): AHHS_WORKER_FAULT=nan makes every result a
// NaN fitness.
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <thread>

#include "base/children.h"
#include "base/cli.h"
#include "bus/fault_bus.h"
#include "bus/lcm_bus.h"
#include "bus/wire_text.h"
#include "episode/arena/process_arena.h"
#include "evolver/farm/arena_evaluator.h"
#include "evolver/farm/worker_node.h"

namespace ev = ahhs::evolver;

namespace {

std::atomic<bool> g_stop{false};
void OnSignal(int) { g_stop = true; }

// The port of a udpm://GROUP:PORT[?...] URL, or -1.
int UdpmPort(const std::string& url) {
  const std::string scheme = "udpm://";
  if (url.rfind(scheme, 0) != 0) return -1;
  const auto colon = url.find(':', scheme.size());
  if (colon == std::string::npos) return -1;
  int port = 0, digits = 0;
  for (auto i = colon + 1; i < url.size() && url[i] != '?' && url[i] != '/'; ++i, ++digits) {
    if (url[i] < '0' || url[i] > '9' || digits == 5) return -1;
    port = port * 10 + (url[i] - '0');
  }
  return digits > 0 ? port : -1;
}

// Every process on a multicast port receives every datagram sent to it, and in a lockstep arena
// that per-datagram cost is most of the time: arenas sharing a port (or sharing it with the
// farm) slow each other down several times. So each worker's arena gets a port of its own,
// 7668 + pid % 4000 (a collision costs speed, never correctness: arenas have unique names), but
// never the farm's port, whose datagrams a lossy link or a filter may drop.
std::string PrivateArenaUrl(const std::string& farm_url) {
  int offset = getpid() % 4000;
  if (UdpmPort(farm_url) == 7668 + offset) offset = (offset + 1) % 4000;
  const int port = 7668 + offset;
  return "udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0&recv_buf_size=4194304";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"ahhs-worker: evaluates genomes for ahhs-evolve runs on this bus"};
  std::string url = ahhs::bus::kDefaultLcmUrl, arena = "direct", id,
              arena_url = ahhs::bus::kDefaultLcmUrl;
  int slots = 1;
  bool verbose = false, quiet = false, any_run = false;
  std::string run;
  const auto wire_text = [](const std::string& text) {
    return ahhs::bus::IsWireText(text)
               ? std::string()
               : "must be UTF-8 text of at most " + std::to_string(ahhs::bus::kMaxWireText) +
                     " bytes without NUL";
  };
  auto* run_option =
      app.add_option("--run", run,
                     "serve this run only (its id, which ahhs-evolve prints); runs are isolated")
          ->check(wire_text);
  app.add_flag("--any-run", any_run, "serve every run on this bus (a shared farm)")
      ->excludes(run_option);
  app.add_option("--lcm-url", url, "LCM URL of the evaluation farm (ttl=1 to serve a LAN)")
      ->capture_default_str();
  app.add_option("--slots", slots, "evaluations at once (one worker process each)")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  app.add_option("--arena-kind", arena, "how to evaluate: direct, fused or processes")
      ->check(CLI::IsMember({"direct", "fused", "processes"}))
      ->capture_default_str();
  auto* arena_url_option =
      app.add_option("--arena-url", arena_url,
                     "LCM URL of the process arena's own traffic (--arena-kind processes; default: "
                     "host-only multicast on a port of this worker's own)");
  std::string external, arena_name;
  int external_timeout_s = 60;
  auto* external_option = app.add_option(
      "--external", external,
      "roles of the process arena that others play (hardware, other languages): sim, fitness, "
      "module:N[,M...] or modules (docs/hardware.md); needs --arena-name and --arena-url");
  auto* arena_name_option = app.add_option(
      "--arena-name", arena_name,
      "channel prefix of the process arena (default W<pid>; the external roles must use it)");
  app.add_option("--external-timeout", external_timeout_s,
                 "seconds an episode waits for the external roles to answer")
      ->check(CLI::Range(1, 86400))
      ->capture_default_str();
  bool realtime = false;
  auto* realtime_option =
      app.add_flag("--realtime", realtime,
                   "episodes at wall-clock pace, for a physical organism (--arena-kind processes)");
  app.add_option("--id", id, "worker id, unique on the bus (default: host:pid)")->check(wire_text);
  app.add_flag("-v,--verbose", verbose, "print a line per evaluation");
  app.add_flag("-q,--quiet", quiet, "print errors only");
  if (const int code = ahhs::cli::Parse(app, argc, argv); code >= 0) return code;

  if (run.empty() && !any_run) {
    std::cerr << "ahhs-worker: say which run to serve: --run RUN_ID (ahhs-evolve prints it) or "
                 "--any-run\n";
    return ahhs::cli::kExitUsage;
  }
  if (realtime_option->count() > 0 && arena != "processes") {
    std::cerr << "ahhs-worker: --realtime needs --arena-kind processes\n";
    return ahhs::cli::kExitUsage;
  }
  if (external_option->count() > 0) {
    std::string why;
    if (arena != "processes")
      why = "--external needs --arena-kind processes";
    else if (arena_name_option->count() == 0 || arena_url_option->count() == 0)
      why =
          "--external needs --arena-name NAME and --arena-url URL: the external roles must "
          "know the arena";
    else if (slots != 1)
      why = "--external serves one organism: --slots must be 1";
    else {
      try {
        ahhs::episode::ParseExternalRoles(external, 1 << 15);  // modules checked per scenario
      } catch (const std::exception& e) {
        why = e.what();
      }
    }
    if (!why.empty()) {
      std::cerr << "ahhs-worker: " << why << '\n';
      return ahhs::cli::kExitUsage;
    }
  }
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  const std::string host = ahhs::base::HostName();
  if (arena_url_option->count() == 0) arena_url = PrivateArenaUrl(url);

  if (slots > 1) {
    // One process per slot (ODE's solver RNG is process-global); this one only supervises.
    ahhs::base::ChildProcesses children;
    const std::string self = ahhs::base::ExecutableDir() + "/ahhs-worker";
    for (int k = 0; k < slots; ++k) {
      std::vector<std::string> args{
          self,
          "--lcm-url",
          url,
          "--arena-kind",
          arena,
          "--id",
          (id.empty() ? host + ":" + std::to_string(getpid()) : id) + "/" + std::to_string(k)};
      if (arena_url_option->count() > 0) args.insert(args.end(), {"--arena-url", arena_url});
      if (any_run)
        args.push_back("--any-run");
      else
        args.insert(args.end(), {"--run", run});
      if (verbose) args.push_back("--verbose");
      if (quiet) args.push_back("--quiet");
      if (realtime) args.push_back("--realtime");
      children.Start("slot " + std::to_string(k), args, false);
    }
    if (!quiet) std::cerr << "ahhs-worker: " << slots << " worker processes on " << host << '\n';
    while (!g_stop) {
      children.Reap();
      if (children.running() == 0) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    children.StopAll(std::chrono::seconds(5));
    return 0;
  }

  if (id.empty()) id = host + ":" + std::to_string(getpid());
  const char* fault = std::getenv("AHHS_WORKER_FAULT");
  const std::string fault_mode = fault ? fault : "";
  if (!fault_mode.empty() && fault_mode != "nan") {
    std::cerr << "ahhs-worker: unknown AHHS_WORKER_FAULT '" << fault_mode << "' (only: nan)\n";
    return 1;
  }
  try {
    ahhs::episode::ArenaOptions arena_options;
    arena_options.kind = ahhs::episode::ParseArenaKind(arena);
    arena_options.url = arena_url;
    arena_options.name = arena_name.empty() ? "W" + std::to_string(getpid()) : arena_name;
    arena_options.external = external;
    arena_options.external_timeout = std::chrono::seconds(external_timeout_s);
    arena_options.realtime = realtime;
    ev::ArenaEvaluator evaluator(arena_options);
    auto bus = ahhs::bus::OpenBusWithFaultInjection(url);
    ev::WorkerNode node(bus.get(), id, host, [&](const ev::FarmJob& job) {
      ev::FarmResult out = evaluator.Evaluate(job);
      if (fault_mode == "nan") out.fitness = std::numeric_limits<double>::quiet_NaN();
      if (verbose)
        std::cout << "job " << job.job << " attempt " << job.attempt << ": fitness " << out.fitness
                  << (out.message.empty() ? "" : " (" + out.message + ")") << std::endl;
      return out;
    });
    if (!quiet)
      std::cerr << "ahhs-worker " << id << ": serving " << (run.empty() ? "any run" : "run " + run)
                << " (" << arena << " arena"
                << (external.empty()
                        ? std::string()
                        : " " + arena_options.name + " on " + arena_url + ", external: " + external)
                << ") on " << url << '\n';
    if (!run.empty()) node.ServeOnlyRun(run);
    node.Serve([&] { return g_stop.load(); });
    const auto& c = node.counters();
    if (!quiet)
      std::cerr << "ahhs-worker " << id << ": " << c.evaluations << " evaluations, " << c.refused
                << " requests of another protocol version refused, " << c.requests.dropped
                << " undecodable messages dropped\n";
  } catch (const std::exception& e) {
    std::cerr << "ahhs-worker: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
