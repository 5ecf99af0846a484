#include "bus/fault_bus.h"

#include <cstdlib>
#include <string>

#include "bus/open_bus.h"

namespace ahhs::bus {

FaultBus::FaultBus(std::unique_ptr<Bus> inner, double drop_rate, std::uint64_t seed)
    : inner_(std::move(inner)), drop_rate_(drop_rate), rng_(seed) {}

int FaultBus::Subscribe(const std::string& channel_regex, RawHandler handler, int queue_capacity) {
  return inner_->Subscribe(
      channel_regex,
      [this, handler = std::move(handler)](const std::string& channel, const std::uint8_t* data,
                                           std::size_t size) {
        if (static_cast<double>(rng_() >> 11) * 0x1.0p-53 < drop_rate_) {
          ++dropped_;
          return;
        }
        handler(channel, data, size);
      },
      queue_capacity);
}

std::unique_ptr<Bus> OpenBusWithFaultInjection(const std::string& url) {
  auto bus = OpenBus(url);
  const char* drop = std::getenv("AHHS_FAULT_DROP");
  if (drop == nullptr || *drop == '\0') return bus;
  char* end = nullptr;
  const double rate = std::strtod(drop, &end);
  if (*end != '\0' || !(rate >= 0.0 && rate <= 1.0))
    throw BusError(std::string("AHHS_FAULT_DROP must be a number in [0, 1], not '") + drop + "'");
  const char* seed = std::getenv("AHHS_FAULT_SEED");
  return std::make_unique<FaultBus>(std::move(bus), rate,
                                    seed ? std::strtoull(seed, nullptr, 10) : 1);
}

}  // namespace ahhs::bus
