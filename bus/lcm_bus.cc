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
  return true;
}

void LcmBus::OnMessage(const lcm::ReceiveBuffer* rbuf, const std::string& channel, Entry* entry) {
  // A handler must never take the process down: count and drop whatever it throws.
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

int LcmBus::Handle(std::chrono::microseconds timeout) {
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
