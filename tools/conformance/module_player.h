// ahhs-conformance module: plays the launcher, the sim and two docked neighbours against a module
// controller under test, over a Bus, and judges it (module_checks.h). Three episodes: lockstep
// AHHS2 (with a repeated GENOME and TOPOLOGY, foreign-episode messages and a lost packet),
// lockstep AHHS1 after a RESET, and real time joined at tick 100. The genomes, sensor values and
// packets are drawn from `seed`.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bus/bus.h"
#include "tools/conformance/module_checks.h"

namespace ahhs::conformance {

struct ModulePlayOptions {
  std::string arena;
  int id = 0;  // the module under test; its neighbours are id + 1 and id + 2
  std::uint64_t seed = 1;
  double lost_packet_limit = 1.0;  // s: half the sim's default lockstep timeout
};

std::vector<Check> PlayModule(bus::Bus& bus, const ModulePlayOptions& options,
                              const Budget& budget);

}  // namespace ahhs::conformance
