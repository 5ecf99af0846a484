// Opens the bus a URL names, so that a caller can offer every transport with one option.
// (Executables use OpenBusWithFaultInjection() in bus/fault_bus.h, which adds fault injection on
// request.)
#pragma once

#include <memory>
#include <string>

#include "bus/bus.h"

namespace ahhs::bus {

// `inproc://`: an InProcessBus (one process, no system calls; bus/in_process_bus.h). Any other
// URL goes to LCM (udpm://, memq://, file://...): an LcmBus. Throws BusError when the URL is
// unusable.
std::unique_ptr<Bus> OpenBus(const std::string& url);

// Whether `url` keeps every message inside this process (inproc:// or LCM's memq://): the
// transports a fused arena can run on.
bool IsInProcessUrl(const std::string& url);

}  // namespace ahhs::bus
