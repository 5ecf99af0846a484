// ahhs-bench sim: wall time of physics-only episodes with the built-in drives.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

namespace ahhs::bench {

struct SimBench {
  int repeats = 5;
  std::uint64_t seed = 1;
  int seeds = 1;
  std::string solver = "chain";
  CLI::App* Add(CLI::App& app);
  void Run() const;
};

}  // namespace ahhs::bench
