#include "evolver/app/worker_app.h"

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <thread>
#include <vector>

#include "base/children.h"
#include "bus/fault_bus.h"
#include "bus/wire_text.h"
#include "episode/arena/process_arena.h"
#include "evolver/farm/arena_evaluator.h"
#include "evolver/farm/worker_node.h"

namespace cli = ahhs::base::cli;

namespace ahhs::evolver {
namespace ev = ahhs::evolver;
namespace {

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

void AddWorkerOptions(cli::App& app, WorkerOptions* o) {
  const auto wire_text = [](const std::string& text) {
    return ahhs::bus::IsWireText(text)
               ? std::string()
               : "must be UTF-8 text of at most " + std::to_string(ahhs::bus::kMaxWireText) +
                     " bytes without NUL";
  };
  auto* run_option =
      app.add_option("--run", o->run,
                     "serve this run only (its id, which ahhs-evolve prints); runs are isolated")
          ->check(wire_text);
  app.add_flag("--any-run", o->any_run, "serve every run on this bus (a shared farm)")
      ->excludes(run_option);
  app.add_option("--lcm-url", o->url, "LCM URL of the evaluation farm (ttl=1 to serve a LAN)")
      ->capture_default_str();
  app.add_option("--slots", o->slots, "evaluations at once (one worker process each)")
      ->check(cli::Range(1, 256))
      ->capture_default_str();
  app.add_option("--arena-kind", o->arena, "how to evaluate: direct, fused or processes")
      ->check(cli::IsMember({"direct", "fused", "processes"}))
      ->capture_default_str();
  app.add_option("--arena-url", o->arena_url,
                 "LCM URL of the process arena's own traffic (--arena-kind processes; default: "
                 "host-only multicast on a port of this worker's own)");
  app.add_option(
      "--external", o->external,
      "roles of the process arena that others play (hardware, other languages): sim, fitness, "
      "module:N[,M...] or modules (docs/hardware.md); needs --arena and --arena-url");
  auto* arena = app.add_option(
      "--arena", o->arena_name,
      "channel prefix of the process arena, as --arena of every other tool (default W<pid>; the "
      "external roles must use it)");
  // The old name, for one release: it says what replaced it.
  app.add_option("--arena-name", o->arena_name, "deprecated: use --arena")
      ->excludes(arena)
      ->each([](const std::string&) {
        std::cerr << "ahhs-worker: --arena-name is deprecated and will go; use --arena\n";
      });
  app.add_option("--external-timeout", o->external_timeout_s,
                 "seconds an episode waits for the external roles to answer")
      ->check(cli::Range(1, 86400))
      ->capture_default_str();
  app.add_flag("--realtime", o->realtime,
               "episodes at wall-clock pace, for a physical organism (--arena-kind processes)");
  app.add_option("--id", o->id, "worker id, unique on the bus (default: host:pid)")
      ->check(wire_text);
  app.add_flag("-v,--verbose", o->verbose, "print a line per evaluation");
  app.add_flag("-q,--quiet", o->quiet, "print errors only");
}

std::string CheckWorkerOptions(const cli::App& app, WorkerOptions* o) {
  if (o->run.empty() && !o->any_run)
    return "say which run to serve: --run RUN_ID (ahhs-evolve prints it) or --any-run";
  if (app.count("--realtime") > 0 && o->arena != "processes")
    return "--realtime needs --arena-kind processes";
  if (app.count("--external") > 0) {
    if (o->arena != "processes") return "--external needs --arena-kind processes";
    if (app.count("--arena") + app.count("--arena-name") == 0 || app.count("--arena-url") == 0)
      return "--external needs --arena NAME and --arena-url URL: the external roles must "
             "know the arena";
    if (o->slots != 1) return "--external serves one organism: --slots must be 1";
    try {
      ahhs::episode::ParseExternalRoles(o->external, 1 << 15);  // modules checked per scenario
    } catch (const std::exception& e) {
      return e.what();
    }
  }
  o->arena_url_given = app.count("--arena-url") > 0;
  if (!o->arena_url_given) o->arena_url = PrivateArenaUrl(o->url);
  return "";
}

int SuperviseSlots(const WorkerOptions& o, const std::atomic<bool>& stop) {
  const std::string host = ahhs::base::HostName();
  // One process per slot (ODE's solver RNG is process-global); this one only supervises.
  ahhs::base::ChildProcesses children;
  const std::string self = ahhs::base::ExecutableDir() + "/ahhs-worker";
  for (int k = 0; k < o.slots; ++k) {
    std::vector<std::string> args{
        self,
        "--lcm-url",
        o.url,
        "--arena-kind",
        o.arena,
        "--id",
        (o.id.empty() ? host + ":" + std::to_string(getpid()) : o.id) + "/" + std::to_string(k)};
    if (o.arena_url_given) args.insert(args.end(), {"--arena-url", o.arena_url});
    if (o.any_run)
      args.push_back("--any-run");
    else
      args.insert(args.end(), {"--run", o.run});
    if (o.verbose) args.push_back("--verbose");
    if (o.quiet) args.push_back("--quiet");
    if (o.realtime) args.push_back("--realtime");
    children.Start("slot " + std::to_string(k), args, false);
  }
  if (!o.quiet) std::cerr << "ahhs-worker: " << o.slots << " worker processes on " << host << '\n';
  while (!stop) {
    children.Reap();
    if (children.running() == 0) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  children.StopAll(std::chrono::seconds(5));
  return 0;
}

int ServeJobs(WorkerOptions o, const std::atomic<bool>& stop) {
  const std::string host = ahhs::base::HostName();
  if (o.id.empty()) o.id = host + ":" + std::to_string(getpid());
  const char* fault = std::getenv("AHHS_WORKER_FAULT");
  const std::string fault_mode = fault ? fault : "";
  if (!fault_mode.empty() && fault_mode != "nan") {
    std::cerr << "ahhs-worker: unknown AHHS_WORKER_FAULT '" << fault_mode << "' (only: nan)\n";
    return 1;
  }
  try {
    ahhs::episode::ArenaOptions arena_options;
    arena_options.kind = ahhs::episode::ParseArenaKind(o.arena);
    arena_options.url = o.arena_url;
    arena_options.name = o.arena_name.empty() ? "W" + std::to_string(getpid()) : o.arena_name;
    arena_options.external = o.external;
    arena_options.external_timeout = std::chrono::seconds(o.external_timeout_s);
    arena_options.realtime = o.realtime;
    ev::ArenaEvaluator evaluator(arena_options);
    auto bus = ahhs::bus::OpenBusWithFaultInjection(o.url);
    ev::WorkerNode node(bus.get(), o.id, host, [&](const ev::FarmJob& job) {
      ev::FarmResult out = evaluator.Evaluate(job);
      if (fault_mode == "nan") out.fitness = std::numeric_limits<double>::quiet_NaN();
      if (o.verbose)
        std::cout << "job " << job.job << " attempt " << job.attempt << ": fitness " << out.fitness
                  << (out.message.empty() ? "" : " (" + out.message + ")") << std::endl;
      return out;
    });
    if (!o.quiet)
      std::cerr << "ahhs-worker " << o.id << ": serving "
                << (o.run.empty() ? "any run" : "run " + o.run) << " (" << o.arena << " arena"
                << (o.external.empty() ? std::string()
                                       : " " + arena_options.name + " on " + o.arena_url +
                                             ", external: " + o.external)
                << ") on " << o.url << '\n';
    if (!o.run.empty()) node.ServeOnlyRun(o.run);
    node.Serve([&] { return stop.load(); });
    const auto& c = node.counters();
    if (!o.quiet)
      std::cerr << "ahhs-worker " << o.id << ": " << c.evaluations << " evaluations, " << c.refused
                << " requests of another protocol version refused, " << c.requests.dropped
                << " undecodable messages dropped\n";
  } catch (const std::exception& e) {
    std::cerr << "ahhs-worker: " << e.what() << '\n';
    return 1;
  }
  return 0;
}

}  // namespace ahhs::evolver
