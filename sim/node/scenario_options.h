// The scenario as command-line options, declared once for every tool that names one: --scenario,
// --docking, --modules, --duration and the pendulum's open choices (sim/core/scenario.h). A bad
// name is a usage error with the same message as the scenario's own parser ("unknown scenario
// 'walker' (use gait or pendulum)"). --joints, the old name of --docking, works for one release
// and says it is deprecated (also as a config file's key).
#pragma once

#include <iostream>
#include <stdexcept>
#include <string>

#include "base/cli.h"
#include "sim/core/scenario.h"

namespace ahhs::sim {

struct ScenarioOptions {
  std::string scenario = "gait";
  std::string docking = "damped";
  int modules = 5;
  double duration = 0;  // s; 0: the scenario's
  double pendulum_gain = 1;
  std::string pendulum_walls = "rigid";

  // `context` begins every help text ("with --genome: "); `duration_help` says what the
  // duration means for this tool.
  void Add(base::cli::App& app, const std::string& context, const std::string& duration_help) {
    app.add_option("--scenario", scenario, context + "gait or pendulum")
        ->check(NameCheck("SCENARIO", [](const std::string& s) { ParseScenarioKind(s); }))
        ->capture_default_str();
    auto* docking_opt =
        app.add_option("--docking", docking, context + "gait docking: damped or fixed")
            ->check(NameCheck("DOCKING", [](const std::string& s) { ParseDocking(s); }))
            ->capture_default_str();
    app.add_option("--joints", docking, "deprecated: use --docking")
        ->check(NameCheck("DOCKING", [](const std::string& s) { ParseDocking(s); }))
        ->excludes(docking_opt)
        ->each([](const std::string&) {
          std::cerr << base::ProgramName()
                    << ": --joints is deprecated and will go; use --docking\n";
        });
    app.add_option("--modules", modules, context + "gait: modules in the chain (>= 2)")
        ->capture_default_str();
    duration_opt_ = app.add_option("--duration", duration, context + duration_help);
    app.add_option("--pendulum.actuator-gain", pendulum_gain,
                   context +
                       "pendulum: v = top speed x clamp(gain (A1 - A0) / 2, -1, 1), 1 to "
                       "100 (docs/scenarios.md, \"Choices the paper leaves open\")")
        ->capture_default_str();
    app.add_option("--pendulum.walls", pendulum_walls,
                   context + "pendulum: rigid (the cart stops dead) or soft (a spring-damper stop)")
        ->check(NameCheck("WALLS", [](const std::string& s) { ParsePendulumWalls(s); }))
        ->capture_default_str();
  }
  // --physics VERSION, for the tools that evaluate for a run (ahhs-evolve, ahhs-evaluate): keep
  // an earlier physics this build still simulates (ahhs-sim's --physics is another option).
  void AddPhysics(base::cli::App& app) {
    app.add_option("--physics", physics,
                   "the physics version to evaluate in: this build's (default) or an earlier one "
                   "it still simulates (`--version` lists them; docs/reference.md), so that a "
                   "study keeps one physics across builds");
  }
  bool duration_given() const { return duration_opt_ && duration_opt_->count() > 0; }
  // The configuration the options name (the scenario's own checks still apply: CheckConfig,
  // which also refuses a physics this build does not simulate).
  ScenarioConfig Config() const {
    ScenarioConfig c =
        MakeScenarioConfig(ParseScenarioKind(scenario), ParseDocking(docking), modules, duration);
    c.pendulum.actuator_gain = pendulum_gain;
    c.pendulum.walls = ParsePendulumWalls(pendulum_walls);
    KeepPhysics(physics, &c);
    return c;
  }
  std::string physics;  // "" or this build's: its own

 private:
  template <typename Parse>
  static base::cli::Validator NameCheck(const std::string& what, Parse parse) {
    return base::cli::Validator(
        [parse](std::string& value) -> std::string {
          try {
            parse(value);
            return "";
          } catch (const std::invalid_argument& e) {
            return e.what();
          }
        },
        what);
  }
  base::cli::Option* duration_opt_ = nullptr;
};

}  // namespace ahhs::sim
