// ahhs-conformance's counterpart roles over a Bus: plays an episode server's SIM/CLOCK (and a
// controller's HINGE commands for a firmware) and records what the implementation under test
// publishes (docs/hardware.md, "Conformance kit").
#pragma once

#include <vector>

#include "bus/bus.h"
#include "tools/conformance/checks.h"

namespace ahhs::conformance {

struct PlayOptions {
  std::string arena;
  int id = 0;       // firmware: the module under test
  int modules = 3;  // tracker: bodies expected
  int ticks = 40;
  double period = 0.05;
  double commanded = 0.5;        // firmware: hinge target in the second half of a phase
  double foreign_target = -1.0;  // firmware: target of a foreign episode's HINGE
};

// Both return the clock played and fill `seen` with what arrived, then judge it.
std::vector<Check> PlayFirmware(bus::Bus& bus, const PlayOptions& options, const Budget& budget);
std::vector<Check> PlayTracker(bus::Bus& bus, const PlayOptions& options, const Budget& budget);

}  // namespace ahhs::conformance
