// ahhs-view: watch an arena in a browser (docs/viewer.md). One page (three.js) served by an
// embedded civetweb server, fed over a WebSocket:
//   ahhs-view LOG.lcm                        a log of ahhs-launch --log or ahhs-replay --log
//   ahhs-view --lcm-url URL --arena NAME     a live arena (also one already running)
//   ahhs-view --run RUN_DIR                  the newest generation's best of a run, replayed
//   ahhs-view LOG.lcm --video out.mp4        an H.264 video, rendered by headless Chromium
//   ahhs-view LOG.lcm --filmstrip out.png    8 frames across the episode in one PNG
// Options: view_options.h; what is shown and how pages are fed: view_session.h.
#include <atomic>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>

#include "base/children.h"
#include "base/cli.h"
#include "bus/lcm_bus.h"
#include "bus/wire_version.h"
#include "evolver/store/run_store.h"
#include "tools/view/view_options.h"
#include "tools/view/view_session.h"
#include "tools/view/web_server.h"

namespace cli = ahhs::base::cli;

namespace av = ahhs::view;

namespace {

std::atomic<bool> g_stop{false};
void OnSignal(int) { g_stop = true; }

}  // namespace

int main(int argc, char** argv) {
  cli::App app{"ahhs-view: watch an arena, a log or an evolving run in a browser (docs/viewer.md)"};
  av::ViewOptions o;
  o.lcm_url = ahhs::bus::kDefaultLcmUrl;
  o.web_root = ahhs::base::DataDir() + "/web";
  o.three_js = AHHS_THREE_JS;
  av::AddViewOptions(app, &o);
  ahhs::base::SetVersion(
      app, {ahhs::bus::WireVersionLine(), ahhs::evolver::RunStore::FormatVersionLine()});
  if (const int code = ahhs::base::Parse(app, argc, argv); code >= 0) return code;
  av::Json hormones;
  if (const std::string error = av::CheckViewOptions(app, &o, &hormones); !error.empty()) {
    std::cerr << "ahhs-view: " << error << '\n';
    return ahhs::base::kExitUsage;
  }
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  std::signal(SIGPIPE, SIG_IGN);

  std::unique_ptr<av::ViewSession> session;
  std::unique_ptr<av::WebServer> server;
  const bool capture = !o.video.empty() || !o.filmstrip.empty();
  try {
    session = std::make_unique<av::ViewSession>(&o, hormones);
    av::WebServer::Options web;
    web.bind = capture ? "127.0.0.1" : o.bind;
    web.port = capture ? 0 : o.port;
    web.web_root = o.web_root;
    web.three_js = o.three_js;
    web.announce = !capture;
    web.allow_hosts = o.allow_hosts;
    web.max_pages = o.max_pages;
    server = std::make_unique<av::WebServer>(
        web, [&] { return session->Greeting(); },
        [&](const std::string& text) { session->OnPageMessage(text); });
  } catch (const std::exception& e) {
    std::cerr << "ahhs-view: " << e.what() << '\n';
    return ahhs::base::kExitFailure;
  }

  if (capture) {  // headless Chromium films the page (tools/view/ahhs_capture.py)
    std::vector<std::string> args{ahhs::base::ExecutableDir() + "/ahhs-capture"};
    if (!o.video.empty()) {
      args.insert(args.end(), {"video", server->url(), o.video, "--fps", std::to_string(o.fps),
                               "--from", std::to_string(o.from)});
      if (o.to >= 0) args.insert(args.end(), {"--to", std::to_string(o.to)});
    } else {
      args.insert(args.end(),
                  {"filmstrip", server->url(), o.filmstrip, "--frames", std::to_string(o.frames)});
    }
    args.insert(args.end(), {"--size", o.size});
    const int code = ahhs::base::RunChildToEnd(args, [] { return g_stop.load(); });
    return g_stop ? ahhs::base::kExitInterrupted : code;
  }

  std::printf("ahhs-view: %s\nopen %s in a browser (Ctrl-C to stop)\n", session->what().c_str(),
              server->url().c_str());
  std::fflush(stdout);
  return session->Serve(*server, g_stop);
}
