// Typed publish/subscribe on top of a Bus. A message that fails to decode is counted in the
// subscription's counters and dropped; the callback only ever sees valid messages.
#pragma once

#include <ahhs/hinge_command_t.hpp>
#include <ahhs/hormone_packet_t.hpp>
#include <ahhs/module_sensors_t.hpp>
#include <ahhs/sim_state_t.hpp>
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

// Encodes and publishes `msg`. Returns false when it was not sent: a message that cannot be
// encoded (bus/codec.h) or that the transport refused; either is counted in the bus's
// stats().publish_failures and logged.
template <class Msg>
bool PublishTyped(Bus& bus, const std::string& channel, const Msg& msg) {
  // One encode buffer per thread and type, reused: publishing allocates nothing once warm.
  thread_local std::vector<std::uint8_t> bytes;
  const int size = msg.getEncodedSize();
  bytes.resize(static_cast<std::size_t>(size));
  if (size <= 0 || !HasWireText(msg) || msg.encode(bytes.data(), 0, size) != size) {
    bus.CountUnencodable(channel);
    return false;
  }
  return bus.Publish(channel, bytes.data(), bytes.size());
}

// Readies a message object for decoding the next message into it. lcm-gen's decoder resizes an
// array only when its length is not 0 (a zero-length array would keep the previous message's
// elements), so every array must be emptied first. The per-tick types empty theirs and keep the
// capacity, so that decoding them allocates nothing once warm; any other type starts afresh.
// A new array field in one of these types must be added here (tests/bus/codec_test.cc).
template <class Msg>
void ClearForDecode(Msg* msg) {
  *msg = Msg{};
}
inline void ClearForDecode(hormone_packet_t* m) {
  m->to_modules.clear();
  m->amounts.clear();
}
inline void ClearForDecode(hinge_command_t* m) {
  m->values.clear();
  m->present.clear();
}
inline void ClearForDecode(module_sensors_t* m) {
  m->values.clear();
  m->present.clear();
  m->actuator_present.clear();
}
inline void ClearForDecode(sim_state_t* m) {
  m->module.clear();
  m->shape.clear();
  for (auto* v :
       {&m->px, &m->py, &m->pz, &m->qw, &m->qx, &m->qy, &m->qz, &m->sx, &m->sy, &m->sz, &m->mass})
    v->clear();
}

// Subscribes `on_message(const std::string& channel, const Msg& msg)`. `counters` may be null;
// when given it must outlive the subscription. The subscription lasts as long as the returned
// handle.
template <class Msg, class Callback>
Subscription SubscribeTyped(Bus& bus, const std::string& channel_regex, Callback on_message,
                            DecodeCounters* counters = nullptr,
                            int queue_capacity = kDefaultQueueCapacity) {
  // One message object per subscription, decoded into again and again. `msg` is valid only
  // during the callback (a callback must not handle the bus itself).
  auto handler = [on_message = std::move(on_message), counters, msg = std::make_shared<Msg>()](
                     const std::string& channel, const std::uint8_t* data, std::size_t size) {
    ClearForDecode(msg.get());
    if (!Decode(data, size, msg.get())) {
      if (counters != nullptr) ++counters->dropped;
      return;
    }
    if (counters != nullptr) ++counters->decoded;
    on_message(channel, *msg);
  };
  return Subscription(&bus, bus.Subscribe(channel_regex, std::move(handler), queue_capacity));
}

}  // namespace ahhs::bus
