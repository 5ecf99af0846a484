#include "modules/core/genome_json.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "base/temp_files.h"

namespace ahhs::modules {
namespace {

using nlohmann::json;

[[noreturn]] void Fail(const std::string& field, const std::string& what) {
  throw GenomeFileError(field + ": " + what);
}

void OnlyKeys(const json& obj, const std::string& where, std::initializer_list<const char*> keys) {
  std::set<std::string> allowed(keys.begin(), keys.end());
  for (auto it = obj.begin(); it != obj.end(); ++it)
    if (!allowed.count(it.key()))
      Fail(where.empty() ? it.key() : where + "." + it.key(), "unknown field");
}

const json& Field(const json& obj, const std::string& where, const char* key) {
  const std::string name = where.empty() ? key : where + "." + key;
  if (!obj.is_object()) Fail(where.empty() ? "(document)" : where, "must be a JSON object");
  auto it = obj.find(key);
  if (it == obj.end()) Fail(name, "missing");
  return *it;
}

double Real(const json& obj, const std::string& where, const char* key) {
  const json& v = Field(obj, where, key);
  const std::string name = where.empty() ? key : where + "." + key;
  if (!v.is_number()) Fail(name, "must be a number");
  const double d = v.get<double>();
  if (!std::isfinite(d)) Fail(name, "must be finite");
  return d;
}

int Integer(const json& obj, const std::string& where, const char* key, int lo, int hi) {
  const json& v = Field(obj, where, key);
  const std::string name = where.empty() ? key : where + "." + key;
  if (!v.is_number_integer()) Fail(name, "must be an integer");
  const auto i = v.get<std::int64_t>();
  if (i < lo || i > hi)
    Fail(name, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return static_cast<int>(i);
}

std::string Text(const json& obj, const std::string& where, const char* key) {
  const json& v = Field(obj, where, key);
  if (!v.is_string()) Fail(where.empty() ? key : where + "." + key, "must be a string");
  return v.get<std::string>();
}

const json& List(const json& obj, const char* key) {
  const json& v = Field(obj, "", key);
  if (!v.is_array()) Fail(key, "must be a list");
  return v;
}

}  // namespace

json GenomeToJson(const Genome& g, const json& meta) {
  json doc = json::object();
  doc["format"] = kGenomeFormat;
  doc["version"] = kGenomeFormatVersion;
  doc["variant"] = VariantName(g.variant);
  doc["sensors"] = g.num_sensors;
  doc["actuators"] = g.num_actuators;
  json hormones = json::array();
  for (const auto& h : g.hormones)
    hormones.push_back({{"alpha", h.alpha}, {"mu", h.mu}, {"diffusion", h.diffusion}});
  doc["hormones"] = hormones;
  json rules = json::array();
  for (const auto& r : g.ahhs2_rules) {
    json w = json::object();
    for (int p = 0; p < 5; ++p) w[Ahhs2PartName(p)] = r.weights[static_cast<std::size_t>(p)];
    rules.push_back({{"weights", w},
                     {"zeta", r.zeta},
                     {"eta", r.eta},
                     {"kappa", r.kappa},
                     {"lambda", r.lambda},
                     {"sensor", r.sensor},
                     {"input", r.input},
                     {"output", r.output},
                     {"actuator", r.actuator}});
  }
  for (const auto& r : g.ahhs1_rules) {
    rules.push_back({{"type", Ahhs1TypeName(r.type)},
                     {"input", r.input},
                     {"output", r.output},
                     {"tau", r.tau},
                     {"direction", r.direction == Direction::kAbove ? "above" : "below"},
                     {"lambda", r.lambda},
                     {"kappa", r.kappa}});
  }
  doc["rules"] = rules;
  if (!meta.is_null()) doc["meta"] = meta;
  return doc;
}

Genome GenomeFromJson(const json& doc) {
  if (!doc.is_object()) Fail("(document)", "must be a JSON object");
  OnlyKeys(doc, "",
           {"format", "version", "variant", "sensors", "actuators", "hormones", "rules", "meta"});
  if (Text(doc, "", "format") != kGenomeFormat)
    Fail("format", std::string("must be \"") + kGenomeFormat + "\"");
  const json& version = Field(doc, "", "version");
  if (!version.is_number_integer() || version.get<std::int64_t>() != kGenomeFormatVersion)
    Fail("version",
         "unsupported (this build reads version " + std::to_string(kGenomeFormatVersion) + ")");
  if (doc.contains("meta") && !doc["meta"].is_object()) Fail("meta", "must be an object");

  Genome g;
  const std::string variant = Text(doc, "", "variant");
  if (variant == "ahhs1")
    g.variant = Variant::kAhhs1;
  else if (variant == "ahhs2")
    g.variant = Variant::kAhhs2;
  else
    Fail("variant", "must be \"ahhs1\" or \"ahhs2\", not \"" + variant + "\"");
  g.num_sensors = Integer(doc, "", "sensors", 1, Ranges::kMaxSlots);
  g.num_actuators = Integer(doc, "", "actuators", 1, Ranges::kMaxSlots);

  const json& hormones = List(doc, "hormones");
  if (hormones.empty() || hormones.size() > static_cast<std::size_t>(Ranges::kMaxHormones))
    Fail("hormones", "must hold 1 to " + std::to_string(Ranges::kMaxHormones) + " hormones");
  for (std::size_t h = 0; h < hormones.size(); ++h) {
    const std::string at = "hormones[" + std::to_string(h) + "]";
    const json& item = hormones[h];
    if (!item.is_object()) Fail(at, "must be an object");
    OnlyKeys(item, at, {"alpha", "mu", "diffusion"});
    g.hormones.push_back(
        {Real(item, at, "alpha"), Real(item, at, "mu"), Real(item, at, "diffusion")});
  }

  const json& rules = List(doc, "rules");
  if (rules.size() > static_cast<std::size_t>(Ranges::kMaxRules)) Fail("rules", "too many rules");
  for (std::size_t r = 0; r < rules.size(); ++r) {
    const std::string at = "rules[" + std::to_string(r) + "]";
    const json& item = rules[r];
    if (!item.is_object()) Fail(at, "must be an object");
    if (g.variant == Variant::kAhhs2) {
      OnlyKeys(
          item, at,
          {"weights", "zeta", "eta", "kappa", "lambda", "sensor", "input", "output", "actuator"});
      Ahhs2Rule rule;
      const json& w = Field(item, at, "weights");
      if (!w.is_object()) Fail(at + ".weights", "must be an object");
      OnlyKeys(w, at + ".weights", {"idle", "sensor", "linear", "nonlinear", "actuator"});
      for (int p = 0; p < 5; ++p)
        rule.weights[static_cast<std::size_t>(p)] = Real(w, at + ".weights", Ahhs2PartName(p));
      rule.zeta = Real(item, at, "zeta");
      rule.eta = Real(item, at, "eta");
      rule.kappa = Real(item, at, "kappa");
      rule.lambda = Real(item, at, "lambda");
      rule.sensor = Real(item, at, "sensor");
      rule.input = Real(item, at, "input");
      rule.output = Real(item, at, "output");
      rule.actuator = Real(item, at, "actuator");
      g.ahhs2_rules.push_back(rule);
    } else {
      OnlyKeys(item, at, {"type", "input", "output", "tau", "direction", "lambda", "kappa"});
      Ahhs1Rule rule;
      const std::string type = Text(item, at, "type");
      if (type == "idle")
        rule.type = Ahhs1Type::kIdle;
      else if (type == "sensor")
        rule.type = Ahhs1Type::kSensor;
      else if (type == "hormone")
        rule.type = Ahhs1Type::kHormone;
      else if (type == "actuator")
        rule.type = Ahhs1Type::kActuator;
      else
        Fail(at + ".type", "must be idle, sensor, hormone or actuator, not \"" + type + "\"");
      rule.input = Integer(item, at, "input", 0, Ranges::kMaxSlots);
      rule.output = Integer(item, at, "output", 0, Ranges::kMaxSlots);
      rule.tau = Real(item, at, "tau");
      const std::string dir = Text(item, at, "direction");
      if (dir == "above")
        rule.direction = Direction::kAbove;
      else if (dir == "below")
        rule.direction = Direction::kBelow;
      else
        Fail(at + ".direction", "must be \"above\" or \"below\"");
      rule.lambda = Real(item, at, "lambda");
      rule.kappa = Real(item, at, "kappa");
      g.ahhs1_rules.push_back(rule);
    }
  }
  const std::string error = CheckGenome(g);
  if (!error.empty()) throw GenomeFileError(error);
  return g;
}

namespace {

json ParseJsonText(const std::string& text, const std::string& source) {
  // The last key read names the field of a number too large for a double (1e400), which the
  // parser reports without a position.
  std::string last_key;
  const json::parser_callback_t track = [&](int, json::parse_event_t event, json& parsed) {
    if (event == json::parse_event_t::key && parsed.is_string()) last_key = parsed;
    return true;
  };
  try {
    return json::parse(text, track);
  } catch (const json::parse_error& e) {
    throw GenomeFileError(source + ": not valid JSON (" + std::string(e.what()) + ")");
  } catch (const json::out_of_range& e) {
    throw GenomeFileError(source + ": " + (last_key.empty() ? "a number" : last_key) +
                          ": out of range (" + std::string(e.what()) + ")");
  }
}

Genome GenomeFromDocument(const json& doc, const std::string& source) {
  try {
    return GenomeFromJson(doc);
  } catch (const GenomeFileError& e) {
    throw GenomeFileError(source + ": " + e.what());
  }
}

}  // namespace

Genome ParseGenome(const std::string& text, const std::string& source) {
  return GenomeFromDocument(ParseJsonText(text, source), source);
}

Genome LoadGenomeFile(const std::string& path) { return LoadGenomeFile(path, nullptr); }

Genome LoadGenomeFile(const std::string& path, json* meta) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw GenomeFileError(path + ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw GenomeFileError(path + ": read error");
  const json doc = ParseJsonText(text.str(), path);
  Genome g = GenomeFromDocument(doc, path);
  if (meta != nullptr) *meta = doc.contains("meta") ? doc["meta"] : json(nullptr);
  return g;
}

std::optional<std::uint64_t> StoredEvalSeed(const json& meta) {
  if (!meta.is_object() || !meta.contains("eval_seed")) return std::nullopt;
  const json& seed = meta["eval_seed"];
  if (seed.is_number_unsigned()) return seed.get<std::uint64_t>();
  if (seed.is_number_integer() && seed.get<std::int64_t>() >= 0)
    return static_cast<std::uint64_t>(seed.get<std::int64_t>());
  return std::nullopt;
}

void SaveGenomeFile(const std::string& path, const Genome& genome, const json& meta) {
  const std::string error = CheckGenome(genome);
  if (!error.empty())
    throw GenomeFileError(path + ": refusing to write an invalid genome: " + error);
  std::string tmp;
  try {
    tmp = base::CreateTempBeside(path);
  } catch (const std::runtime_error& e) {
    throw GenomeFileError(e.what());
  }
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw GenomeFileError(path + ": cannot write " + tmp + ": " + std::strerror(errno));
    out << GenomeToJson(genome, meta).dump(2) << '\n';
    out.flush();
    if (!out) {
      const std::string why = std::strerror(errno);
      std::remove(tmp.c_str());
      throw GenomeFileError(path + ": write failed: " + why);
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    std::remove(tmp.c_str());
    throw GenomeFileError(path + ": cannot rename " + tmp + " into place: " + why);
  }
}

}  // namespace ahhs::modules
