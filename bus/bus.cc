#include "bus/bus.h"

#include <cstdio>

namespace ahhs::bus {

void LogSendFailure(const std::string& channel, const char* why, std::uint64_t failures) {
  std::uint64_t power = 1;
  while (power * 10 <= failures) power *= 10;
  if (failures != power) return;
  std::fprintf(stderr, "ahhs: could not send on %s: %s (%llu sends failed)\n", channel.c_str(), why,
               static_cast<unsigned long long>(failures));
}

}  // namespace ahhs::bus
