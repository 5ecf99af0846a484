#include "tools/conformance/model_vectors.h"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "base/format.h"
#include "modules/core/hormone_system.h"
#include "modules/core/random.h"
#include "modules/core/variation.h"
#include "modules/node/genome_codec.h"

namespace ahhs::conformance {

namespace {

using modules::Genome;

struct Tick {
  int num_neighbours = 0;
  std::vector<std::vector<double>> received;
  std::vector<double> sensors;
  std::vector<char> sensor_present, actuator_present;  // char: std::vector<bool> has no data()
};

struct VectorOutputs {
  std::vector<double> hormones, actuators, outflow;
};

struct Case {
  std::string name;
  Genome genome;
  std::vector<Tick> ticks;
  std::vector<VectorOutputs> expected;  // read from a file; empty when generated
};

// Runs a case through modules/core: the outputs after every tick.
std::vector<VectorOutputs> Run(const Case& c) {
  const modules::Controller controller(c.genome);
  modules::CompartmentState state = modules::MakeState(controller);
  std::vector<VectorOutputs> out;
  for (const Tick& t : c.ticks) {
    for (const auto& packet : t.received) modules::ReceiveHormones(packet.data(), &state);
    static_assert(sizeof(char) == sizeof(bool));
    modules::TickInput in;
    in.sensors = t.sensors.data();
    in.sensor_present = reinterpret_cast<const bool*>(t.sensor_present.data());
    in.actuator_present = reinterpret_cast<const bool*>(t.actuator_present.data());
    in.num_neighbours = t.num_neighbours;
    modules::Step(controller, in, &state);
    const auto copy = [](const Eigen::VectorXd& v) {
      return std::vector<double>(v.data(), v.data() + v.size());
    };
    out.push_back({copy(state.hormones), copy(state.actuators), copy(state.outflow)});
  }
  return out;
}

void Line(std::ostringstream& out, const char* key, const std::vector<double>& values) {
  out << key;
  for (double v : values) out << ' ' << base::ExactDouble(v);
  out << '\n';
}

// Inputs of `ticks` ticks drawn from `rng`: up to `max_neighbours` packets of up to `max_packet`
// per hormone, sensors in [0, 1] (some exactly 0 or 1, some absent), now and then an absent
// actuator.
std::vector<Tick> RandomTicks(const Genome& g, int ticks, int max_neighbours, double max_packet,
                              modules::Rng& rng) {
  std::vector<Tick> out;
  for (int k = 0; k < ticks; ++k) {
    Tick t;
    t.num_neighbours = rng.UniformInt(max_neighbours + 1);
    for (int p = 0; p < t.num_neighbours; ++p) {
      std::vector<double> packet;
      for (int h = 0; h < g.num_hormones(); ++h) packet.push_back(rng.Uniform(0, max_packet));
      t.received.push_back(packet);
    }
    for (int s = 0; s < g.num_sensors; ++s) {
      const double u = rng.Uniform();
      t.sensors.push_back(u < 0.1 ? 0.0 : u > 0.9 ? 1.0 : rng.Uniform());
      t.sensor_present.push_back(rng.Bernoulli(0.9) ? 1 : 0);
    }
    for (int a = 0; a < g.num_actuators; ++a)
      t.actuator_present.push_back(rng.Bernoulli(0.95) ? 1 : 0);
    out.push_back(std::move(t));
  }
  return out;
}

// AHHS2 rules that reach the corners of the evaluation order: an output index on an integer
// (the second item gets weight 0), one just below n (it wraps to item 0), a rule whose input sits
// exactly on the edge of its window (tent 0), the narrowest window, all four parts at once.
Genome Ahhs2EdgeGenome() {
  Genome g;
  g.variant = modules::Variant::kAhhs2;
  g.num_sensors = 2;
  g.num_actuators = 2;
  g.hormones = {{0.1, 0.05, 0.4}, {0.02, 0.3, 0.0}, {0.0, 0.0, 1.0}};
  modules::Ahhs2Rule all;
  all.weights = {0.1, 0.2, 0.3, 0.25, 0.15};
  all.zeta = 0.3;
  all.eta = 0.5;
  all.kappa = 0.05;
  all.lambda = -1.5;
  all.sensor = 1.5;
  all.input = 0.2;
  all.output = 2.75;  // items 2 and 0
  all.actuator = 1.25;
  modules::Ahhs2Rule integer = all;
  integer.output = 1.0;  // item 1 only (item 2 gets 0)
  integer.actuator = 0.0;
  integer.zeta = -0.2;
  modules::Ahhs2Rule edge = all;
  edge.zeta = 0.1;  // with H[2] = 0 at the start: |0 - 0.1| = eta -> tent 0
  edge.eta = 0.1;
  edge.input = 2.0;
  modules::Ahhs2Rule narrow = all;
  narrow.eta = 0.01;
  narrow.zeta = 0.0;  // fires only while H[1] < 0.01
  narrow.input = 1.999;
  narrow.weights = {0, 0, 0.5, 0.5, 0};
  g.ahhs2_rules = {all, integer, edge, narrow};
  return g;
}

// AHHS1 rules on the tie band: hormone 0 saturates at 1 and comes back from diffusion within
// rounding of 1, where "below tau = 1" must not fire (docs/model.md).
Genome Ahhs1TieGenome() {
  Genome g;
  g.variant = modules::Variant::kAhhs1;
  g.num_sensors = 1;
  g.num_actuators = 1;
  g.hormones = {{0.1, 0.0, 0.07}, {0.01, 0.2, 0.03}};
  using T = modules::Ahhs1Type;
  using D = modules::Direction;
  g.ahhs1_rules = {{T::kHormone, 0, 1, 1.0, D::kBelow, 0.5, 0.01},
                   {T::kActuator, 0, 0, 1.0, D::kBelow, -2.0, 0.2},
                   {T::kSensor, 0, 0, 0.5, D::kAbove, 1.5, 0.1},
                   {T::kActuator, 1, 0, 0.0, D::kAbove, 0.7, -0.05},
                   {T::kIdle, 0, 0, 0.5, D::kAbove, 0, 0}};
  return g;
}

std::vector<Case> GeneratedCases() {
  std::vector<Case> cases;
  const struct {
    const char* name;
    modules::Shape shape;
    std::uint64_t seed;
  } random[] = {
      {"ahhs2-gait", {modules::Variant::kAhhs2, 5, 30, 6, 1}, 1},
      {"ahhs1-gait", {modules::Variant::kAhhs1, 5, 80, 6, 1}, 2},
      {"ahhs2-pendulum", {modules::Variant::kAhhs2, 15, 15, 4, 2}, 3},
      {"ahhs1-pendulum", {modules::Variant::kAhhs1, 15, 60, 4, 2}, 4},
  };
  for (const auto& r : random) {
    modules::Rng rng(modules::DeriveSeed(r.seed, {0x766563}));  // "vec"
    Case c;
    c.name = r.name;
    c.genome = modules::RandomGenome(r.shape, rng);
    c.ticks = RandomTicks(c.genome, 40, 2, 0.3, rng);
    cases.push_back(std::move(c));
  }
  {
    modules::Rng rng(modules::DeriveSeed(5, {0x766563}));
    Case c;
    c.name = "ahhs2-edges";
    c.genome = Ahhs2EdgeGenome();
    c.ticks = RandomTicks(c.genome, 30, 4, 0.2, rng);
    cases.push_back(std::move(c));
  }
  {
    modules::Rng rng(modules::DeriveSeed(6, {0x766563}));
    Case c;
    c.name = "ahhs1-tie-band";
    c.genome = Ahhs1TieGenome();
    c.ticks = RandomTicks(c.genome, 60, 2, 0.05, rng);
    for (auto& t : c.ticks) {  // two neighbours every tick: the middle of a chain
      t.num_neighbours = 2;
      t.received.resize(2, std::vector<double>(2, 0.0));
      for (auto& p : t.received) p[0] = 0.07 / 4;  // what a saturated neighbour sends
    }
    cases.push_back(std::move(c));
  }
  return cases;
}

// A line-by-line reader of the format; throws std::runtime_error("line N: ...").
class Reader {
 public:
  explicit Reader(const std::string& text) : in_(text) {}

  // The next non-comment line's tokens; false at the end.
  bool Next() {
    std::string line;
    while (std::getline(in_, line)) {
      ++number_;
      if (line.empty() || line[0] == '#') continue;
      tokens_.clear();
      std::istringstream words(line);
      std::string w;
      while (words >> w) tokens_.push_back(w);
      if (!tokens_.empty()) return true;
    }
    return false;
  }
  const std::string& key() const { return tokens_.front(); }
  std::size_t count() const { return tokens_.size() - 1; }
  void Expect(const std::string& key, std::size_t n) const {
    if (tokens_.front() != key) Fail("expected '" + key + "', found '" + tokens_.front() + "'");
    if (count() != n)
      Fail("'" + key + "' needs " + std::to_string(n) + " values, has " + std::to_string(count()));
  }
  double Real(std::size_t i) const {
    const std::string& t = tokens_.at(i + 1);
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (end == t.c_str() || *end != '\0' || !std::isfinite(v)) Fail("not a number: '" + t + "'");
    return v;
  }
  long long Int(std::size_t i) const {
    const std::string& t = tokens_.at(i + 1);
    char* end = nullptr;
    const long long v = std::strtoll(t.c_str(), &end, 10);
    if (end == t.c_str() || *end != '\0') Fail("not an integer: '" + t + "'");
    return v;
  }
  const std::string& Token(std::size_t i) const { return tokens_.at(i + 1); }
  std::vector<double> Reals() const {
    std::vector<double> v;
    for (std::size_t i = 0; i < count(); ++i) v.push_back(Real(i));
    return v;
  }
  [[noreturn]] void Fail(const std::string& what) const {
    throw std::runtime_error("line " + std::to_string(number_) + ": " + what);
  }

 private:
  std::istringstream in_;
  std::vector<std::string> tokens_;
  int number_ = 0;
};

Case ReadCase(Reader& r) {
  Case c;
  c.name = r.Token(0);
  if (!r.Next()) r.Fail("the case ends early");
  r.Expect("genome", 7);
  genome_t m{};
  m.episode = 0;
  m.variant = static_cast<std::int8_t>(r.Int(0));
  m.num_hormones = static_cast<std::int16_t>(r.Int(1));
  m.num_sensors = static_cast<std::int16_t>(r.Int(2));
  m.num_actuators = static_cast<std::int16_t>(r.Int(3));
  m.num_rules = static_cast<std::int16_t>(r.Int(4));
  m.fields_per_rule = static_cast<std::int16_t>(r.Int(5));
  m.genome_hash = static_cast<std::int64_t>(r.Int(6));
  const auto nh = static_cast<std::size_t>(m.num_hormones);
  for (const char* key : {"alpha", "mu", "diffusion"}) {
    if (!r.Next()) r.Fail("the case ends early");
    r.Expect(key, nh);
    (std::string(key) == "alpha" ? m.alpha
     : std::string(key) == "mu"  ? m.mu
                                 : m.diffusion) = r.Reals();
  }
  if (!r.Next()) r.Fail("the case ends early");
  r.Expect("rules",
           static_cast<std::size_t>(m.num_rules) * static_cast<std::size_t>(m.fields_per_rule));
  m.rule_values = r.Reals();
  m.num_rule_values = static_cast<std::int16_t>(m.rule_values.size());
  const std::string error = modules::GenomeFromMessage(m, &c.genome);
  if (!error.empty()) r.Fail("genome: " + error);
  const auto ns = static_cast<std::size_t>(c.genome.num_sensors);
  const auto na = static_cast<std::size_t>(c.genome.num_actuators);
  while (r.Next() && r.key() != "end") {
    r.Expect("tick", 1);
    Tick t;
    t.num_neighbours = static_cast<int>(r.Int(0));
    if (!r.Next()) r.Fail("the tick ends early");
    while (r.key() == "received") {
      r.Expect("received", nh);
      t.received.push_back(r.Reals());
      if (!r.Next()) r.Fail("the tick ends early");
    }
    r.Expect("sensors", ns);
    for (std::size_t i = 0; i < ns; ++i) {
      const bool absent = r.Token(i) == "-";
      t.sensors.push_back(absent ? 0.0 : r.Real(i));
      t.sensor_present.push_back(absent ? 0 : 1);
    }
    if (!r.Next()) r.Fail("the tick ends early");
    r.Expect("actuators", na);
    for (std::size_t i = 0; i < na; ++i) {
      if (r.Token(i) != "0" && r.Token(i) != "1") r.Fail("an actuator is 1 or 0");
      t.actuator_present.push_back(r.Token(i) == "1" ? 1 : 0);
    }
    VectorOutputs e;
    for (const auto& [key, n, dest] : {std::tuple<const char*, std::size_t, std::vector<double>*>{
                                           "expect_hormones", nh, &e.hormones},
                                       {"expect_actuators", na, &e.actuators},
                                       {"expect_outflow", nh, &e.outflow}}) {
      if (!r.Next()) r.Fail("the tick ends early");
      r.Expect(key, n);
      *dest = r.Reals();
    }
    c.ticks.push_back(std::move(t));
    c.expected.push_back(std::move(e));
  }
  if (r.key() != "end") r.Fail("case " + c.name + " has no 'end'");
  return c;
}

}  // namespace

std::string WriteModelVectors() {
  std::ostringstream out;
  out << "ahhs-model-vectors " << kModelVectorsVersion << '\n'
      << "# Golden vectors of the hormone controller: docs/hardware.md, \"Golden vectors\"; the\n"
      << "# evaluation order they pin: docs/model.md, \"Exact evaluation order\". Made by\n"
      << "# `ahhs-conformance vectors --write FILE` from modules/core.\n";
  for (const Case& c : GeneratedCases()) {
    const genome_t m = modules::GenomeMessage(c.genome, 0);
    out << "case " << c.name << '\n'
        << "genome " << static_cast<int>(m.variant) << ' ' << m.num_hormones << ' ' << m.num_sensors
        << ' ' << m.num_actuators << ' ' << m.num_rules << ' ' << m.fields_per_rule << ' '
        << m.genome_hash << '\n';
    Line(out, "alpha", m.alpha);
    Line(out, "mu", m.mu);
    Line(out, "diffusion", m.diffusion);
    Line(out, "rules", m.rule_values);
    const std::vector<VectorOutputs> outputs = Run(c);
    for (std::size_t k = 0; k < c.ticks.size(); ++k) {
      const Tick& t = c.ticks[k];
      out << "tick " << t.num_neighbours << '\n';
      for (const auto& p : t.received) Line(out, "received", p);
      out << "sensors";
      for (std::size_t s = 0; s < t.sensors.size(); ++s)
        out << ' ' << (t.sensor_present[s] ? base::ExactDouble(t.sensors[s]) : "-");
      out << "\nactuators";
      for (char a : t.actuator_present) out << ' ' << (a ? 1 : 0);
      out << '\n';
      Line(out, "expect_hormones", outputs[k].hormones);
      Line(out, "expect_actuators", outputs[k].actuators);
      Line(out, "expect_outflow", outputs[k].outflow);
    }
    out << "end\n";
  }
  return out.str();
}

std::string CheckModelVectors(const std::string& text) {
  try {
    Reader r(text);
    if (!r.Next() || r.key() != "ahhs-model-vectors" || r.count() != 1)
      r.Fail("not a model vectors file (its first line is 'ahhs-model-vectors VERSION')");
    if (r.Int(0) != kModelVectorsVersion)
      r.Fail("version " + r.Token(0) + " (this build reads version " +
             std::to_string(kModelVectorsVersion) + ")");
    int cases = 0;
    while (r.Next()) {
      r.Expect("case", 1);
      const Case c = ReadCase(r);
      ++cases;
      const std::vector<VectorOutputs> got = Run(c);
      for (std::size_t k = 0; k < got.size(); ++k)
        for (const auto& [key, want, have] :
             {std::tuple<const char*, const std::vector<double>*, const std::vector<double>*>{
                  "expect_hormones", &c.expected[k].hormones, &got[k].hormones},
              {"expect_actuators", &c.expected[k].actuators, &got[k].actuators},
              {"expect_outflow", &c.expected[k].outflow, &got[k].outflow}})
          for (std::size_t i = 0; i < want->size(); ++i)
            if ((*want)[i] != (*have)[i] || std::signbit((*want)[i]) != std::signbit((*have)[i]))
              return "case " + c.name + " tick " + std::to_string(k) + ": " + key + "[" +
                     std::to_string(i) + "] is " + base::ExactDouble((*want)[i]) +
                     ", modules/core gives " + base::ExactDouble((*have)[i]);
    }
    if (cases == 0) return "no case in the file";
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace ahhs::conformance
