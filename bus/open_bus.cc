#include "bus/open_bus.h"

#include "bus/in_process_bus.h"
#include "bus/lcm_bus.h"

namespace ahhs::bus {

std::unique_ptr<Bus> OpenBus(const std::string& url) {
  if (url == kInProcessUrl) return std::make_unique<InProcessBus>();
  if (url.rfind(kInProcessUrl, 0) == 0)
    throw BusError("'" + url + "': inproc:// takes no address or options");
  return std::make_unique<LcmBus>(url);
}

bool IsInProcessUrl(const std::string& url) {
  return url == kInProcessUrl || url.rfind("memq://", 0) == 0;
}

}  // namespace ahhs::bus
