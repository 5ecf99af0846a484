// Typed publish/subscribe on top of a Bus. A message that fails to decode is counted in the
// subscription's counters and dropped; the callback only ever sees valid messages.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bus/bus.h"
#include "bus/codec.h"

namespace ahhs::bus {

struct DecodeCounters {
  std::uint64_t decoded = 0;  // messages passed to the callback
  std::uint64_t dropped = 0;  // messages that failed to decode
};

template <class Msg>
bool PublishTyped(Bus& bus, const std::string& channel, const Msg& msg) {
  // One encode buffer per thread and type, reused: publishing allocates nothing once warm.
  thread_local std::vector<std::uint8_t> bytes;
  const int size = msg.getEncodedSize();
  bytes.resize(static_cast<std::size_t>(size));
  if (size <= 0 || msg.encode(bytes.data(), 0, size) != size) return false;
  return bus.Publish(channel, bytes.data(), bytes.size());
}

// Subscribes `on_message(const std::string& channel, const Msg& msg)`. `counters` may be null;
// when given it must outlive the subscription. Returns the subscription id.
template <class Msg, class Callback>
int SubscribeTyped(Bus& bus, const std::string& channel_regex, Callback on_message,
                   DecodeCounters* counters = nullptr, int queue_capacity = kDefaultQueueCapacity) {
  auto handler = [on_message = std::move(on_message), counters](
                     const std::string& channel, const std::uint8_t* data, std::size_t size) {
    Msg msg;
    if (!Decode(data, size, &msg)) {
      if (counters != nullptr) ++counters->dropped;
      return;
    }
    if (counters != nullptr) ++counters->decoded;
    on_message(channel, msg);
  };
  return bus.Subscribe(channel_regex, std::move(handler), queue_capacity);
}

}  // namespace ahhs::bus
