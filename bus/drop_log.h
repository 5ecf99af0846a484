// Why messages were dropped, per channel: what a role reports at the end of an episode and in its
// STATUS, so that a hardware bring-up sees "11 SENSORS (NaN)" rather than a bare count
// (docs/protocol.md, "Dropped messages"). Pure; no bus.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>

#include "bus/typed.h"

namespace ahhs::bus {

class DropLog {
 public:
  // `channel` as a reader knows it, without the arena prefix ("SENSORS", "SIM/STATE").
  void Count(const std::string& channel, const std::string& reason, std::uint64_t n = 1) {
    if (n > 0) counts_[{channel, reason}] += n;
  }
  // Messages of `channel` that did not decode, as a subscription counted them.
  void CountUndecodable(const std::string& channel, const DecodeCounters& counters) {
    Count(channel, "undecodable", counters.dropped);
  }
  std::uint64_t total() const {
    std::uint64_t sum = 0;
    for (const auto& [key, n] : counts_) sum += n;
    return sum;
  }
  // "11 SENSORS (NaN or out of range), 2 HORMONE (another episode)", by channel and reason;
  // "" when nothing was dropped.
  std::string Summary() const {
    std::string out;
    for (const auto& [key, n] : counts_)
      out +=
          (out.empty() ? "" : ", ") + std::to_string(n) + " " + key.first + " (" + key.second + ")";
    return out;
  }
  void Clear() { counts_.clear(); }
  // Both logs' counts.
  DropLog& operator+=(const DropLog& other) {
    for (const auto& [key, n] : other.counts_) counts_[key] += n;
    return *this;
  }

 private:
  std::map<std::pair<std::string, std::string>, std::uint64_t> counts_;
};

}  // namespace ahhs::bus
