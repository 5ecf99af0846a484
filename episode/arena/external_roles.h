// Roles of an arena that someone else plays (docs/hardware.md): a sim or episode server, a
// fitness monitor or tracker, modules on their own boards or in another language. The process
// arena starts every other role and waits for the external ones to answer the handshake.
#pragma once

#include <set>
#include <string>

namespace ahhs::episode {

struct ExternalRoles {
  bool sim = false;
  bool fitness = false;
  std::set<int> modules;
  bool empty() const { return !sim && !fitness && modules.empty(); }
  bool has_module(int m) const { return modules.count(m) > 0; }
};

// Parses "sim", "fitness", "module:N", "module:N,M", "modules" (every module) and lists of them
// separated by commas, e.g. "sim,module:2,3". Throws std::invalid_argument naming the bad item.
ExternalRoles ParseExternalRoles(const std::string& text, int num_modules);

// "the sim, the fitness monitor, module 2" (for messages); "" when empty.
std::string DescribeExternalRoles(const ExternalRoles& roles);

}  // namespace ahhs::episode
