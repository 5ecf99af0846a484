// Bus over LCM, for any LCM URL: udpm://GROUP:PORT?ttl=0&recv_buf_size=N, memq://, file://...
// Not thread-safe: one thread publishes and handles (with memq:// the bus counts what it
// published so that Handle() never waits in select() for a message it knows is queued).
// Over udpm:// the bus keeps a kernel socket filter on LCM's receive socket that passes only the
// channels its subscriptions can match (bus/channel_filter.h), updated on every Subscribe and
// Unsubscribe before they return; where the socket cannot be found, nothing is filtered.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>

#include "bus/bus.h"

namespace lcm {
class LCM;
}  // namespace lcm
struct _lcm_recv_buf_t;
struct _lcm_subscription_t;

namespace ahhs::bus {

class LcmBus final : public Bus {
 public:
  // Throws BusError when LCM cannot open `url` (bad syntax, no multicast route, ...).
  explicit LcmBus(const std::string& url);
  ~LcmBus() override;
  LcmBus(const LcmBus&) = delete;
  LcmBus& operator=(const LcmBus&) = delete;

  bool Publish(const std::string& channel, const void* data, std::size_t size) override;
  int Subscribe(const std::string& channel_regex, RawHandler handler,
                int queue_capacity = kDefaultQueueCapacity) override;
  void Unsubscribe(int subscription_id) override;
  void CountUnencodable(const std::string& channel) override;
  int Handle(std::chrono::microseconds timeout) override;
  const BusStats& stats() const override { return stats_; }

  const std::string& url() const { return url_; }
  // Whether a channel filter is attached to the receive socket now (udpm:// only).
  bool channel_filter_attached() const { return filter_attached_; }

 private:
  // Subscriptions go through LCM's C API: its C++ wrapper builds a std::string of the channel
  // name for every message (an allocation for names over 15 characters); here each
  // subscription keeps one buffer for it.
  struct Entry {
    RawHandler handler;
    _lcm_subscription_t* subscription = nullptr;
    std::string channel_regex;
    std::string channel;  // the channel of the message being handled
    LcmBus* bus = nullptr;
  };
  static void OnMessage(const _lcm_recv_buf_t* rbuf, const char* channel, void* entry);
  static void Ignore(const _lcm_recv_buf_t* rbuf, const char* channel, void* bus);
  int HandleQueued();          // memq:// only
  void UpdateChannelFilter();  // udpm:// only

  std::string url_;
  std::unique_ptr<lcm::LCM> lcm_;
  std::map<int, std::unique_ptr<Entry>> entries_;
  int next_id_ = 1;
  bool memq_ = false;                // memq://: one thread publishes and handles
  std::int64_t memq_unhandled_ = 0;  // memq://: messages published and not yet handled
  bool delivered_ = false;           // the message being handled reached one of our handlers
  int recv_fd_ = -1;                 // udpm://: LCM's receive socket, when found
  bool filter_attached_ = false;
  BusStats stats_;
};

// The URL used when none is given: host-only multicast (ttl=0) with a receive buffer large
// enough for a lockstep burst.
inline constexpr const char* kDefaultLcmUrl =
    "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";

}  // namespace ahhs::bus
