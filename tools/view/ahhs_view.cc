// ahhs-view: watch an arena in a browser (docs/viewer.md). One page (three.js) served by an
// embedded civetweb server, fed over a WebSocket:
//   ahhs-view LOG.lcm                        a log of ahhs-launch --log or ahhs-replay --log
//   ahhs-view --lcm-url URL --arena NAME     a live arena (also one already running)
//   ahhs-view --run RUN_DIR                  the newest generation's best of a run, replayed
//   ahhs-view LOG.lcm --video out.mp4        an H.264 video, rendered by headless Chromium
//   ahhs-view LOG.lcm --filmstrip out.png    8 frames across the episode in one PNG
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <thread>

#include "base/children.h"
#include "base/cli.h"
#include "base/temp_files.h"
#include "bus/channels.h"
#include "bus/fault_bus.h"
#include "bus/lcm_bus.h"
#include "bus/log_reader.h"
#include "evolver/store/run_store.h"
#include "tools/view/live_bridge.h"
#include "tools/view/run_follower.h"
#include "tools/view/view_events.h"
#include "tools/view/web_server.h"

namespace fs = std::filesystem;
namespace av = ahhs::view;

namespace {

std::atomic<bool> g_stop{false};
void OnSignal(int) { g_stop = true; }

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"ahhs-view: watch an arena, a log or an evolving run in a browser (docs/viewer.md)"};
  std::string log_file, lcm_url = ahhs::bus::kDefaultLcmUrl, arena, run_dir;
  std::string bind = "127.0.0.1", web_root = AHHS_VIEW_WEB_ROOT, three_js = AHHS_THREE_JS;
  std::string video, filmstrip, size = "1280x720", hormones = "0,1,2";
  int port = 8080, fps = 25, frames = 8, max_pages = 8;
  std::vector<std::string> allow_hosts;
  double rate = 30, from = 0, to = -1, poll = 2;
  bool overwrite = false;
  app.add_option("log", log_file, "an LCM log to play (ahhs-launch --log, ahhs-replay --log)");
  auto* url_opt = app.add_option("--lcm-url", lcm_url, "follow a live arena on this bus");
  app.add_option("--arena", arena, "the arena to show (default: AHHS live, the first in a log)");
  app.add_option("--run", run_dir, "follow a run directory: its newest generation's best");
  app.add_option("--bind", bind,
                 "address to serve on (default 127.0.0.1: this machine only; 0.0.0.0 only on a "
                 "trusted network, the viewer has no authentication)")
      ->capture_default_str();
  app.add_option("--allow-host", allow_hosts,
                 "answer requests for this host name or address too (a trusted LAN: the name "
                 "or IP address that pages use to reach this machine; repeatable); 127.0.0.1, "
                 "localhost, [::1] and --bind are always allowed")
      ->check([](const std::string& name) { return av::AccessPolicy::CheckName(name); });
  app.add_option("--max-pages", max_pages, "pages that may watch at once")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  app.add_option("--port", port, "HTTP port, 0 for any free one")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  app.add_option("--rate", rate, "live: at most this many updates per second to the page")
      ->check(CLI::Range(1.0, 1000.0))
      ->capture_default_str();
  app.add_option("--hormones", hormones,
                 "the three hormones shown as red, green and blue (module colours)")
      ->capture_default_str();
  app.add_option("--poll", poll, "--run: seconds between looks at the run")
      ->check(CLI::Range(0.1, 3600.0))
      ->capture_default_str();
  app.add_option("--video", video, "with a log: write an H.264 MP4 of its first episode and exit");
  app.add_option("--filmstrip", filmstrip,
                 "with a log: write N frames across it as one PNG and exit");
  app.add_option("--frames", frames, "frames of --filmstrip")
      ->check(CLI::Range(1, 32))
      ->capture_default_str();
  app.add_option("--from", from, "--video: start, simulated seconds")->check(CLI::Range(0.0, 1e6));
  app.add_option("--to", to, "--video: end, simulated seconds (default: the episode's end)")
      ->check(CLI::Range(0.0, 1e6));
  app.add_option("--fps", fps, "--video: frames per second of simulated time")
      ->check(CLI::Range(1, 60))
      ->capture_default_str();
  app.add_option("--size", size, "--video, --filmstrip: frame size WIDTHxHEIGHT")
      ->capture_default_str();
  app.add_flag("--overwrite", overwrite, "replace --video or --filmstrip if it exists");
  app.add_option("--web-root", web_root, "the page's folder")->capture_default_str();
  if (const int code = ahhs::cli::Parse(app, argc, argv); code >= 0) return code;

  const int modes = !log_file.empty() + (url_opt->count() > 0) + !run_dir.empty();
  auto usage = [](const std::string& what) {
    std::cerr << "ahhs-view: " << what << '\n';
    return ahhs::cli::kExitUsage;
  };
  if (modes != 1) return usage("give one of LOG, --lcm-url URL or --run RUN_DIR");
  if ((!video.empty() || !filmstrip.empty()) && log_file.empty())
    return usage("--video and --filmstrip need a LOG (ahhs-replay RUN_DIR --video makes one)");
  if (to >= 0 && to <= from) return usage("--to must be after --from");
  {
    int w = 0, h = 0;
    char x = 0;
    if (std::sscanf(size.c_str(), "%d%c%d", &w, &x, &h) != 3 || x != 'x' || w < 64 || h < 64 ||
        w > 3840 || h > 2160 || w % 2 || h % 2)
      return usage("--size must be WIDTHxHEIGHT, even numbers from 64x64 to 3840x2160");
  }
  nlohmann::json hormone_list = nlohmann::json::array();
  {
    std::stringstream ss(hormones);
    std::string part;
    while (std::getline(ss, part, ',')) {
      try {
        std::size_t used = 0;
        const int h = std::stoi(part, &used);
        if (used != part.size() || h < 0) throw std::invalid_argument(part);
        hormone_list.push_back(h);
      } catch (const std::exception&) {
        return usage("--hormones must be three hormone numbers, like 0,1,2");
      }
    }
    if (hormone_list.size() != 3)
      return usage("--hormones must be three hormone numbers, like 0,1,2");
  }
  const std::string exists = ahhs::cli::RefuseExisting({video, filmstrip}, overwrite);
  if (!exists.empty()) return usage(exists);

  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  std::signal(SIGPIPE, SIG_IGN);

  av::Json hello = {{"type", "hello"}, {"hormones", hormone_list}};
  std::mutex greeting_mutex;
  std::vector<std::string> fixed;  // log mode: the recordings; run mode: the newest
  std::unique_ptr<ahhs::bus::Bus> bus;
  std::unique_ptr<av::LiveBridge> bridge;
  std::unique_ptr<av::RunFollower> follower;
  std::unique_ptr<ahhs::base::TempDir> scratch;  // --run: where the best's episode is recorded
  std::string what;
  try {
    if (!log_file.empty()) {
      std::vector<av::Json> recordings = av::LoadRecordings(log_file, &arena);
      hello["mode"] = "log";
      hello["title"] = fs::path(log_file).filename().string();
      hello["arena"] = arena;
      std::size_t frames_total = 0;
      for (auto& r : recordings) {
        frames_total += r["frames"].size();
        fixed.push_back(r.dump());
      }
      what = log_file + " (arena " + arena + ", " + std::to_string(recordings.size()) +
             " episode(s), " + std::to_string(frames_total) + " states)";
    } else if (!run_dir.empty()) {
      scratch = std::make_unique<ahhs::base::TempDir>("ahhs-view-");
      follower = std::make_unique<av::RunFollower>(run_dir, scratch->path());
      hello["waiting"] = follower->waiting_for();
      hello["mode"] = "run";
      hello["title"] = run_dir;
      what = "run " + run_dir;
    } else {
      if (arena.empty()) arena = ahhs::bus::kDefaultArena;
      bus = ahhs::bus::OpenBusWithFaultInjection(lcm_url);
      bridge = std::make_unique<av::LiveBridge>(*bus, arena);
      hello["mode"] = "live";
      hello["title"] = "arena " + arena;
      hello["arena"] = arena;
      what = "arena " + arena + " on " + lcm_url;
    }
  } catch (const std::exception& e) {
    std::cerr << "ahhs-view: " << e.what() << '\n';
    return ahhs::cli::kExitFailure;
  }
  const bool capture = !video.empty() || !filmstrip.empty();
  if (capture) {
    bind = "127.0.0.1";
    port = 0;
  }

  std::unique_ptr<av::WebServer> server;
  try {
    server = std::make_unique<av::WebServer>(
        [&] {
          av::WebServer::Options o;
          o.bind = bind;
          o.port = port;
          o.web_root = web_root;
          o.three_js = three_js;
          o.announce = !capture;
          o.allow_hosts = allow_hosts;
          o.max_pages = max_pages;
          return o;
        }(),
        [&]() {
          std::vector<std::string> g{hello.dump()};
          std::lock_guard<std::mutex> lock(greeting_mutex);
          g.insert(g.end(), fixed.begin(), fixed.end());
          if (bridge) {
            auto s = bridge->Snapshot();
            g.insert(g.end(), s.begin(), s.end());
          }
          return g;
        },
        [&](const std::string& text) {
          // {"type": "select", "module": M}: a page opened module M's panel.
          const auto m = nlohmann::json::parse(text, nullptr, false);
          if (bridge && m.is_object() && m.value("type", "") == "select" && m.contains("module") &&
              m["module"].is_number_integer())
            bridge->Want(m["module"].get<int>());
        });
  } catch (const std::exception& e) {
    std::cerr << "ahhs-view: " << e.what() << '\n';
    return ahhs::cli::kExitFailure;
  }

  if (capture) {
    const std::string tool = ahhs::base::ExecutableDir() + "/ahhs-capture";
    std::vector<std::string> args{tool};
    if (!video.empty()) {
      args.insert(args.end(), {"video", server->url(), video, "--fps", std::to_string(fps),
                               "--from", std::to_string(from)});
      if (to >= 0) args.insert(args.end(), {"--to", std::to_string(to)});
    } else {
      args.insert(args.end(),
                  {"filmstrip", server->url(), filmstrip, "--frames", std::to_string(frames)});
    }
    args.insert(args.end(), {"--size", size});
    const int code = ahhs::base::RunChildToEnd(args, [] { return g_stop.load(); });
    return g_stop ? ahhs::cli::kExitInterrupted : code;
  }

  std::printf("ahhs-view: %s\nopen %s in a browser (Ctrl-C to stop)\n", what.c_str(),
              server->url().c_str());
  std::fflush(stdout);

  if (bridge) {
    // At --rate: take every message that arrived (the bus queues them), send what changed. The
    // viewer wakes at its own pace, not once per message of the arena it watches.
    const auto period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(1.0 / rate));
    auto next = std::chrono::steady_clock::now();
    while (!g_stop) {
      next = std::max(next + period, std::chrono::steady_clock::now() - period);  // no bursts
      std::this_thread::sleep_until(next);
      while (bus->Handle(std::chrono::microseconds(0)) > 0) {
      }
      bridge->Maintain();
      for (const auto& m : bridge->Drain()) server->Broadcast(m);
    }
    std::printf("ahhs-view: %llu states seen, %llu messages that did not decode\n",
                static_cast<unsigned long long>(bridge->states_seen()),
                static_cast<unsigned long long>(bridge->undecodable()));
  } else if (follower) {
    while (!g_stop) {
      try {
        if (auto r = follower->Poll()) {
          const std::string text = r->dump();
          {
            std::lock_guard<std::mutex> lock(greeting_mutex);
            fixed = {text};
          }
          server->Broadcast(text);
          std::printf("ahhs-view: showing %s\n", (*r)["title"].get<std::string>().c_str());
          std::fflush(stdout);
        }
      } catch (const std::exception& e) {
        std::cerr << "ahhs-view: " << e.what() << '\n';
        return ahhs::cli::kExitFailure;
      }
      for (int i = 0; i < static_cast<int>(poll * 10) && !g_stop; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  } else {
    while (!g_stop) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return 0;
}
