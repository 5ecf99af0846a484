#include "modules/node/genome_codec.h"

#include <cmath>

namespace ahhs::modules {

genome_t GenomeMessage(const Genome& g, std::int64_t episode) {
  genome_t m{};
  m.episode = episode;
  m.genome_hash = static_cast<std::int64_t>(GenomeHash(g));
  m.variant = g.variant == Variant::kAhhs1 ? genome_t::AHHS1 : genome_t::AHHS2;
  m.num_sensors = static_cast<std::int16_t>(g.num_sensors);
  m.num_actuators = static_cast<std::int16_t>(g.num_actuators);
  m.num_hormones = static_cast<std::int16_t>(g.num_hormones());
  for (const auto& h : g.hormones) {
    m.alpha.push_back(h.alpha);
    m.mu.push_back(h.mu);
    m.diffusion.push_back(h.diffusion);
  }
  m.num_rules = static_cast<std::int16_t>(g.num_rules());
  if (g.variant == Variant::kAhhs2) {
    m.fields_per_rule = kAhhs2FieldsPerRule;
    for (const auto& r : g.ahhs2_rules) {
      m.rule_values.insert(m.rule_values.end(), r.weights.begin(), r.weights.end());
      m.rule_values.insert(m.rule_values.end(), {r.zeta, r.eta, r.kappa, r.lambda, r.sensor,
                                                 r.input, r.output, r.actuator});
    }
  } else {
    m.fields_per_rule = kAhhs1FieldsPerRule;
    for (const auto& r : g.ahhs1_rules) {
      m.rule_values.insert(
          m.rule_values.end(),
          {static_cast<double>(r.type), static_cast<double>(r.input), static_cast<double>(r.output),
           r.tau, static_cast<double>(r.direction), r.lambda, r.kappa});
    }
  }
  m.num_rule_values = static_cast<std::int16_t>(m.rule_values.size());
  return m;
}

std::string GenomeFromMessage(const genome_t& m, Genome* out) {
  Genome g;
  if (m.variant == genome_t::AHHS1) {
    g.variant = Variant::kAhhs1;
  } else if (m.variant == genome_t::AHHS2) {
    g.variant = Variant::kAhhs2;
  } else {
    return "unknown variant";
  }
  const int per_rule = g.variant == Variant::kAhhs2 ? kAhhs2FieldsPerRule : kAhhs1FieldsPerRule;
  if (m.fields_per_rule != per_rule || m.num_rules < 0 ||
      m.num_rule_values != m.num_rules * per_rule)
    return "rule array has the wrong size";
  g.num_sensors = m.num_sensors;
  g.num_actuators = m.num_actuators;
  for (int h = 0; h < m.num_hormones; ++h) {
    const auto k = static_cast<std::size_t>(h);
    g.hormones.push_back({m.alpha[k], m.mu[k], m.diffusion[k]});
  }
  for (int r = 0; r < m.num_rules; ++r) {
    const double* v = &m.rule_values[static_cast<std::size_t>(r * per_rule)];
    if (g.variant == Variant::kAhhs2) {
      Ahhs2Rule rule;
      for (std::size_t p = 0; p < 5; ++p) rule.weights[p] = v[p];
      rule.zeta = v[5];
      rule.eta = v[6];
      rule.kappa = v[7];
      rule.lambda = v[8];
      rule.sensor = v[9];
      rule.input = v[10];
      rule.output = v[11];
      rule.actuator = v[12];
      g.ahhs2_rules.push_back(rule);
    } else {
      for (int k : {0, 1, 2, 4})
        if (!std::isfinite(v[k]) || v[k] != std::floor(v[k]) || std::fabs(v[k]) > 1e6)
          return "rule field is not an integer";
      Ahhs1Rule rule;
      if (v[0] < 0 || v[0] > 3) return "unknown AHHS1 rule type";
      if (v[4] < 0 || v[4] > 1) return "unknown AHHS1 direction";
      rule.type = static_cast<Ahhs1Type>(static_cast<int>(v[0]));
      rule.input = static_cast<int>(v[1]);
      rule.output = static_cast<int>(v[2]);
      rule.tau = v[3];
      rule.direction = static_cast<Direction>(static_cast<int>(v[4]));
      rule.lambda = v[5];
      rule.kappa = v[6];
      g.ahhs1_rules.push_back(rule);
    }
  }
  const std::string error = CheckGenome(g);
  if (!error.empty()) return error;
  if (static_cast<std::uint64_t>(m.genome_hash) != GenomeHash(g))
    return "genome hash does not match its contents";
  *out = std::move(g);
  return "";
}

bool GenomeHashMatches(std::int64_t reported, std::uint64_t expected) {
  const auto bits = static_cast<std::int64_t>(expected);
  return reported == bits || static_cast<double>(reported) == static_cast<double>(bits);
}

}  // namespace ahhs::modules
