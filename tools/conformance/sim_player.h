// ahhs-conformance sim: plays the launcher and an operator's button against an episode server in
// real time (ahhs-sim, ahhs-sim --physics none, or a server of one's own) and judges it
// (sim_checks.h). A gait chain of 3 modules: a full episode of 2 s with another episode's PAUSE
// and STOP in its middle, an episode stopped at tick 10, and a RESET of an unknown scenario.
#pragma once

#include <string>
#include <vector>

#include "bus/bus.h"
#include "tools/conformance/sim_checks.h"

namespace ahhs::conformance {

struct SimPlayOptions {
  std::string arena;
};

std::vector<Check> PlaySim(bus::Bus& bus, const SimPlayOptions& options, const Budget& budget);

}  // namespace ahhs::conformance
