// ahhs-bench sim: wall time of physics-only episodes with the built-in drives.
#pragma once

#include <cstdint>
#include <string>

#include "base/cli.h"

namespace ahhs::bench {

struct SimBench {
  int repeats = 5;
  std::uint64_t seed = 1;
  int seeds = 1;
  std::string solver = "chain";
  base::cli::App* Add(base::cli::App& app);
  void Run() const;
};

}  // namespace ahhs::bench
