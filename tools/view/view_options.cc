#include "tools/view/view_options.h"

#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "base/cli.h"
#include "tools/view/access_policy.h"

namespace cli = ahhs::base::cli;

namespace ahhs::view {
namespace av = ahhs::view;

void AddViewOptions(cli::App& app, ViewOptions* o) {
  app.add_option("log", o->log_file, "an LCM log to play (ahhs-launch --log, ahhs-replay --log)");
  app.add_option("--lcm-url", o->lcm_url, "follow a live arena on this bus");
  app.add_option("--arena", o->arena, "the arena to show (default: AHHS live, the first in a log)");
  app.add_option("--run", o->run_dir, "follow a run directory: its newest generation's best");
  app.add_option("--bind", o->bind,
                 "address to serve on (default 127.0.0.1: this machine only; 0.0.0.0 only on a "
                 "trusted network, the viewer has no authentication)")
      ->capture_default_str();
  app.add_option("--allow-host", o->allow_hosts,
                 "answer requests for this host name or address too (a trusted LAN: the name "
                 "or IP address that pages use to reach this machine; repeatable); 127.0.0.1, "
                 "localhost, [::1] and --bind are always allowed")
      ->check([](const std::string& name) { return av::AccessPolicy::CheckName(name); });
  app.add_option("--max-pages", o->max_pages, "pages that may watch at once")
      ->check(cli::Range(1, 64))
      ->capture_default_str();
  app.add_option("--port", o->port, "HTTP port, 0 for any free one")
      ->check(cli::Range(0, 65535))
      ->capture_default_str();
  app.add_option("--rate", o->rate, "live: at most this many updates per second to the page")
      ->check(cli::Range(1.0, 1000.0))
      ->capture_default_str();
  app.add_option("--hormones", o->hormones,
                 "the three hormones shown as red, green and blue (module colours)")
      ->capture_default_str();
  app.add_option("--poll", o->poll, "--run: seconds between looks at the run")
      ->check(cli::Range(0.1, 3600.0))
      ->capture_default_str();
  app.add_option("--video", o->video,
                 "with a log: write an H.264 MP4 of its first episode and exit");
  app.add_option("--filmstrip", o->filmstrip,
                 "with a log: write N frames across it as one PNG and exit");
  app.add_option("--frames", o->frames, "frames of --filmstrip")
      ->check(cli::Range(1, 32))
      ->capture_default_str();
  app.add_option("--from", o->from, "--video: start, simulated seconds")
      ->check(cli::Range(0.0, 1e6));
  app.add_option("--to", o->to, "--video: end, simulated seconds (default: the episode's end)")
      ->check(cli::Range(0.0, 1e6));
  app.add_option("--fps", o->fps, "--video: frames per second of simulated time")
      ->check(cli::Range(1, 60))
      ->capture_default_str();
  app.add_option("--size", o->size, "--video, --filmstrip: frame size WIDTHxHEIGHT")
      ->capture_default_str();
  app.add_flag("--overwrite", o->overwrite, "replace --video or --filmstrip if it exists");
  app.add_option("--web-root", o->web_root, "the page's folder")->capture_default_str();
}

std::string CheckViewOptions(const cli::App& app, ViewOptions* o, nlohmann::json* hormone_list) {
  o->live = app.count("--lcm-url") > 0;
  const int modes = !o->log_file.empty() + o->live + !o->run_dir.empty();
  if (modes != 1) return "give one of LOG, --lcm-url URL or --run RUN_DIR";
  if ((!o->video.empty() || !o->filmstrip.empty()) && o->log_file.empty())
    return "--video and --filmstrip need a LOG (ahhs-replay RUN_DIR --video makes one)";
  if (o->to >= 0 && o->to <= o->from) return "--to must be after --from";
  {
    int w = 0, h = 0;
    char x = 0;
    if (std::sscanf(o->size.c_str(), "%d%c%d", &w, &x, &h) != 3 || x != 'x' || w < 64 || h < 64 ||
        w > 3840 || h > 2160 || w % 2 || h % 2)
      return "--size must be WIDTHxHEIGHT, even numbers from 64x64 to 3840x2160";
  }
  *hormone_list = nlohmann::json::array();
  {
    std::stringstream ss(o->hormones);
    std::string part;
    while (std::getline(ss, part, ',')) {
      try {
        std::size_t used = 0;
        const int h = std::stoi(part, &used);
        if (used != part.size() || h < 0) throw std::invalid_argument(part);
        hormone_list->push_back(h);
      } catch (const std::exception&) {
        return "--hormones must be three hormone numbers, like 0,1,2";
      }
    }
    if (hormone_list->size() != 3) return "--hormones must be three hormone numbers, like 0,1,2";
  }
  const std::string exists = ahhs::base::RefuseExisting({o->video, o->filmstrip}, o->overwrite);
  return exists;
}

}  // namespace ahhs::view
