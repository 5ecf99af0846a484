#include "modules/core/genome_vector.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ahhs::modules {

namespace {

constexpr int kAhhs1Types = 4, kDirections = 2;

VectorLayout Build(const Shape& s) {
  VectorLayout layout;
  const auto add = [&](std::string name, double lo, double hi) {
    layout.names.push_back(std::move(name));
    layout.lower.push_back(lo);
    layout.upper.push_back(hi);
  };
  for (int h = 0; h < s.hormones; ++h) {
    const std::string f = "hormones[" + std::to_string(h) + "].";
    add(f + "alpha", 0, Ranges::kAlphaMax);
    add(f + "mu", 0, 1);
    add(f + "diffusion", 0, 1);
  }
  for (int r = 0; r < s.rules; ++r) {
    const std::string f = "rules[" + std::to_string(r) + "].";
    if (s.variant == Variant::kAhhs2) {
      for (int p = 0; p < 5; ++p) add(f + "weights." + Ahhs2PartName(p), 0, 1);
      add(f + "zeta", Ranges::kZetaMin, Ranges::kZetaMax);
      add(f + "eta", Ranges::kEtaMin, Ranges::kEtaMax);
      add(f + "kappa", -Ranges::kKappaMax, Ranges::kKappaMax);
      add(f + "lambda", -Ranges::kLambdaMax, Ranges::kLambdaMax);
      add(f + "sensor", 0, s.sensors);
      add(f + "input", 0, s.hormones);
      add(f + "output", 0, s.hormones);
      add(f + "actuator", 0, s.actuators);
    } else {
      add(f + "type", 0, kAhhs1Types);
      add(f + "input", 0, 1);
      add(f + "output", 0, 1);
      add(f + "tau", 0, 1);
      add(f + "direction", 0, kDirections);
      add(f + "lambda", -Ranges::kLambdaMax, Ranges::kLambdaMax);
      add(f + "kappa", -Ranges::kKappaMax, Ranges::kKappaMax);
    }
  }
  return layout;
}

int InRange(const Shape& s, Ahhs1Type t) {
  return t == Ahhs1Type::kSensor ? s.sensors : s.hormones;
}
int OutRange(const Shape& s, Ahhs1Type t) {
  return t == Ahhs1Type::kActuator ? s.actuators : s.hormones;
}

// Index i of n as a share: the middle of its interval.
double Share(int i, int n) { return (i + 0.5) / n; }
// The index a value in [0, n) (or a share times n) floors to, at most n - 1.
int Floor(double v, int n) { return std::min(n - 1, static_cast<int>(std::floor(v))); }

// Reads a vector in layout order, each value clipped into its bounds.
class Reader {
 public:
  Reader(const VectorLayout& layout, const std::vector<double>& x) : layout_(layout), x_(x) {}
  double Next() {
    const double v = x_[k_];
    if (!std::isfinite(v))
      throw std::invalid_argument("vector[" + std::to_string(k_) + "] (" + layout_.names[k_] +
                                  ") is not finite");
    const double clipped = std::clamp(v, layout_.lower[k_], layout_.upper[k_]);
    ++k_;
    return clipped;
  }
  // A floating index: below its upper bound n.
  double NextIndex() {
    const double n = layout_.upper[k_];
    return std::min(Next(), std::nextafter(n, 0.0));
  }

 private:
  const VectorLayout& layout_;
  const std::vector<double>& x_;
  std::size_t k_ = 0;
};

}  // namespace

VectorLayout GenomeVectorLayout(const Shape& shape) { return Build(shape); }

std::vector<double> GenomeToVector(const Genome& g) {
  const Shape s = g.shape();
  std::vector<double> x;
  for (const auto& h : g.hormones) x.insert(x.end(), {h.alpha, h.mu, h.diffusion});
  for (const auto& r : g.ahhs2_rules) {
    x.insert(x.end(), r.weights.begin(), r.weights.end());
    x.insert(x.end(), {r.zeta, r.eta, r.kappa, r.lambda, r.sensor, r.input, r.output, r.actuator});
  }
  for (const auto& r : g.ahhs1_rules)
    x.insert(x.end(), {static_cast<int>(r.type) + 0.5, Share(r.input, InRange(s, r.type)),
                       Share(r.output, OutRange(s, r.type)), r.tau,
                       static_cast<int>(r.direction) + 0.5, r.lambda, r.kappa});
  return x;
}

Genome GenomeFromVector(const Shape& shape, const std::vector<double>& x) {
  const VectorLayout layout = Build(shape);
  if (x.size() != layout.size())
    throw std::invalid_argument("a vector of " + std::to_string(x.size()) +
                                " values for a genome of " + std::to_string(layout.size()));
  Reader in(layout, x);
  Genome g;
  g.variant = shape.variant;
  g.num_sensors = shape.sensors;
  g.num_actuators = shape.actuators;
  g.hormones.resize(static_cast<std::size_t>(shape.hormones));
  for (auto& h : g.hormones) {
    h.alpha = in.Next();
    h.mu = in.Next();
    h.diffusion = in.Next();
  }
  for (int r = 0; r < shape.rules; ++r) {
    if (shape.variant == Variant::kAhhs2) {
      Ahhs2Rule rule;
      double sum = 0;
      for (auto& w : rule.weights) sum += (w = in.Next());
      if (sum == 0)
        rule.weights = {1, 0, 0, 0, 0};
      else if (std::fabs(sum - 1.0) > Ranges::kWeightSumTolerance)
        for (auto& w : rule.weights) w /= sum;
      rule.zeta = in.Next();
      rule.eta = in.Next();
      rule.kappa = in.Next();
      rule.lambda = in.Next();
      rule.sensor = in.NextIndex();
      rule.input = in.NextIndex();
      rule.output = in.NextIndex();
      rule.actuator = in.NextIndex();
      g.ahhs2_rules.push_back(rule);
    } else {
      Ahhs1Rule rule;
      rule.type = static_cast<Ahhs1Type>(Floor(in.Next(), kAhhs1Types));
      const int n_in = InRange(shape, rule.type), n_out = OutRange(shape, rule.type);
      rule.input = Floor(in.Next() * n_in, n_in);
      rule.output = Floor(in.Next() * n_out, n_out);
      rule.tau = in.Next();
      rule.direction = static_cast<Direction>(Floor(in.Next(), kDirections));
      rule.lambda = in.Next();
      rule.kappa = in.Next();
      g.ahhs1_rules.push_back(rule);
    }
  }
  return g;
}

nlohmann::json VectorToJson(const Shape& shape, const std::vector<double>& x) {
  const VectorLayout layout = Build(shape);
  return {{"format", "ahhs-genome-vector"},
          {"version", kGenomeVectorVersion},
          {"shape",
           {{"variant", VariantName(shape.variant)},
            {"hormones", shape.hormones},
            {"rules", shape.rules},
            {"sensors", shape.sensors},
            {"actuators", shape.actuators}}},
          {"x", x},
          {"names", layout.names},
          {"lower", layout.lower},
          {"upper", layout.upper}};
}

std::vector<double> VectorFromJson(const nlohmann::json& doc, Shape* shape) {
  try {
    if (doc.at("format") != "ahhs-genome-vector")
      throw std::invalid_argument("not a genome vector (format must be ahhs-genome-vector)");
    if (doc.at("version") != kGenomeVectorVersion)
      throw std::invalid_argument("genome vector version " + doc.at("version").dump() +
                                  " (this build reads version " +
                                  std::to_string(kGenomeVectorVersion) + ")");
    const auto& s = doc.at("shape");
    const std::string variant = s.at("variant").get<std::string>();
    if (variant != "ahhs1" && variant != "ahhs2")
      throw std::invalid_argument("shape.variant must be ahhs1 or ahhs2");
    shape->variant = variant == "ahhs1" ? Variant::kAhhs1 : Variant::kAhhs2;
    shape->hormones = s.at("hormones").get<int>();
    shape->rules = s.at("rules").get<int>();
    shape->sensors = s.at("sensors").get<int>();
    shape->actuators = s.at("actuators").get<int>();
    if (shape->hormones < 1 || shape->hormones > Ranges::kMaxHormones || shape->rules < 0 ||
        shape->rules > Ranges::kMaxRules || shape->sensors < 1 ||
        shape->sensors > Ranges::kMaxSlots || shape->actuators < 1 ||
        shape->actuators > Ranges::kMaxSlots)
      throw std::invalid_argument("shape: a size is out of range");
    return doc.at("x").get<std::vector<double>>();
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("genome vector: ") + e.what());
  }
}

}  // namespace ahhs::modules
