// A study plan (docs/evolution.md, "Studies"): named configurations of ahhs-evolve, each a preset
// file plus overrides, and how many runs (seeds 1..n) of each. A TOML file:
//
//   name = "paper-2010"                  # the study's name
//   [defaults]                           # optional: overrides for every configuration
//   generations = 200
//   [[config]]
//   name = "pendulum-ahhs1-60"           # letters, digits, '-', '_', '.'; unique
//   preset = "../configs/pendulum-ahhs1-60.toml"   # relative to the plan file
//   seeds = 20                           # runs with seeds 1..20
//   [config.set]                         # optional: overrides for this configuration
//   population = 200
//
// Every key is checked: an unknown key, a wrong type or a repeated name is an error naming the
// line. Overrides are the keys of ahhs-evolve's config files (its long options).
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace ahhs::study {

// Every problem with a plan; what() is one line for the user ("FILE:LINE: ...").
class StudyPlanError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct StudyConfig {
  std::string name;
  std::string preset;  // absolute path
  int seeds = 0;
  // Key -> TOML value text (e.g. "200", "\"fixed\"", "0.1"): defaults, then the config's own.
  std::map<std::string, std::string> overrides;
};

struct StudyPlan {
  std::string name;
  std::vector<StudyConfig> configs;
};

// One run of a study: configuration and seed, and its place in the plan.
struct StudyRun {
  std::string config;
  std::uint64_t seed = 0;
  int index = 0;  // 0-based position in plan order (configuration by configuration)
  std::string Name() const { return config + "/seed-" + std::to_string(seed); }
};

// Reads and checks a plan; presets must exist (unless !check_presets: a plan kept in a study
// directory, whose configurations are already resolved). Throws StudyPlanError.
StudyPlan LoadStudyPlan(const std::string& path);
StudyPlan ParseStudyPlan(const std::string& text, const std::string& path,
                         bool check_presets = true);

// Every run of the plan in the order a study runs them: seed 1 of every configuration, then seed
// 2 of every configuration, ..., so that a partial study covers every configuration.
std::vector<StudyRun> StudyRuns(const StudyPlan& plan);

// The preset's keys with the overrides applied, as a flat TOML file for ahhs-evolve --config.
// Throws StudyPlanError when the preset is not a flat TOML table.
std::string ResolvedConfigToml(const StudyConfig& config);

}  // namespace ahhs::study
