// ahhs-bench evolve: whole evolution runs through ahhs-evolve, timed from the outside.
#pragma once

#include <string>

#include "base/cli.h"

namespace ahhs::bench {

struct EvolveBench {
  std::string task = "all", url = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304",
              envelope = "none";
  int generations = 200, workers = -1, trials = 1;
  base::cli::App* Add(base::cli::App& app);
  void Run() const;
};

}  // namespace ahhs::bench
