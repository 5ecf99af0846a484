// ahhs-bench controller: nanoseconds per compartment tick of the hormone system.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

namespace ahhs::bench {

struct ControllerBench {
  long ticks = 2000000;
  int repeats = 7;
  std::uint64_t seed = 1;
  std::string only;
  // Declares the subcommand and its options on `app`.
  CLI::App* Add(CLI::App& app);
  void Run() const;
};

}  // namespace ahhs::bench
