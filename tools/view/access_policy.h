// Which requests the viewer answers: the Host header against an allow-list (DNS rebinding: a
// foreign name that resolves to this machine) and the Origin of a WebSocket (a page of another
// site reading what the viewer shows). docs/viewer.md, "Security".
#pragma once

#include <string>
#include <vector>

namespace ahhs::view {

class AccessPolicy {
 public:
  // Allows 127.0.0.1, localhost and [::1] on `port`, `bind` unless it is a wildcard address,
  // and every name of `extra` (NAME for NAME:port, or NAME:PORT as it is). On port 80 a name
  // without a port is allowed too, as browsers leave it out there.
  AccessPolicy(const std::string& bind, int port, const std::vector<std::string>& extra = {});

  // A Host header (null: none sent, refused).
  bool HostAllowed(const char* host) const;
  // An Origin header: absent (null: not a browser page) is allowed; otherwise it must be
  // http://ALLOWED-HOST. "null" (a sandboxed or file page) is refused.
  bool OriginAllowed(const char* origin) const;
  // The allowed hosts, for messages: "127.0.0.1:8080, localhost:8080, [::1]:8080".
  std::string Describe() const;

  // Checks a --allow-host value; returns "" or what is wrong with it.
  static std::string CheckName(const std::string& name);

 private:
  std::vector<std::string> hosts_;  // lower case, "name:port"
};

}  // namespace ahhs::view
