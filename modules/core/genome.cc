#include "modules/core/genome.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace ahhs::modules {
namespace {

// Shortest text that reads back as the same double ("0.2", not "0.20000000000000001").
std::string Num(double v) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

// Builds "field: problem" messages; the first failure wins.
class Checker {
 public:
  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }

  void Range(const std::string& field, double v, double lo, double hi) {
    if (!ok()) return;
    if (!std::isfinite(v)) {
      Fail(field, "is not a finite number");
    } else if (v < lo || v > hi) {
      Fail(field, "value " + Num(v) + " outside [" + Num(lo) + ", " + Num(hi) + "]");
    }
  }
  // Floating index: [0, n).
  void Index(const std::string& field, double v, int n) {
    if (!ok()) return;
    if (!std::isfinite(v) || v < 0 || v >= n) {
      Fail(field, "index " + Num(v) + " outside [0, " + std::to_string(n) + ")");
    }
  }
  void IntIndex(const std::string& field, int v, int n) {
    if (!ok()) return;
    if (v < 0 || v >= n)
      Fail(field, "index " + std::to_string(v) + " outside [0, " + std::to_string(n) + ")");
  }
  void Fail(const std::string& field, const std::string& what) {
    if (ok()) error_ = field + ": " + what;
  }

 private:
  std::string error_;
};

int InputRange(const Genome& g, Ahhs1Type t) {
  return t == Ahhs1Type::kSensor ? g.num_sensors : g.num_hormones();
}
int OutputRange(const Genome& g, Ahhs1Type t) {
  return t == Ahhs1Type::kActuator ? g.num_actuators : g.num_hormones();
}

}  // namespace

std::string CheckGenome(const Genome& g) {
  Checker c;
  if (g.variant != Variant::kAhhs1 && g.variant != Variant::kAhhs2) c.Fail("variant", "unknown");
  if (g.num_sensors < 1 || g.num_sensors > Ranges::kMaxSlots)
    c.Fail("sensors", "must be in [1, " + std::to_string(Ranges::kMaxSlots) + "]");
  if (g.num_actuators < 1 || g.num_actuators > Ranges::kMaxSlots)
    c.Fail("actuators", "must be in [1, " + std::to_string(Ranges::kMaxSlots) + "]");
  if (g.hormones.empty() || g.num_hormones() > Ranges::kMaxHormones)
    c.Fail("hormones", "must hold 1 to " + std::to_string(Ranges::kMaxHormones) + " hormones");
  if (g.num_rules() > Ranges::kMaxRules)
    c.Fail("rules", "more than " + std::to_string(Ranges::kMaxRules) + " rules");
  if (g.variant == Variant::kAhhs1 && !g.ahhs2_rules.empty())
    c.Fail("rules", "an ahhs1 genome holds AHHS2 rules");
  if (g.variant == Variant::kAhhs2 && !g.ahhs1_rules.empty())
    c.Fail("rules", "an ahhs2 genome holds AHHS1 rules");
  if (!c.ok()) return c.error();

  for (std::size_t h = 0; h < g.hormones.size(); ++h) {
    const std::string f = "hormones[" + std::to_string(h) + "].";
    c.Range(f + "alpha", g.hormones[h].alpha, 0, Ranges::kAlphaMax);
    c.Range(f + "mu", g.hormones[h].mu, 0, 1);
    c.Range(f + "diffusion", g.hormones[h].diffusion, 0, 1);
  }
  for (std::size_t r = 0; r < g.ahhs2_rules.size(); ++r) {
    const Ahhs2Rule& rule = g.ahhs2_rules[r];
    const std::string f = "rules[" + std::to_string(r) + "].";
    double sum = 0;
    for (int p = 0; p < 5; ++p) {
      c.Range(f + "weights." + Ahhs2PartName(p), rule.weights[static_cast<std::size_t>(p)], 0, 1);
      sum += rule.weights[static_cast<std::size_t>(p)];
    }
    if (c.ok() && std::fabs(sum - 1.0) > Ranges::kWeightSumTolerance) {
      c.Fail(f + "weights",
             "sum " + Num(sum) + " is not 1 (tolerance " + Num(Ranges::kWeightSumTolerance) + ")");
    }
    c.Range(f + "zeta", rule.zeta, Ranges::kZetaMin, Ranges::kZetaMax);
    c.Range(f + "eta", rule.eta, Ranges::kEtaMin, Ranges::kEtaMax);
    c.Range(f + "kappa", rule.kappa, -Ranges::kKappaMax, Ranges::kKappaMax);
    c.Range(f + "lambda", rule.lambda, -Ranges::kLambdaMax, Ranges::kLambdaMax);
    c.Index(f + "sensor", rule.sensor, g.num_sensors);
    c.Index(f + "input", rule.input, g.num_hormones());
    c.Index(f + "output", rule.output, g.num_hormones());
    c.Index(f + "actuator", rule.actuator, g.num_actuators);
  }
  for (std::size_t r = 0; r < g.ahhs1_rules.size(); ++r) {
    const Ahhs1Rule& rule = g.ahhs1_rules[r];
    const std::string f = "rules[" + std::to_string(r) + "].";
    const int type = static_cast<int>(rule.type);
    if (type < 0 || type > 3) c.Fail(f + "type", "unknown rule type");
    const int dir = static_cast<int>(rule.direction);
    if (dir < 0 || dir > 1) c.Fail(f + "direction", "must be above or below");
    if (!c.ok()) break;
    c.IntIndex(f + "input", rule.input, InputRange(g, rule.type));
    c.IntIndex(f + "output", rule.output, OutputRange(g, rule.type));
    c.Range(f + "tau", rule.tau, 0, 1);
    c.Range(f + "lambda", rule.lambda, -Ranges::kLambdaMax, Ranges::kLambdaMax);
    c.Range(f + "kappa", rule.kappa, -Ranges::kKappaMax, Ranges::kKappaMax);
  }
  return c.error();
}

namespace {
struct Fnv1a {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  // 64 bits, least significant byte first whatever the host (docs/hardware.md, "Genome hash").
  void Word(std::uint64_t v) {
    for (int k = 0; k < 8; ++k) h = (h ^ ((v >> (8 * k)) & 0xff)) * 0x100000001b3ULL;
  }
  void Int(std::int64_t v) { Word(static_cast<std::uint64_t>(v)); }
  void Real(double v) {
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    Word(bits);
  }
};
}  // namespace

std::uint64_t GenomeHash(const Genome& g) {
  Fnv1a f;
  f.Int(static_cast<int>(g.variant));
  f.Int(g.num_sensors);
  f.Int(g.num_actuators);
  f.Int(g.num_hormones());
  f.Int(g.num_rules());
  for (const auto& h : g.hormones) {
    f.Real(h.alpha);
    f.Real(h.mu);
    f.Real(h.diffusion);
  }
  for (const auto& r : g.ahhs2_rules) {
    for (double w : r.weights) f.Real(w);
    for (double v : {r.zeta, r.eta, r.kappa, r.lambda, r.sensor, r.input, r.output, r.actuator})
      f.Real(v);
  }
  for (const auto& r : g.ahhs1_rules) {
    f.Int(static_cast<int>(r.type));
    f.Int(r.input);
    f.Int(r.output);
    f.Real(r.tau);
    f.Int(static_cast<int>(r.direction));
    f.Real(r.lambda);
    f.Real(r.kappa);
  }
  return f.h;
}

const char* VariantName(Variant v) { return v == Variant::kAhhs1 ? "ahhs1" : "ahhs2"; }

const char* Ahhs1TypeName(Ahhs1Type t) {
  switch (t) {
    case Ahhs1Type::kIdle:
      return "idle";
    case Ahhs1Type::kSensor:
      return "sensor";
    case Ahhs1Type::kHormone:
      return "hormone";
    case Ahhs1Type::kActuator:
      return "actuator";
  }
  return "?";
}

const char* Ahhs2PartName(int part) {
  static const char* names[] = {"idle", "sensor", "linear", "nonlinear", "actuator"};
  return part >= 0 && part < 5 ? names[part] : "?";
}

std::string HashText(std::uint64_t hash) {
  char text[20];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

std::string GenomeHashText(const Genome& genome) { return HashText(GenomeHash(genome)); }

}  // namespace ahhs::modules
