#include "bus/in_process_bus.h"

#include <algorithm>
#include <thread>

namespace ahhs::bus {

const std::vector<InProcessBus::Subscription*>& InProcessBus::Route(const std::string& channel) {
  auto it = routes_.find(channel);
  if (it != routes_.end()) return it->second;
  // First message on this channel since the subscriptions changed: match every expression once.
  std::vector<Subscription*> takers;
  for (const auto& s : subscriptions_)
    if (regexec(&s->pattern, channel.c_str(), 0, nullptr, 0) == 0) takers.push_back(s.get());
  return routes_.emplace(channel, std::move(takers)).first->second;
}

InProcessBus::Slot& InProcessBus::PushSlot() {
  if (count_ == ring_.size()) {
    // Full: unroll the ring so that it starts at 0, then add as many free slots again. Slots
    // are heap objects, so a message being dispatched keeps its address.
    std::rotate(ring_.begin(), ring_.begin() + static_cast<std::ptrdiff_t>(head_), ring_.end());
    head_ = 0;
    const std::size_t grow = std::max<std::size_t>(ring_.size(), 16);
    for (std::size_t k = 0; k < grow; ++k) ring_.push_back(std::make_unique<Slot>());
  }
  Slot& slot = *ring_[(head_ + count_) % ring_.size()];
  ++count_;
  return slot;
}

void InProcessBus::CountUnencodable(const std::string& channel) {
  LogSendFailure(channel, "a string field is not wire text", ++stats_.publish_failures);
}

bool InProcessBus::Publish(const std::string& channel, const void* data, std::size_t size) {
  ++stats_.published;
  const auto& route = Route(channel);
  if (route.empty()) return true;  // nobody listens: LCM's memq drops it the same way
  Slot* slot = nullptr;
  for (Subscription* s : route) {
    if (s->waiting >= s->capacity) continue;  // its queue is full: this one is dropped for it
    if (slot == nullptr) {
      slot = &PushSlot();
      slot->channel.assign(channel);
      const auto* bytes = static_cast<const std::uint8_t*>(data);
      slot->data.assign(bytes, bytes + size);
      slot->takers.clear();
    }
    slot->takers.push_back(s);
    ++s->waiting;
  }
  return true;
}

int InProcessBus::Subscribe(const std::string& channel_regex, RawHandler handler,
                            int queue_capacity) {
  auto s = std::make_unique<Subscription>();
  const std::string whole = "^(" + channel_regex + ")$";  // the whole name, as LCM matches
  const int error = regcomp(&s->pattern, whole.c_str(), REG_EXTENDED | REG_NOSUB);
  if (error != 0) {
    char why[256];
    regerror(error, &s->pattern, why, sizeof why);
    throw BusError("cannot subscribe to '" + channel_regex + "': " + why);
  }
  s->compiled = true;
  s->id = next_id_++;
  s->handler = std::move(handler);
  s->capacity = std::max(1, queue_capacity);
  subscriptions_.push_back(std::move(s));
  routes_.clear();
  return subscriptions_.back()->id;
}

void InProcessBus::Unsubscribe(int subscription_id) {
  auto it = std::find_if(subscriptions_.begin(), subscriptions_.end(),
                         [&](const auto& s) { return s->id == subscription_id; });
  if (it == subscriptions_.end()) return;
  (*it)->active = false;  // queued messages still name it: they skip it from now on
  retired_.push_back(std::move(*it));
  subscriptions_.erase(it);
  routes_.clear();
  if (!dispatching_) ReleaseRetired();
}

void InProcessBus::ReleaseRetired() {
  if (count_ == 0) retired_.clear();
}

int InProcessBus::Handle(std::chrono::microseconds timeout) {
  if (dispatching_) return 0;  // from inside a handler: the running Handle() goes on
  if (count_ == 0) {
    // Nothing can arrive from another thread or process: waiting is only a pace for the caller.
    if (timeout.count() > 0) std::this_thread::sleep_for(timeout);
    return 0;
  }
  dispatching_ = true;
  int dispatched = 0;
  // Handlers may publish; those go to the back of the queue and are handled in this call too,
  // bounded so that handlers answering each other forever cannot hold the caller.
  while (count_ > 0 && dispatched < 100000) {
    Slot* slot = ring_[head_].get();
    bool delivered = false;
    for (std::size_t k = 0; k < slot->takers.size(); ++k) {
      Subscription* s = slot->takers[k];
      --s->waiting;
      if (!s->active) continue;
      delivered = true;
      // A handler must never take the process down: count and drop whatever it throws.
      try {
        s->handler(slot->channel, slot->data.data(), slot->data.size());
        ++stats_.dispatched;
      } catch (...) {
        ++stats_.handler_errors;
      }
    }
    // The slot is still the queue's head: a handler's Publish may have grown the ring, which
    // moves the ring to start at 0 but keeps the order, so pop by position, not by index.
    head_ = (head_ + 1) % ring_.size();
    --count_;
    if (delivered) ++dispatched;
  }
  dispatching_ = false;
  ReleaseRetired();
  return dispatched;
}

}  // namespace ahhs::bus
