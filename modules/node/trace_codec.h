// A compartment's controller state <-> MODULE<i>/TRACE (module_trace_t; pure functions).
#pragma once

#include <ahhs/module_trace_t.hpp>
#include <cstdint>
#include <vector>

#include "modules/core/hormone_system.h"

namespace ahhs::modules {

// The trace of one compartment after tick `tick`: the sensors it read (`present` marks the
// slots it owns), its hormones and actuators, the measured hinge angle, and which rules fired
// in the tick: those whose activity counter moved since `previous_activity` (updated here; an
// empty vector counts every rule as quiet before).
module_trace_t TraceMessage(const CompartmentState& state, const std::vector<double>& sensors,
                            const std::vector<bool>& present, std::int64_t episode,
                            std::int64_t tick, int module, double hinge_angle,
                            std::vector<std::uint64_t>* previous_activity);

}  // namespace ahhs::modules
