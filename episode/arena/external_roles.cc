#include "episode/arena/external_roles.h"

#include <cctype>
#include <sstream>
#include <stdexcept>

namespace ahhs::episode {

namespace {
bool ParseIndex(const std::string& text, int* out) {
  if (text.empty() || text.size() > 6) return false;
  for (char c : text)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  *out = std::stoi(text);
  return true;
}
}  // namespace

ExternalRoles ParseExternalRoles(const std::string& text, int num_modules) {
  ExternalRoles roles;
  std::stringstream items(text);
  std::string item;
  bool after_module = false;
  auto add_module = [&](const std::string& index, const std::string& what) {
    int m = -1;
    if (!ParseIndex(index, &m) || m >= num_modules)
      throw std::invalid_argument("--external: '" + what + "': modules are 0 to " +
                                  std::to_string(num_modules - 1));
    roles.modules.insert(m);
  };
  while (std::getline(items, item, ',')) {
    if (item == "sim") {
      roles.sim = true;
      after_module = false;
    } else if (item == "fitness") {
      roles.fitness = true;
      after_module = false;
    } else if (item == "modules") {
      for (int m = 0; m < num_modules; ++m) roles.modules.insert(m);
      after_module = false;
    } else if (item.rfind("module:", 0) == 0) {
      add_module(item.substr(7), item);
      after_module = true;
    } else if (after_module && !item.empty() && std::isdigit(static_cast<unsigned char>(item[0]))) {
      add_module(item, item);
    } else {
      throw std::invalid_argument("--external: unknown role '" + item +
                                  "' (sim, fitness, module:N[,M...] or modules)");
    }
  }
  if (roles.empty()) throw std::invalid_argument("--external: no role given");
  return roles;
}

std::string DescribeExternalRoles(const ExternalRoles& roles) {
  std::string text;
  auto add = [&text](const std::string& part) { text += (text.empty() ? "" : ", ") + part; };
  if (roles.sim) add("the sim");
  if (roles.fitness) add("the fitness monitor");
  for (int m : roles.modules) add("module " + std::to_string(m));
  return text;
}

}  // namespace ahhs::episode
