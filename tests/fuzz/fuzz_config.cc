// The strict TOML config reader (base/cli_toml.h) with options of every kind ahhs-evolve has:
// any text gives `key = value` items that all name configurable options, or a CLI::ConfigError
// (a usage error naming the line); nothing else escapes. Accepted items then parse.
#include <CLI/CLI.hpp>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "base/cli_toml.h"
#include "tests/fuzz/fuzz_contract.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ahhs::base::cli::App facade{"fuzz"};
  CLI::App& app = facade.native();
  std::string scenario = "gait";
  int rules = 30;
  double rate = 0.15;
  std::uint64_t seed = 1;
  bool overwrite = false;
  ahhs::base::AddStrictTomlConfig(facade, "config");
  app.add_option("--scenario", scenario)->check(CLI::IsMember({"gait", "pendulum"}));
  app.add_option("--rules", rules);
  app.add_option("--mutation-rate", rate);
  app.add_option("--seed", seed);
  app.add_flag("--overwrite", overwrite);
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  std::vector<CLI::ConfigItem> items;
  try {
    items = app.get_config_formatter()->from_config(in);
  } catch (const CLI::ConfigError&) {
    return 0;
  }
  for (const auto& item : items) {
    const CLI::Option* option = app.get_option_no_throw("--" + item.name);
    FUZZ_CONTRACT(option != nullptr && option->get_configurable(), "an unknown key was accepted");
    FUZZ_CONTRACT(item.inputs.size() == 1, "a key with other than one value");
  }
  return 0;
}
