#include "bus/lcm_bus.h"

#include <algorithm>
#include <exception>
#include <lcm/lcm-cpp.hpp>

namespace ahhs::bus {

LcmBus::LcmBus(const std::string& url) : url_(url), lcm_(std::make_unique<lcm::LCM>(url)) {
  if (!lcm_->good()) {
    throw BusError("cannot open LCM bus '" + url +
                   "' (check the URL; udpm:// needs a multicast route, see docs/protocol.md)");
  }
  if (url.rfind("memq://", 0) == 0) {
    // LCM's memq provider queues a message only when some subscription matches its channel;
    // with this catch-all every published message is queued, so we know how many are waiting.
    memq_ = true;
    lcm::Subscription* all = lcm_->subscribeFunction(".*", &LcmBus::Ignore, this);
    if (all == nullptr) throw BusError("cannot subscribe to every channel of '" + url + "'");
    all->setQueueCapacity(1 << 30);
  }
}

LcmBus::~LcmBus() {
  for (auto& [id, entry] : entries_) lcm_->unsubscribe(entry->subscription);
}

bool LcmBus::Publish(const std::string& channel, const void* data, std::size_t size) {
  if (lcm_->publish(channel, data, static_cast<unsigned int>(size)) != 0) {
    ++stats_.publish_failures;
    return false;
  }
  ++stats_.published;
  if (memq_) ++memq_unhandled_;
  return true;
}

void LcmBus::Ignore(const lcm::ReceiveBuffer*, const std::string&, LcmBus*) {}

void LcmBus::OnMessage(const lcm::ReceiveBuffer* rbuf, const std::string& channel, Entry* entry) {
  // A handler must never take the process down: count and drop whatever it throws.
  entry->bus->delivered_ = true;
  try {
    entry->handler(channel, static_cast<const std::uint8_t*>(rbuf->data), rbuf->data_size);
    ++entry->bus->stats_.dispatched;
  } catch (...) {
    ++entry->bus->stats_.handler_errors;
  }
}

int LcmBus::Subscribe(const std::string& channel_regex, RawHandler handler, int queue_capacity) {
  auto entry = std::make_unique<Entry>();
  entry->handler = std::move(handler);
  entry->bus = this;
  entry->subscription = lcm_->subscribeFunction(channel_regex, &LcmBus::OnMessage, entry.get());
  if (entry->subscription == nullptr) throw BusError("cannot subscribe to '" + channel_regex + "'");
  entry->subscription->setQueueCapacity(std::max(1, queue_capacity));
  const int id = next_id_++;
  entries_.emplace(id, std::move(entry));
  return id;
}

void LcmBus::Unsubscribe(int subscription_id) {
  auto it = entries_.find(subscription_id);
  if (it == entries_.end()) return;
  lcm_->unsubscribe(it->second->subscription);
  entries_.erase(it);
}

int LcmBus::HandleQueued() {
  // Every message we published is queued (the catch-all subscription sees to it) and handle()
  // dispatches exactly one, so handle() is called once per unhandled message and never blocks:
  // no select() per message, which in the fused arena cost more than decoding the messages.
  // Handlers may publish; those are handled in the same call.
  int dispatched = 0;
  while (memq_unhandled_ > 0 && dispatched < 100000) {
    --memq_unhandled_;
    delivered_ = false;
    if (lcm_->handle() != 0) break;
    if (delivered_) ++dispatched;
  }
  return dispatched;
}

int LcmBus::Handle(std::chrono::microseconds timeout) {
  if (memq_) {
    const bool any = memq_unhandled_ > 0;
    const int dispatched = HandleQueued();
    // Nothing was queued: a memq bus is private to its LCM instance, so nothing can arrive; a
    // caller that asked to wait (a real-time pace) still waits, below.
    if (any || timeout.count() <= 0) return dispatched;
  }
  // LCM waits in whole milliseconds; round up so a short timeout still waits.
  const auto wait_ms = static_cast<int>((std::max<std::int64_t>(timeout.count(), 0) + 999) / 1000);
  int dispatched = 0;
  if (lcm_->handleTimeout(wait_ms) <= 0) return 0;
  ++dispatched;
  // Drain what is already waiting, bounded so a flood cannot starve the caller forever.
  while (dispatched < 100000 && lcm_->handleTimeout(0) > 0) ++dispatched;
  return dispatched;
}

}  // namespace ahhs::bus

#include <chrono>

#include "bus/channels.h"

namespace ahhs::bus {
std::int64_t NowUtime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}
}  // namespace ahhs::bus
