// The message bus as an injectable interface. Nodes talk only to a Bus, so the same node runs
// over udpm:// (separate processes or hosts), memq:// (one process, the fused arena) or a log.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>

namespace ahhs::bus {

// Thrown by bus constructors for an unusable URL or transport; never thrown from Handle().
class BusError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Receives one raw message. `data` is valid only during the call.
using RawHandler =
    std::function<void(const std::string& channel, const std::uint8_t* data, std::size_t size)>;

// Messages a subscription buffers between two Handle() calls before messages are dropped.
// LCM's own default is 30, far too few for a lockstep tick with many modules.
inline constexpr int kDefaultQueueCapacity = 10000;

// Counters of one bus, for diagnostics and tests.
struct BusStats {
  std::uint64_t published = 0;         // messages handed to the transport
  std::uint64_t publish_failures = 0;  // sends that failed: refused by the transport, or a
                                       // message that could not be encoded (CountUnencodable)
  std::uint64_t dispatched = 0;        // messages passed to a handler
  std::uint64_t handler_errors = 0;    // handlers that threw (caught, counted, message dropped)
};

class Bus {
 public:
  virtual ~Bus() = default;

  // Publishes `size` bytes on `channel`. Returns false when the transport refused them.
  virtual bool Publish(const std::string& channel, const void* data, std::size_t size) = 0;

  // Subscribes `handler` to every channel matching the regular expression `channel_regex`
  // (LCM semantics: the whole channel name must match). Returns a subscription id.
  virtual int Subscribe(const std::string& channel_regex, RawHandler handler,
                        int queue_capacity = kDefaultQueueCapacity) = 0;
  virtual void Unsubscribe(int subscription_id) = 0;

  // Counts a message for `channel` that its sender could not encode (a string that is not wire
  // text, bus/wire_text.h) as a publish failure, and logs it (LogSendFailure).
  virtual void CountUnencodable(const std::string& channel) = 0;

  // Waits at most `timeout` for a message, then dispatches every message already waiting.
  // Returns the number of messages dispatched (0 on timeout). Handlers that throw are caught
  // and counted in stats().handler_errors.
  virtual int Handle(std::chrono::microseconds timeout) = 0;

  virtual const BusStats& stats() const = 0;
};

// A send that failed is never silent: a line on stderr, "ahhs: could not send on CHANNEL:
// WHY (N sends failed)", for the 1st, 10th, 100th, ... failure (`failures` counts them).
void LogSendFailure(const std::string& channel, const char* why, std::uint64_t failures);

// A subscription that ends itself: destroying (or reset()ting) it unsubscribes, as Drake's
// DrakeSubscriptionInterface does, so a node that subscribes callbacks on `this` can never be
// called after it is gone. Movable, not copyable; the bus must outlive it.
class [[nodiscard]] Subscription {
 public:
  Subscription() = default;
  Subscription(Bus* bus, int id) : bus_(bus), id_(id) {}
  ~Subscription() { reset(); }
  Subscription(Subscription&& other) noexcept : bus_(other.bus_), id_(other.id_) {
    other.bus_ = nullptr;
  }
  Subscription& operator=(Subscription&& other) noexcept {
    if (this != &other) {
      reset();
      bus_ = other.bus_;
      id_ = other.id_;
      other.bus_ = nullptr;
    }
    return *this;
  }
  Subscription(const Subscription&) = delete;
  Subscription& operator=(const Subscription&) = delete;

  void reset() {
    if (bus_ != nullptr) bus_->Unsubscribe(id_);
    bus_ = nullptr;
  }
  bool active() const { return bus_ != nullptr; }

 private:
  Bus* bus_ = nullptr;
  int id_ = -1;
};

}  // namespace ahhs::bus
