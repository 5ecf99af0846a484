// What every AHHS program shares on its command line (docs/development.md, "Exit codes"):
//   0  done;  1  the work failed (a run, an episode, a file);  2  a usage error (bad option,
//   bad value, unknown key in a config file);  130  interrupted (Ctrl-C), where resumable.
// A usage error is one line, "PROGRAM: what", with the nearest known option when a name is
// mistyped, and the hint to run --help. Namespace ahhs::base like the rest of base/; its own
// library (ahhs_cli) because only programs need CLI11.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace ahhs::base {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;
inline constexpr int kExitInterrupted = 130;

// Parses the command line. Returns -1 when the program should go on; otherwise the exit code
// (0 after --help or --version, kExitUsage after an error, which has been printed). Every
// program gets a --version (SetVersion's, or one that prints the version alone).
int Parse(CLI::App& app, int argc, char** argv);

// This build's version, the project's (CMakeLists.txt), e.g. "0.1.0".
const char* Version();

// Gives `app` a --version that prints "PROGRAM VERSION" and then one line for each thing the
// program speaks, as its layer words it ("farm protocol 3", "physics: pendulum 2026-12-01,
// ...": docs/reference.md).
void SetVersion(CLI::App& app, std::vector<std::string> speaks);

// The option names of `app` closest to `unknown` (edit distance at most 2 or a third of its
// length), best first: "--population" for "--populaton" or "populaton".
std::vector<std::string> NearestOptions(const CLI::App& app, const std::string& unknown);

// Output files a program is about to write: "" when none exists (or `overwrite`), else the
// usage error naming the first one that does. Every program refuses to replace a file or a
// directory unless told to (--overwrite; ahhs-logger --force, as lcm-logger).
std::string RefuseExisting(const std::vector<std::string>& paths, bool overwrite);

}  // namespace ahhs::base
