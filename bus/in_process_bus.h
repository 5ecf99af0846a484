// A bus inside one process, for the fused arena (URL `inproc://`): what is published is copied
// into one first-in-first-out queue and dispatched by the next Handle() on the same thread, as
// LCM's memq:// provider does, but without its notification pipe (a write and a read system call
// per message), its mutex and its per-message allocations. Messages are the same encoded LCM
// bytes, so the node classes cannot tell the two apart and the results are the same to the bit.
//
// Semantics (those of LcmBus over memq://):
// - a subscription takes every channel its regular expression matches as a whole (LCM anchors
//   the expression at both ends); several subscriptions may take the same message, in the order
//   they were made. Expressions are POSIX extended ones; LCM's are PCRE, which reads the common
//   part (literals, `.`, `*`, `+`, `?`, `[...]`, `|`, groups) the same way;
// - a message is queued for the subscriptions that match when it is published; one that nobody
//   hears is counted as published and dropped;
// - Handle() dispatches everything queued, including what handlers publish meanwhile, and
//   returns how many messages reached a handler; with nothing queued it waits `timeout` (nothing
//   can arrive from elsewhere) and returns 0;
// - a subscription with `queue_capacity` messages waiting does not take more until the next
//   Handle() (the newest are dropped, as LCM drops them);
// - a handler that throws is counted in stats().handler_errors; Unsubscribe() from inside a
//   handler is allowed and takes effect at once; Handle() from inside a handler returns 0.
// Not thread-safe: one thread publishes and handles. Nothing here does I/O or system calls.
#pragma once

#include <regex.h>

#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "bus/bus.h"

namespace ahhs::bus {

inline constexpr const char* kInProcessUrl = "inproc://";

class InProcessBus final : public Bus {
 public:
  InProcessBus() = default;
  InProcessBus(const InProcessBus&) = delete;
  InProcessBus& operator=(const InProcessBus&) = delete;

  bool Publish(const std::string& channel, const void* data, std::size_t size) override;
  int Subscribe(const std::string& channel_regex, RawHandler handler,
                int queue_capacity = kDefaultQueueCapacity) override;
  void Unsubscribe(int subscription_id) override;
  void CountUnencodable(const std::string& channel) override;
  int Handle(std::chrono::microseconds timeout) override;
  const BusStats& stats() const override { return stats_; }

  // Messages queued and not yet dispatched.
  std::size_t queued() const { return count_; }

 private:
  struct Subscription {
    Subscription() = default;
    Subscription(const Subscription&) = delete;
    Subscription& operator=(const Subscription&) = delete;
    ~Subscription() {
      if (compiled) regfree(&pattern);
    }
    int id = 0;
    regex_t pattern{};
    bool compiled = false;
    RawHandler handler;
    int capacity = kDefaultQueueCapacity;
    int waiting = 0;  // messages queued for it
    bool active = true;
  };
  // One queued message: its bytes and the subscriptions it was queued for. Slots are reused,
  // so in a steady state publishing allocates nothing.
  struct Slot {
    std::string channel;
    std::vector<std::uint8_t> data;
    std::vector<Subscription*> takers;
  };

  // The subscriptions whose expression matches `channel`, cached per channel name (the cache is
  // rebuilt after every Subscribe and Unsubscribe).
  const std::vector<Subscription*>& Route(const std::string& channel);
  Slot& PushSlot();
  void ReleaseRetired();

  std::vector<std::unique_ptr<Subscription>> subscriptions_;  // in subscription order
  // Unsubscribed while messages for them were queued: kept until the queue is empty.
  std::vector<std::unique_ptr<Subscription>> retired_;
  std::unordered_map<std::string, std::vector<Subscription*>> routes_;
  std::vector<std::unique_ptr<Slot>> ring_;  // circular: count_ slots from head_
  std::size_t head_ = 0, count_ = 0;
  int next_id_ = 1;
  bool dispatching_ = false;
  BusStats stats_;
};

}  // namespace ahhs::bus
