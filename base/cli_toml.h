// Strict config files for CLI11 programs: a real TOML parser (toml++) instead of CLI11's
// lenient reader. A config file is flat: `key = value` lines whose keys are the program's long
// option names. Invalid TOML, a repeated key, a [section] or an array, and a key that is no
// option are each a usage error naming the file and line ("FILE:3: unknown key 'populaton'
// (did you mean population?)"). Options on the command line still override the file.
#pragma once

#include <string>

#include "base/cli.h"

namespace ahhs::base {

// Adds `--config FILE` to `app`, read strictly as above.
void AddStrictTomlConfig(cli::App& app, const std::string& help);

}  // namespace ahhs::base
