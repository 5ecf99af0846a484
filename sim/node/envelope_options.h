// The envelope of noise as command-line options, declared once for every tool that runs
// episodes directly: --envelope none|paper|wide, then any single key (--envelope.friction 0.1,
// ...) on top of the preset (sim/core/envelope.h, docs/scenarios.md).
#pragma once

#include <cstdio>
#include <map>
#include <string>

#include "base/cli.h"
#include "base/format.h"
#include "sim/core/envelope.h"

namespace ahhs::sim {

// The options that give `envelope` back (to print a command that replays an episode): "" for
// none, " --envelope paper" for a preset, " --envelope none --envelope.KEY W ..." otherwise.
inline std::string EnvelopeArguments(const Envelope& envelope) {
  const std::string name = EnvelopeName(envelope);
  if (name == "none") return "";
  if (name != "custom") return " --envelope " + name;
  std::string args = " --envelope none";
  for (const auto& k : EnvelopeKeys()) {
    const double w = envelope.*k.field;
    if (w == 0) continue;
    args += std::string(" --") + k.name + " " + base::ExactDouble(w);
  }
  return args;
}

class EnvelopeOptions {
 public:
  void Add(base::cli::App& app, const std::string& preset_help) {
    preset_opt_ = app.add_option("--envelope", preset_, preset_help)
                      ->check(base::cli::IsMember({"none", "paper", "wide"}));
    for (const auto& k : EnvelopeKeys())
      app.add_option(std::string("--") + k.name, keys_[k.name],
                     std::string(k.help) + " (on top of --envelope)")
          ->check(base::cli::Range(0.0, 1.0));
    app_ = &app;
  }
  // Whether any envelope option was given.
  bool given() const {
    if (preset_opt_ && preset_opt_->count() > 0) return true;
    for (const auto& k : EnvelopeKeys())
      if (app_->count(std::string("--") + k.name) > 0) return true;
    return false;
  }
  // The preset (or `fallback` when none was given) with the single keys applied. Throws
  // std::invalid_argument naming the bad key.
  Envelope Resolve(const std::string& fallback = "none") const {
    Envelope e = EnvelopePreset(preset_opt_ && preset_opt_->count() > 0 ? preset_ : fallback);
    for (const auto& k : EnvelopeKeys())
      if (app_->count(std::string("--") + k.name) > 0) e.*k.field = keys_.at(k.name);
    const std::string error = CheckEnvelope(e);
    if (!error.empty()) throw std::invalid_argument("--" + error);
    return e;
  }

 private:
  base::cli::App* app_ = nullptr;
  base::cli::Option* preset_opt_ = nullptr;
  std::string preset_ = "none";
  std::map<std::string, double> keys_;
};

}  // namespace ahhs::sim
