#include "base/cli.h"

#include <sys/stat.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <iostream>
#include <sstream>

namespace ahhs::base {

namespace {

std::size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

std::string Strip(const std::string& name) {
  std::size_t start = name.find_first_not_of('-');
  std::string s = start == std::string::npos ? "" : name.substr(start);
  const auto eq = s.find('=');
  if (eq != std::string::npos) s = s.substr(0, eq);
  std::replace(s.begin(), s.end(), '_', '-');
  return s;
}

// The unknown names a CLI11 error is about (plain string search: std::regex trips GCC 12's
// -Wmaybe-uninitialized in sanitizer builds).
std::vector<std::string> UnknownNames(const std::string& what) {
  std::vector<std::string> names;
  for (const std::string marker : {"not expected: ", "not expected:"}) {
    const auto at = what.find(marker);
    if (at == std::string::npos) continue;
    std::istringstream words(what.substr(at + marker.size()));
    for (std::string w; words >> w;)
      if (w.rfind("-", 0) == 0) names.push_back(w);
    return names;
  }
  const std::string parse = "not able to parse ";
  const auto at = what.find(parse);
  if (at != std::string::npos) {
    std::istringstream words(what.substr(at + parse.size()));
    std::string w;
    if (words >> w) names.push_back(w);
  }
  return names;
}

void Score(const CLI::App& app, const std::string& want,
           std::vector<std::pair<std::size_t, std::string>>* scored) {
  for (const CLI::Option* option : app.get_options()) {
    for (const std::string& name : option->get_lnames()) {
      const std::size_t d = EditDistance(want, name);
      if (d <= std::max<std::size_t>(2, want.size() / 3)) scored->emplace_back(d, "--" + name);
    }
  }
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    Score(*sub, want, scored);
}

}  // namespace

std::vector<std::string> NearestOptions(const CLI::App& app, const std::string& unknown) {
  const std::string want = Strip(unknown);
  std::vector<std::pair<std::size_t, std::string>> scored;
  Score(app, want, &scored);
  std::sort(scored.begin(), scored.end());
  std::vector<std::string> best;
  for (const auto& s : scored)
    if (s.first == scored.front().first) best.push_back(s.second);
  return best;
}

namespace {
std::string& MutableProgramName() {
  static std::string name = "ahhs";
  return name;
}
}  // namespace

const std::string& ProgramName() { return MutableProgramName(); }

const char* Version() { return AHHS_VERSION; }

void SetVersion(cli::App& app, std::vector<std::string> speaks) {
  app.native().set_version_flag("--version", [speaks = std::move(speaks)] {
    std::string text = ProgramName() + " " + Version();
    for (const std::string& line : speaks) text += "\n  " + line;
    return text;
  });
}

int Parse(cli::App& facade, int argc, char** argv) {
  CLI::App& app = facade.native();
  if (argc > 0) {
    const std::string path = argv[0];
    MutableProgramName() = path.substr(path.rfind('/') + 1);
  }
  if (app.get_option_no_throw("--version") == nullptr) SetVersion(facade, {});
  try {
    app.parse(argc, argv);
    return -1;
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::Error& error) {
    // CLI11 checks required options before unknown ones: an unknown name explains more.
    const std::vector<std::string> extras = app.remaining(true);
    const bool required = dynamic_cast<const CLI::RequiredError*>(&error) != nullptr;
    const CLI::Error& e = required && !extras.empty()
                              ? static_cast<const CLI::Error&>(CLI::ExtrasError(extras))
                              : error;
    std::string program = argc > 0 ? argv[0] : "ahhs";
    program = program.substr(program.rfind('/') + 1);
    std::string line = program + ": " + e.what();
    const bool from_config = dynamic_cast<const CLI::ConfigError*>(&e) != nullptr;
    for (const std::string& name : UnknownNames(e.what())) {
      if (from_config) line = program + ": unknown key '" + name + "' in the config file";
      const auto near = NearestOptions(app, name);
      if (!near.empty())
        line += " (did you mean " + (from_config ? Strip(near.front()) : near.front()) + "?)";
    }
    std::cerr << line << "; run with --help for the options\n";
    return kExitUsage;
  }
}

std::string RefuseExisting(const std::vector<std::string>& paths, bool overwrite) {
  if (overwrite) return "";
  for (const std::string& path : paths) {
    struct stat st;
    if (!path.empty() && ::stat(path.c_str(), &st) == 0)
      return path + " exists; pass --overwrite to replace it";
  }
  return "";
}

namespace cli {

struct Validator::Spec {
  std::function<CLI::Validator()> make;
};

namespace {
Validator Make(std::function<CLI::Validator()> make) {
  return Validator(std::make_shared<const Validator::Spec>(Validator::Spec{std::move(make)}));
}
}  // namespace

Validator::Validator(Check check, const std::string& name)
    : Validator(std::make_shared<const Spec>(
          Spec{[check = std::move(check), name] { return CLI::Validator(check, name); }})) {}

Validator RangeReal(double low, double high) {
  return Make([=] { return CLI::Validator(CLI::Range(low, high)); });
}
Validator RangeInteger(long long low, long long high) {
  return Make([=] { return CLI::Validator(CLI::Range(low, high)); });
}
Validator IsMember(std::vector<std::string> members) {
  return Make([members = std::move(members)] { return CLI::Validator(CLI::IsMember(members)); });
}
const Validator ExistingFile = Make([] { return CLI::Validator(CLI::ExistingFile); });
const Validator PositiveNumber = Make([] { return CLI::Validator(CLI::PositiveNumber); });
const Validator NonNegativeNumber = Make([] { return CLI::Validator(CLI::NonNegativeNumber); });

Option* Option::required(bool value) {
  native_->required(value);
  return this;
}
Option* Option::check(const Validator& validator) {
  native_->check(validator.spec().make());
  return this;
}
Option* Option::capture_default_str() {
  native_->capture_default_str();
  return this;
}
Option* Option::default_str(const std::string& text) {
  native_->default_str(text);
  return this;
}
Option* Option::excludes(Option* other) {
  native_->excludes(other->native_);
  return this;
}
Option* Option::delimiter(char separator) {
  native_->delimiter(separator);
  return this;
}
Option* Option::each(std::function<void(const std::string&)> on_value) {
  native_->each(std::move(on_value));
  return this;
}
std::size_t Option::count() const { return native_->count(); }

App::App(const std::string& description, const std::string& name)
    : owned_(std::make_unique<CLI::App>(description, name)), native_(owned_.get()) {}
App::App(CLI::App* subcommand) : native_(subcommand) {}
App::~App() = default;

Option* App::Keep(CLI::Option* option) {
  options_.emplace_back(option);
  return &options_.back();
}

#define AHHS_CLI_ADD_OPTION(T)                                                          \
  Option* App::add_option(const std::string& name, T& value, const std::string& help) { \
    return Keep(native_->add_option(name, value, help));                                \
  }
AHHS_CLI_ADD_OPTION(std::string)
AHHS_CLI_ADD_OPTION(int)
AHHS_CLI_ADD_OPTION(unsigned)
AHHS_CLI_ADD_OPTION(long)
AHHS_CLI_ADD_OPTION(unsigned long)
AHHS_CLI_ADD_OPTION(long long)
AHHS_CLI_ADD_OPTION(unsigned long long)
AHHS_CLI_ADD_OPTION(double)
AHHS_CLI_ADD_OPTION(std::vector<std::string>)
AHHS_CLI_ADD_OPTION(std::vector<int>)
AHHS_CLI_ADD_OPTION(std::vector<double>)
#undef AHHS_CLI_ADD_OPTION

Option* App::add_flag(const std::string& name, bool& value, const std::string& help) {
  return Keep(native_->add_flag(name, value, help));
}

App* App::add_subcommand(const std::string& name, const std::string& description) {
  subcommands_.push_back(std::unique_ptr<App>(new App(native_->add_subcommand(name, description))));
  return subcommands_.back().get();
}
App* App::require_subcommand(int count) {
  native_->require_subcommand(count);
  return this;
}
bool App::parsed() const { return native_->parsed(); }
std::size_t App::count(const std::string& name) const { return native_->count(name); }

}  // namespace cli

}  // namespace ahhs::base
