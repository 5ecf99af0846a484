#include "base/cli.h"

#include <sys/stat.h>

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
std::string& ProgramName() {
  static std::string name = "ahhs";
  return name;
}
}  // namespace

const char* Version() { return AHHS_VERSION; }

void SetVersion(CLI::App& app, std::vector<std::string> speaks) {
  app.set_version_flag("--version", [speaks = std::move(speaks)] {
    std::string text = ProgramName() + " " + Version();
    for (const std::string& line : speaks) text += "\n  " + line;
    return text;
  });
}

int Parse(CLI::App& app, int argc, char** argv) {
  if (argc > 0) {
    const std::string path = argv[0];
    ProgramName() = path.substr(path.rfind('/') + 1);
  }
  if (app.get_option_no_throw("--version") == nullptr) SetVersion(app, {});
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

}  // namespace ahhs::base
