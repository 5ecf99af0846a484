// Fault injection for tests: a Bus that loses a fraction of the messages it receives, with a
// seeded generator so a test run is repeatable. Every executable builds its bus with
// OpenBusWithFaultInjection(), which wraps the bus of its URL in a FaultBus when the environment
// asks for it:
//   AHHS_FAULT_DROP=0.05   drop 5 % of received messages (per subscription delivery)
//   AHHS_FAULT_SEED=7      seed of the drop decisions (default 1)
#pragma once

#include <memory>
#include <random>

#include "bus/bus.h"

namespace ahhs::bus {

class FaultBus final : public Bus {
 public:
  FaultBus(std::unique_ptr<Bus> inner, double drop_rate, std::uint64_t seed);

  bool Publish(const std::string& channel, const void* data, std::size_t size) override {
    return inner_->Publish(channel, data, size);
  }
  int Subscribe(const std::string& channel_regex, RawHandler handler, int queue_capacity) override;
  void Unsubscribe(int id) override { inner_->Unsubscribe(id); }
  int Handle(std::chrono::microseconds timeout) override { return inner_->Handle(timeout); }
  void CountUnencodable(const std::string& channel) override { inner_->CountUnencodable(channel); }
  const BusStats& stats() const override { return inner_->stats(); }

  std::uint64_t dropped() const { return dropped_; }

 private:
  std::unique_ptr<Bus> inner_;
  double drop_rate_;
  std::mt19937_64 rng_;
  std::uint64_t dropped_ = 0;
};

// The bus for `url` (OpenBus, bus/open_bus.h), wrapped in a FaultBus when AHHS_FAULT_DROP is
// set (see above).
// Throws BusError for a bad URL or a bad AHHS_FAULT_DROP value.
std::unique_ptr<Bus> OpenBusWithFaultInjection(const std::string& url);

}  // namespace ahhs::bus
