// ahhs-bench controller: nanoseconds per compartment tick of the hormone system.
#pragma once

#include <cstdint>
#include <string>

#include "base/cli.h"

namespace ahhs::bench {

struct ControllerBench {
  long ticks = 2000000;
  int repeats = 7;
  std::uint64_t seed = 1;
  std::string only;
  // Declares the subcommand and its options on `app`.
  base::cli::App* Add(base::cli::App& app);
  void Run() const;
};

}  // namespace ahhs::bench
