#include "tools/study/study_plan.h"

#include <toml++/toml.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace ahhs::study {

namespace fs = std::filesystem;

namespace {

// The keys an ahhs-evolve config file may set (its long options that describe a run).
const std::set<std::string>& EvolveKeys() {
  static const std::set<std::string> keys{"scenario",
                                          "docking",
                                          "joints",  // deprecated: docking
                                          "modules",
                                          "duration",
                                          "variant",
                                          "hormones",
                                          "rules",
                                          "population",
                                          "generations",
                                          "elitism",
                                          "mutation-rate",
                                          "mutation-max-change",
                                          "mutation-profile",
                                          "crossover-rate",
                                          "trials",
                                          "aggregate",
                                          "envelope",
                                          "post-eval",
                                          "post-eval-envelope",
                                          "validation",
                                          "validation-candidates",
                                          "envelope.friction",
                                          "envelope.mass",
                                          "envelope.servo-torque",
                                          "envelope.servo-speed",
                                          "envelope.start-heading",
                                          "envelope.start-offset",
                                          "envelope.sensor-noise",
                                          "envelope.start-angle",
                                          "envelope.cart-speed",
                                          "envelope.command-delay",
                                          "envelope.start-hinge",
                                          "pendulum.actuator-gain",
                                          "pendulum.walls",
                                          "physics"};
  return keys;
}

std::string Where(const std::string& path, const toml::source_region& at) {
  return path + ":" + std::to_string(at.begin.line) + ": ";
}

[[noreturn]] void Fail(const std::string& path, const toml::node& at, const std::string& what) {
  throw StudyPlanError(Where(path, at.source()) + what);
}

// "key = value" as TOML prints it, minus the key: the value's own text.
std::string ValueText(const std::string& key, const toml::node& value) {
  toml::table one;
  one.insert(key, value);
  std::ostringstream out;
  out << one;
  const std::string text = out.str();
  const auto eq = text.find(" = ");
  return eq == std::string::npos ? text : text.substr(eq + 3);
}

void ReadOverrides(const std::string& path, const toml::node& node,
                   std::map<std::string, std::string>* out) {
  const toml::table* table = node.as_table();
  if (!table) Fail(path, node, "expected a table of ahhs-evolve settings");
  for (auto&& [key, value] : *table) {
    const std::string k(key.str());
    if (k == "seed") Fail(path, value, "a study sets the seeds itself (seeds = N)");
    if (!EvolveKeys().count(k)) Fail(path, value, "'" + k + "' is not an ahhs-evolve setting");
    if (!value.is_value() || value.is_date() || value.is_time() || value.is_date_time())
      Fail(path, value, "'" + k + "' must be a string, a number or a boolean");
    (*out)[k] = ValueText(k, value);
  }
}

bool GoodName(const std::string& name) {
  return !name.empty() && name[0] != '.' && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
  });
}

}  // namespace

StudyPlan ParseStudyPlan(const std::string& text, const std::string& path, bool check_presets) {
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw StudyPlanError(Where(path, e.source()) + std::string(e.description()));
  }
  StudyPlan plan;
  std::map<std::string, std::string> defaults;
  const fs::path base = fs::absolute(fs::path(path)).parent_path();
  for (auto&& [key, value] : root) {
    const std::string k(key.str());
    if (k == "name") {
      if (!value.is_string() || !GoodName(value.as_string()->get()))
        Fail(path, value, "name must be a string of letters, digits, '-', '_' and '.'");
      plan.name = value.as_string()->get();
    } else if (k == "defaults") {
      ReadOverrides(path, value, &defaults);
    } else if (k == "config") {
      if (!value.is_array_of_tables()) Fail(path, value, "configurations are written [[config]]");
    } else {
      Fail(path, value, "unknown key '" + k + "' (name, defaults, config)");
    }
  }
  if (plan.name.empty()) throw StudyPlanError(path + ": the plan has no name (name = \"...\")");
  const toml::array* configs = root["config"].as_array();
  if (!configs || configs->empty())
    throw StudyPlanError(path + ": the plan has no configuration ([[config]])");
  std::set<std::string> names;
  for (const toml::node& node : *configs) {
    const toml::table& table = *node.as_table();
    StudyConfig config;
    config.overrides = defaults;
    bool has_seeds = false;
    for (auto&& [key, value] : table) {
      const std::string k(key.str());
      if (k == "name") {
        if (!value.is_string() || !GoodName(value.as_string()->get()))
          Fail(path, value, "name must be a string of letters, digits, '-', '_' and '.'");
        config.name = value.as_string()->get();
      } else if (k == "preset") {
        if (!value.is_string()) Fail(path, value, "preset must be a file name");
        const fs::path preset = base / value.as_string()->get();
        std::error_code ec;
        if (check_presets && !fs::is_regular_file(preset, ec))
          Fail(path, value, "preset " + preset.lexically_normal().string() + " does not exist");
        config.preset = fs::weakly_canonical(preset).string();
      } else if (k == "seeds") {
        const auto n = value.value<std::int64_t>();
        if (!value.is_integer() || !n || *n < 1 || *n > 10000)
          Fail(path, value, "seeds must be a whole number from 1 to 10000");
        config.seeds = static_cast<int>(*n);
        has_seeds = true;
      } else if (k == "set") {
        ReadOverrides(path, value, &config.overrides);
      } else {
        Fail(path, value, "unknown key '" + k + "' in [[config]] (name, preset, seeds, set)");
      }
    }
    if (config.name.empty()) Fail(path, node, "a configuration has no name");
    if (config.preset.empty()) Fail(path, node, "configuration " + config.name + " has no preset");
    if (!has_seeds) Fail(path, node, "configuration " + config.name + " has no seeds = N");
    if (!names.insert(config.name).second)
      Fail(path, node, "configuration " + config.name + " is named twice");
    plan.configs.push_back(std::move(config));
  }
  return plan;
}

StudyPlan LoadStudyPlan(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw StudyPlanError("cannot read the study plan " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return ParseStudyPlan(text.str(), path);
}

std::vector<StudyRun> StudyRuns(const StudyPlan& plan) {
  std::vector<StudyRun> runs;
  std::vector<int> first(plan.configs.size());
  int index = 0;
  for (std::size_t c = 0; c < plan.configs.size(); ++c) {
    first[c] = index;
    index += plan.configs[c].seeds;
  }
  int most = 0;
  for (const auto& c : plan.configs) most = std::max(most, c.seeds);
  for (int seed = 1; seed <= most; ++seed)
    for (std::size_t c = 0; c < plan.configs.size(); ++c)
      if (seed <= plan.configs[c].seeds)
        runs.push_back(
            {plan.configs[c].name, static_cast<std::uint64_t>(seed), first[c] + seed - 1});
  return runs;
}

std::string ResolvedConfigToml(const StudyConfig& config) {
  toml::table table;
  try {
    table = toml::parse_file(config.preset);
  } catch (const toml::parse_error& e) {
    throw StudyPlanError(Where(config.preset, e.source()) + std::string(e.description()));
  }
  for (auto&& [key, value] : table)
    if (!value.is_value())
      throw StudyPlanError(Where(config.preset, value.source()) +
                           "a preset holds only 'key = value' lines");
  for (const auto& [key, text] : config.overrides) {
    toml::table one = toml::parse("\"" + key + "\" = " + text);  // quoted: envelope.KEY
    table.insert_or_assign(key, *one.get(key));
  }
  std::ostringstream out;
  out << "# " << config.name << ": " << fs::path(config.preset).filename().string()
      << " with the plan's overrides\n"
      << table << '\n';
  return out.str();
}

}  // namespace ahhs::study
