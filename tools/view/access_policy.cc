#include "tools/view/access_policy.h"

#include <algorithm>
#include <cctype>

namespace ahhs::view {

namespace {

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// Whether `name` already ends in :PORT ("[::1]" has colons but no port).
bool HasPort(const std::string& name) {
  const auto colon = name.rfind(':');
  if (colon == std::string::npos || colon + 1 == name.size()) return false;
  if (name.front() == '[' && name.find(']') > colon) return false;   // inside an IPv6 literal
  if (name.front() != '[' && name.find(':') != colon) return false;  // a bare IPv6 address
  return std::all_of(name.begin() + static_cast<long>(colon) + 1, name.end(),
                     [](unsigned char c) { return std::isdigit(c); });
}

}  // namespace

AccessPolicy::AccessPolicy(const std::string& bind, int port,
                           const std::vector<std::string>& extra) {
  const std::string p = std::to_string(port);
  auto add = [&](const std::string& name) {
    const std::string n = Lower(name);
    if (HasPort(n)) {
      hosts_.push_back(n);
      return;
    }
    hosts_.push_back(n + ":" + p);
    if (port == 80) hosts_.push_back(n);
  };
  for (const char* name : {"127.0.0.1", "localhost", "[::1]"}) add(name);
  if (bind != "0.0.0.0" && bind != "::" && bind != "[::]" && !bind.empty())
    add(bind.find(':') != std::string::npos && bind.front() != '[' ? "[" + bind + "]" : bind);
  for (const auto& name : extra) add(name);
  std::sort(hosts_.begin(), hosts_.end());
  hosts_.erase(std::unique(hosts_.begin(), hosts_.end()), hosts_.end());
}

bool AccessPolicy::HostAllowed(const char* host) const {
  if (host == nullptr) return false;
  return std::binary_search(hosts_.begin(), hosts_.end(), Lower(host));
}

bool AccessPolicy::OriginAllowed(const char* origin) const {
  if (origin == nullptr) return true;
  const std::string o = Lower(origin);
  const std::string scheme = "http://";
  if (o.compare(0, scheme.size(), scheme) != 0) return false;
  return std::binary_search(hosts_.begin(), hosts_.end(), o.substr(scheme.size()));
}

std::string AccessPolicy::Describe() const {
  std::string s;
  for (const auto& h : hosts_) s += (s.empty() ? "" : ", ") + h;
  return s;
}

std::string AccessPolicy::CheckName(const std::string& name) {
  if (name.empty()) return "an empty name";
  if (std::count(name.begin(), name.end(), ':') > 1 && name.front() != '[')
    return "'" + name + "': write an IPv6 address in brackets, like [fe80::1]";
  for (unsigned char c : name)
    if (!(std::isalnum(c) || c == '.' || c == '-' || c == ':' || c == '[' || c == ']'))
      return "'" + name + "' is not a host name or address (letters, digits, '.', '-', ':', [])";
  return "";
}

}  // namespace ahhs::view
