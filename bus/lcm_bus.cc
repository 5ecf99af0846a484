#include "bus/lcm_bus.h"

#include <dirent.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <lcm/lcm-cpp.hpp>
#include <set>

#include "bus/channel_filter.h"

namespace ahhs::bus {

namespace {

std::set<int> OpenDescriptors() {
  std::set<int> fds;
  if (DIR* dir = opendir("/proc/self/fd")) {
    while (const dirent* e = readdir(dir)) {
      if (e->d_name[0] != '.') fds.insert(std::atoi(e->d_name));
    }
    closedir(dir);
  }
  return fds;
}

// The multicast port of a udpm:// URL (LCM's default 7667 when it names none).
int UdpmPort(const std::string& url) {
  const std::string target =
      url.substr(7, url.find('?') == std::string::npos ? std::string::npos : url.find('?') - 7);
  const auto colon = target.rfind(':');
  return colon == std::string::npos ? 7667 : std::atoi(target.c_str() + colon + 1);
}

bool IsUdpSocketOnPort(int fd, int port) {
  int type = 0;
  socklen_t len = sizeof(type);
  if (getsockopt(fd, SOL_SOCKET, SO_TYPE, &type, &len) != 0 || type != SOCK_DGRAM) return false;
  sockaddr_in addr{};
  len = sizeof(addr);
  return getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) == 0 &&
         addr.sin_family == AF_INET && ntohs(addr.sin_port) == port;
}

// LCM offers no way to reach its udpm receive socket, so find the one UDP socket bound to the
// URL's port that it opened since `before` (the receive socket is opened when the LCM instance
// is created or, in some versions, on the first call that needs it, such as getFileno()).
int FindLcmReceiveSocket(lcm::LCM& lcm, const std::string& url, const std::set<int>& before) {
  if (lcm.getFileno() < 0) return -1;
  const int port = UdpmPort(url);
  int found = -1;
  for (int fd : OpenDescriptors()) {
    if (before.count(fd) || !IsUdpSocketOnPort(fd, port)) continue;
    if (found >= 0) return -1;  // ambiguous (another thread opened one too): do not filter
    found = fd;
  }
  return found;
}

}  // namespace

LcmBus::LcmBus(const std::string& url) : url_(url) {
  const std::set<int> fds_before = OpenDescriptors();
  lcm_ = std::make_unique<lcm::LCM>(url);
  if (!lcm_->good()) {
    throw BusError("cannot open LCM bus '" + url +
                   "' (check the URL; udpm:// needs a multicast route, see docs/protocol.md)");
  }
  if (url.rfind("memq://", 0) == 0) {
    // LCM's memq provider queues a message only when some subscription matches its channel;
    // with this catch-all every published message is queued, so we know how many are waiting.
    memq_ = true;
    lcm_subscription_t* all = lcm_subscribe(lcm_->getUnderlyingLCM(), ".*", &LcmBus::Ignore, this);
    if (all == nullptr) throw BusError("cannot subscribe to every channel of '" + url + "'");
    lcm_subscription_set_queue_capacity(all, 1 << 30);
  }
  if (url.rfind("udpm://", 0) == 0) {
    recv_fd_ = FindLcmReceiveSocket(*lcm_, url, fds_before);
    UpdateChannelFilter();  // nothing subscribed yet: no LCM message is wanted
  }
}

void LcmBus::UpdateChannelFilter() {
  if (recv_fd_ < 0) return;
  std::vector<std::string> prefixes;
  for (const auto& [id, entry] : entries_) prefixes.push_back(ChannelPrefix(entry->channel_regex));
  std::vector<sock_filter> program = BuildChannelFilter(prefixes, 8);  // after the UDP header
  if (program.empty()) {
    if (filter_attached_) {
      int unused = 0;
      setsockopt(recv_fd_, SOL_SOCKET, SO_DETACH_FILTER, &unused, sizeof(unused));
    }
    filter_attached_ = false;
    return;
  }
  sock_fprog fprog{static_cast<unsigned short>(program.size()), program.data()};
  // On failure the previous filter would stay, which could be too strict: then filter nothing.
  if (setsockopt(recv_fd_, SOL_SOCKET, SO_ATTACH_FILTER, &fprog, sizeof(fprog)) == 0) {
    filter_attached_ = true;
  } else {
    int unused = 0;
    setsockopt(recv_fd_, SOL_SOCKET, SO_DETACH_FILTER, &unused, sizeof(unused));
    filter_attached_ = false;
    recv_fd_ = -1;
  }
}

LcmBus::~LcmBus() {
  for (auto& [id, entry] : entries_) lcm_unsubscribe(lcm_->getUnderlyingLCM(), entry->subscription);
}

bool LcmBus::Publish(const std::string& channel, const void* data, std::size_t size) {
  if (lcm_->publish(channel, data, static_cast<unsigned int>(size)) != 0) {
    LogSendFailure(channel, "the transport refused the message", ++stats_.publish_failures);
    return false;
  }
  ++stats_.published;
  if (memq_) ++memq_unhandled_;
  return true;
}

void LcmBus::CountUnencodable(const std::string& channel) {
  LogSendFailure(channel, "a string field is not wire text", ++stats_.publish_failures);
}

void LcmBus::Ignore(const lcm_recv_buf_t*, const char*, void*) {}

void LcmBus::OnMessage(const lcm_recv_buf_t* rbuf, const char* channel, void* user) {
  auto* entry = static_cast<Entry*>(user);
  entry->bus->delivered_ = true;
  entry->channel.assign(channel);  // reuses the buffer's capacity
  // A handler must never take the process down: count and drop whatever it throws.
  try {
    entry->handler(entry->channel, static_cast<const std::uint8_t*>(rbuf->data), rbuf->data_size);
    ++entry->bus->stats_.dispatched;
  } catch (...) {
    ++entry->bus->stats_.handler_errors;
  }
}

int LcmBus::Subscribe(const std::string& channel_regex, RawHandler handler, int queue_capacity) {
  auto entry = std::make_unique<Entry>();
  entry->handler = std::move(handler);
  entry->bus = this;
  entry->channel_regex = channel_regex;
  entry->subscription = lcm_subscribe(lcm_->getUnderlyingLCM(), channel_regex.c_str(),
                                      &LcmBus::OnMessage, entry.get());
  if (entry->subscription == nullptr) throw BusError("cannot subscribe to '" + channel_regex + "'");
  lcm_subscription_set_queue_capacity(entry->subscription, std::max(1, queue_capacity));
  const int id = next_id_++;
  entries_.emplace(id, std::move(entry));
  UpdateChannelFilter();
  return id;
}

void LcmBus::Unsubscribe(int subscription_id) {
  auto it = entries_.find(subscription_id);
  if (it == entries_.end()) return;
  lcm_unsubscribe(lcm_->getUnderlyingLCM(), it->second->subscription);
  entries_.erase(it);
  UpdateChannelFilter();
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
