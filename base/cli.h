// What every AHHS program shares on its command line (docs/development.md, "Exit codes"):
//   0  done;  1  the work failed (a run, an episode, a file);  2  a usage error (bad option,
//   bad value, unknown key in a config file);  130  interrupted (Ctrl-C), where resumable.
// A usage error is one line, "PROGRAM: what", with the nearest known option when a name is
// mistyped, and the hint to run --help. Namespace ahhs::base like the rest of base/; its own
// library (ahhs_cli) because only programs need it.
//
// base::cli is the part of CLI11's interface our programs use, under CLI11's own names (so
// its documentation describes them), compiled once in cli.cc. CLI11 2.1 is header-only: a
// file that includes it compiles 5 s (Release) to 9 s (sanitizers) of CLI11 before its own
// code, for the validator objects every file constructs; about 35 files declared options.
// Only cli.cc and cli_toml.cc include it now.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace ahhs::base {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;
inline constexpr int kExitInterrupted = 130;

// A usage error found after parsing (options that do not go together): exit kExitUsage.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

namespace cli {

// A check of an option's value: returns "" when the value is good, else what is wrong; it may
// rewrite the value. `Range`, `IsMember` and the three constants below are CLI11's own checks
// (they print as CLI11 prints them in --help).
class Validator {
 public:
  using Check = std::function<std::string(std::string&)>;
  struct Spec;  // cli.cc: how to make the CLI11 validator
  explicit Validator(std::shared_ptr<const Spec> spec) : spec_(std::move(spec)) {}
  Validator(Check check, const std::string& name);
  // Any callable taking the value (a std::string) and returning its error text, "" if none.
  template <typename F,
            typename = std::enable_if_t<std::is_invocable_r_v<std::string, F&, std::string&>>>
  Validator(F check)  // NOLINT(google-explicit-constructor): CLI11 converts the same way
      : Validator(Check(std::move(check)), "") {}
  const Spec& spec() const { return *spec_; }

 private:
  std::shared_ptr<const Spec> spec_;
};

Validator RangeReal(double low, double high);           // a real value in [low, high]
Validator RangeInteger(long long low, long long high);  // an integer in [low, high]
// CLI::Range: an integer range when both bounds are integers, else a real one.
template <typename Low, typename High>
Validator Range(Low low, High high) {
  if constexpr (std::is_integral_v<Low> && std::is_integral_v<High>)
    return RangeInteger(static_cast<long long>(low), static_cast<long long>(high));
  else
    return RangeReal(static_cast<double>(low), static_cast<double>(high));
}
Validator IsMember(std::vector<std::string> members);  // one of `members`
extern const Validator ExistingFile;                   // a file that exists
extern const Validator PositiveNumber;                 // a number > 0
extern const Validator NonNegativeNumber;              // a number >= 0

// One declared option. Owned by its App; the pointers App hands out stay valid as long as it.
class Option {
 public:
  explicit Option(CLI::Option* native) : native_(native) {}
  Option* required(bool value = true);
  Option* check(const Validator& validator);
  Option* capture_default_str();                 // --help shows the variable's value as the default
  Option* default_str(const std::string& text);  // --help shows `text` as the default
  Option* excludes(Option* other);
  Option* delimiter(char separator);  // a vector option also splits each value at `separator`
  Option* each(std::function<void(const std::string&)> on_value);  // runs for every value
  // How often the option was given.
  std::size_t count() const;
  CLI::Option* native() const { return native_; }

 private:
  CLI::Option* native_;
};

// A program's (or a subcommand's) options. Adding binds a variable: parsing writes it.
class App {
 public:
  explicit App(const std::string& description = "", const std::string& name = "");
  ~App();
  App(const App&) = delete;
  App& operator=(const App&) = delete;

  Option* add_option(const std::string& name, std::string& value, const std::string& help = "");
  Option* add_option(const std::string& name, int& value, const std::string& help = "");
  Option* add_option(const std::string& name, unsigned& value, const std::string& help = "");
  Option* add_option(const std::string& name, long& value, const std::string& help = "");
  Option* add_option(const std::string& name, unsigned long& value, const std::string& help = "");
  Option* add_option(const std::string& name, long long& value, const std::string& help = "");
  Option* add_option(const std::string& name, unsigned long long& value,
                     const std::string& help = "");
  Option* add_option(const std::string& name, double& value, const std::string& help = "");
  Option* add_option(const std::string& name, std::vector<std::string>& value,
                     const std::string& help = "");
  Option* add_option(const std::string& name, std::vector<int>& value,
                     const std::string& help = "");
  Option* add_option(const std::string& name, std::vector<double>& value,
                     const std::string& help = "");
  Option* add_flag(const std::string& name, bool& value, const std::string& help = "");

  App* add_subcommand(const std::string& name, const std::string& description);
  App* require_subcommand(int count);
  // Whether this (sub)command was on the command line.
  bool parsed() const;
  explicit operator bool() const { return parsed(); }
  // How often the option `name` was given ("--seed").
  std::size_t count(const std::string& name) const;

  CLI::App& native() { return *native_; }
  const CLI::App& native() const { return *native_; }

 private:
  explicit App(CLI::App* subcommand);
  Option* Keep(CLI::Option* option);
  std::unique_ptr<CLI::App> owned_;
  CLI::App* native_;
  std::deque<Option> options_;
  std::deque<std::unique_ptr<App>> subcommands_;
};

}  // namespace cli

// Parses the command line. Returns -1 when the program should go on; otherwise the exit code
// (0 after --help or --version, kExitUsage after an error, which has been printed). Every
// program gets a --version (SetVersion's, or one that prints the version alone).
int Parse(cli::App& app, int argc, char** argv);

// The program's name as Parse found it (argv[0] without its directory; "ahhs" before Parse), for
// messages printed while parsing, e.g. that an option is deprecated.
const std::string& ProgramName();

// This build's version, the project's (CMakeLists.txt), e.g. "0.1.0".
const char* Version();

// Gives `app` a --version that prints "PROGRAM VERSION" and then one line for each thing the
// program speaks, as its layer words it ("farm protocol 4", "physics: pendulum 2026-12-01,
// ...": docs/reference.md).
void SetVersion(cli::App& app, std::vector<std::string> speaks);

// The option names of `app` closest to `unknown` (edit distance at most 2 or a third of its
// length), best first: "--population" for "--populaton" or "populaton".
std::vector<std::string> NearestOptions(const CLI::App& app, const std::string& unknown);

// Output files a program is about to write: "" when none exists (or `overwrite`), else the
// usage error naming the first one that does. Every program refuses to replace a file or a
// directory unless told to (--overwrite; ahhs-logger --force, as lcm-logger).
std::string RefuseExisting(const std::vector<std::string>& paths, bool overwrite);

}  // namespace ahhs::base
