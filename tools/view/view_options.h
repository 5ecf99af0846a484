// ahhs-view's command line (docs/viewer.md).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "base/cli.h"

namespace ahhs::view {

struct ViewOptions {
  std::string log_file, lcm_url, arena, run_dir;
  std::string bind = "127.0.0.1", web_root, three_js;
  std::string video, filmstrip, size = "1280x720", hormones = "0,1,2";
  int port = 8080, fps = 25, frames = 8, max_pages = 8;
  std::vector<std::string> allow_hosts;
  double rate = 30, from = 0, to = -1, poll = 2;
  bool overwrite = false;
  bool live = false;  // --lcm-url was given: follow a live arena
};

// Declares every option on `app` (`o` holds the defaults, the page's folders included).
void AddViewOptions(base::cli::App& app, ViewOptions* o);

// After parsing: "" and the three hormones shown (`hormones`), or the usage error to print.
std::string CheckViewOptions(const base::cli::App& app, ViewOptions* o, nlohmann::json* hormones);

}  // namespace ahhs::view
