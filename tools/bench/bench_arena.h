// ahhs-bench arena: one gait episode six ways (physics only, no bus, fused, memq, processes,
// watched by ahhs-view, a whole ahhs-launch run).
#pragma once

#include <cstdint>
#include <string>

#include "base/cli.h"

namespace ahhs::bench {

struct ArenaBench {
  std::string url = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";
  std::uint64_t seed = 1;
  int repeats = 3;
  base::cli::App* Add(base::cli::App& app);
  void Run() const;
};

}  // namespace ahhs::bench
