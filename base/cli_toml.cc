#include "base/cli_toml.h"

#include <toml++/toml.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <optional>
#include <sstream>

#include "base/cli.h"

namespace ahhs::base {

namespace {

class StrictTomlConfig : public CLI::Config {
 public:
  explicit StrictTomlConfig(CLI::App* app) : app_(app) {}

  std::string to_config(const CLI::App* app, bool defaults, bool descriptions,
                        std::string prefix) const override {
    return CLI::ConfigTOML().to_config(app, defaults, descriptions, std::move(prefix));
  }

  std::vector<CLI::ConfigItem> from_config(std::istream& in) const override {
    const std::string path = Path();
    std::ostringstream text;
    text << in.rdbuf();
    toml::table root;
    try {
      root = toml::parse(text.str(), path);
    } catch (const toml::parse_error& e) {
      std::string line = At(path, e.source()) + ": " + std::string(e.description());
      if (line.find("not representable in 64 bits") != std::string::npos)
        line += " (TOML integers are signed 64-bit: write a larger seed as a string, \"...\")";
      throw CLI::ConfigError(line);
    }
    std::vector<CLI::ConfigItem> found;
    for (const auto& [key, node] : root) {
      const std::string name(key.str());
      if (node.is_table() || node.is_array())
        throw CLI::ConfigError(At(path, node.source()) + ": '" + name + "' is a " +
                               (node.is_table() ? "section" : "list") +
                               "; a config file has only top-level `key = value` lines");
      const CLI::Option* option = app_->get_option_no_throw("--" + name);
      if (option != nullptr && option == app_->get_config_ptr())
        throw CLI::ConfigError(At(path, key.source()) +
                               ": a config file cannot name another config file");
      if (option == nullptr || !option->get_configurable()) {
        std::string line = At(path, key.source()) + ": unknown key '" + name + "'";
        const auto near = NearestOptions(*app_, name);
        if (!near.empty()) line += " (did you mean " + near.front().substr(2) + "?)";
        throw CLI::ConfigError(line);
      }
      CLI::ConfigItem item;
      item.name = name;
      item.inputs.push_back(ValueText(path, *option, node));
      found.push_back(std::move(item));
    }
    return found;
  }

 private:
  std::string Path() const {
    const CLI::Option* config = app_->get_config_ptr();
    if (config != nullptr && !config->results().empty()) return config->results().front();
    return "the config file";
  }

  static std::string At(const std::string& path, const toml::source_region& where) {
    return path + ":" + std::to_string(where.begin.line);
  }

  // The value as the option's own text, if its TOML type fits the option's: a flag takes
  // true/false, INT and UINT a whole number (UINT also a string of digits, for seeds above
  // 2^63-1), FLOAT any number, TEXT a string.
  static std::string ValueText(const std::string& path, const CLI::Option& option,
                               const toml::node& node) {
    // "INT", or "INT:INT in [1 - 64]" for an option with a check: the type is before the colon.
    const std::string full_type = option.get_type_name();
    const std::string type = full_type.substr(0, full_type.find(':'));
    const bool flag = option.get_items_expected_max() == 0;
    std::optional<std::string> text;
    std::string want;
    if (flag) {
      want = "true or false";
      if (const auto* b = node.as_boolean()) text = b->get() ? "true" : "false";
    } else if (type == "INT" || type == "UINT") {
      want = "a whole number";
      if (const auto* i = node.as_integer()) text = std::to_string(i->get());
      if (const auto* s = node.as_string(); s != nullptr && type == "UINT") text = s->get();
    } else if (type == "FLOAT") {
      want = "a number";
      if (const auto* i = node.as_integer()) text = std::to_string(i->get());
      if (const auto* f = node.as_floating_point()) {
        char buf[40];
        std::snprintf(buf, sizeof buf, "%.17g", f->get());  // parses back to the same double
        text = buf;
      }
    } else {
      want = "a string in quotes";
      if (const auto* s = node.as_string()) text = s->get();
    }
    if (!text)
      throw CLI::ConfigError(At(path, node.source()) + ": '" + option.get_single_name() +
                             "' must be " + want);
    return *text;
  }

  CLI::App* app_;
};

}  // namespace

void AddStrictTomlConfig(cli::App& facade, const std::string& help) {
  CLI::App& app = facade.native();
  app.allow_config_extras(CLI::config_extras_mode::error);
  app.config_formatter(std::make_shared<StrictTomlConfig>(&app));
  app.set_config("--config", "", help);
}

}  // namespace ahhs::base
