#include "modules/core/variation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ahhs::modules {
namespace {

double Clamp(double v, double lo, double hi) { return std::min(hi, std::max(lo, v)); }

// Wraps a floating index into [0, n).
double WrapIndex(double x, int n) {
  double w = std::fmod(x, static_cast<double>(n));
  if (w < 0) w += n;
  if (w >= n) w = 0;  // -tiny + n rounds to n
  return w;
}

int WrapInt(int x, int n) { return ((x % n) + n) % n; }

// ±U(0, m)
double Step(Rng& rng, double m) { return rng.Sign() * rng.Uniform(0, m); }

HormoneGene RandomHormone(Rng& rng) {
  HormoneGene h;
  h.alpha = Clamp(rng.Uniform(0, 0.1), 0, Ranges::kAlphaMax);
  h.mu = Clamp(rng.Uniform(0, 0.1), 0, 1);
  h.diffusion = Clamp(rng.Uniform(0, 0.1), 0, 1);
  return h;
}

Ahhs2Rule RandomAhhs2Rule(const Shape& s, Rng& rng) {
  Ahhs2Rule r;
  // Uniform on the simplex: sort 4 uniform cut points of [0, 1], take the 5 differences.
  std::array<double, 6> cuts{0, rng.Uniform(), rng.Uniform(), rng.Uniform(), rng.Uniform(), 1};
  std::sort(cuts.begin() + 1, cuts.begin() + 5);
  for (std::size_t p = 0; p < 5; ++p) r.weights[p] = cuts[p + 1] - cuts[p];
  r.zeta = rng.Uniform(-1, 1);
  r.eta = rng.Uniform(Ranges::kEtaMin, Ranges::kEtaMax);
  r.kappa = rng.Uniform(-Ranges::kKappaMax, Ranges::kKappaMax);
  r.lambda = rng.Uniform(-Ranges::kLambdaMax, Ranges::kLambdaMax);
  r.sensor = rng.Uniform(0, s.sensors);
  r.input = rng.Uniform(0, s.hormones);
  r.output = rng.Uniform(0, s.hormones);
  r.actuator = rng.Uniform(0, s.actuators);
  return r;
}

int InputRange(const Shape& s, Ahhs1Type t) {
  return t == Ahhs1Type::kSensor ? s.sensors : s.hormones;
}
int OutputRange(const Shape& s, Ahhs1Type t) {
  return t == Ahhs1Type::kActuator ? s.actuators : s.hormones;
}

Ahhs1Rule RandomAhhs1Rule(const Shape& s, Rng& rng) {
  Ahhs1Rule r;
  r.type = static_cast<Ahhs1Type>(rng.UniformInt(4));
  r.input = rng.UniformInt(InputRange(s, r.type));
  r.output = rng.UniformInt(OutputRange(s, r.type));
  r.tau = rng.Uniform();
  r.direction = static_cast<Direction>(rng.UniformInt(2));
  r.kappa = rng.Uniform(-Ranges::kKappaMax, Ranges::kKappaMax);
  r.lambda = rng.Uniform(-Ranges::kLambdaMax, Ranges::kLambdaMax);
  return r;
}

void MutateHormone(HormoneGene* h, double m, Rng& rng) {
  switch (rng.UniformInt(3)) {
    case 0:
      h->alpha = Clamp(h->alpha + Step(rng, m), 0, Ranges::kAlphaMax);
      break;
    case 1:
      h->mu = Clamp(h->mu + Step(rng, m), 0, 1);
      break;
    default:
      h->diffusion = Clamp(h->diffusion + Step(rng, m), 0, 1);
      break;
  }
}

// The paper's "reduce one weight by w and add w to another": the donor is a type with
// positive weight, the receiver any other type, w ~ U(0, m) capped at the donor's weight.
void ShiftWeight(Ahhs2Rule* r, double m, Rng& rng) {
  std::array<int, 5> donors{};
  int num_donors = 0;
  for (int p = 0; p < 5; ++p)
    if (r->weights[static_cast<std::size_t>(p)] > 0)
      donors[static_cast<std::size_t>(num_donors++)] = p;
  const auto from =
      static_cast<std::size_t>(donors[static_cast<std::size_t>(rng.UniformInt(num_donors))]);
  auto to = static_cast<std::size_t>(rng.UniformInt(4));
  if (to >= from) ++to;
  const double w = std::min(rng.Uniform(0, m), r->weights[from]);
  r->weights[from] -= w;
  r->weights[to] += w;
  // Renormalise so rounding never lets the sum drift from 1 over many mutations.
  double sum = 0;
  for (double v : r->weights) sum += v;
  for (double& v : r->weights) v /= sum;
}

void MutateAhhs2Rule(Ahhs2Rule* r, const Shape& s, const MutationParams& params, Rng& rng) {
  const double m = params.max_change;
  const bool fine = params.profile == MutationProfile::kFineDoses;
  const double dose_step = fine ? m / 50 : m;  // lambda, kappa
  const double index_step = fine ? 1.0 : m;    // floating indices
  // 15 equally likely outcomes: 7 weight shifts, or one of the 8 other fields.
  const int pick = rng.UniformInt(15);
  if (pick < 7) return ShiftWeight(r, m, rng);
  switch (pick - 7) {
    case 0:
      r->zeta = Clamp(r->zeta + Step(rng, m), Ranges::kZetaMin, Ranges::kZetaMax);
      break;
    case 1:
      r->eta = Clamp(r->eta + Step(rng, m), Ranges::kEtaMin, Ranges::kEtaMax);
      break;
    case 2:
      r->lambda = Clamp(r->lambda + Step(rng, dose_step), -Ranges::kLambdaMax, Ranges::kLambdaMax);
      break;
    case 3:
      r->kappa = Clamp(r->kappa + Step(rng, dose_step), -Ranges::kKappaMax, Ranges::kKappaMax);
      break;
    case 4:
      r->sensor = WrapIndex(r->sensor + Step(rng, index_step), s.sensors);
      break;
    case 5:
      r->input = WrapIndex(r->input + Step(rng, index_step), s.hormones);
      break;
    case 6:
      r->output = WrapIndex(r->output + Step(rng, index_step), s.hormones);
      break;
    default:
      r->actuator = WrapIndex(r->actuator + Step(rng, index_step), s.actuators);
      break;
  }
}

void MutateAhhs1Rule(Ahhs1Rule* r, const Shape& s, double m, Rng& rng) {
  switch (rng.UniformInt(7)) {
    case 0: {  // the radical discrete switch to another type
      int t = rng.UniformInt(3);
      if (t >= static_cast<int>(r->type)) ++t;
      r->type = static_cast<Ahhs1Type>(t);
      // Indices keep their value where the new type's range allows, else wrap into it.
      r->input = WrapInt(r->input, InputRange(s, r->type));
      r->output = WrapInt(r->output, OutputRange(s, r->type));
      break;
    }
    case 1:
      r->tau = Clamp(r->tau + Step(rng, m), 0, 1);
      break;
    case 2:
      r->lambda = Clamp(r->lambda + Step(rng, m), -Ranges::kLambdaMax, Ranges::kLambdaMax);
      break;
    case 3:
      r->kappa = Clamp(r->kappa + Step(rng, m), -Ranges::kKappaMax, Ranges::kKappaMax);
      break;
    case 4:
      r->direction = r->direction == Direction::kAbove ? Direction::kBelow : Direction::kAbove;
      break;
    case 5:
      r->input = WrapInt(r->input + (rng.Sign() > 0 ? 1 : -1), InputRange(s, r->type));
      break;
    default:
      r->output = WrapInt(r->output + (rng.Sign() > 0 ? 1 : -1), OutputRange(s, r->type));
      break;
  }
}

void MutateGene(Genome* g, int gene, const MutationParams& params, Rng& rng) {
  const Shape s = g->shape();
  const double m = params.max_change;
  if (gene < s.hormones) return MutateHormone(&g->hormones[static_cast<std::size_t>(gene)], m, rng);
  const auto r = static_cast<std::size_t>(gene - s.hormones);
  if (g->variant == Variant::kAhhs2)
    MutateAhhs2Rule(&g->ahhs2_rules[r], s, params, rng);
  else
    MutateAhhs1Rule(&g->ahhs1_rules[r], s, m, rng);
}

template <class T>
void CrossList(std::vector<T>* a, std::vector<T>* b, Rng& rng) {
  const int n = static_cast<int>(a->size());
  int c1 = rng.UniformInt(n + 1);
  int c2 = rng.UniformInt(n + 1);
  if (c1 > c2) std::swap(c1, c2);
  for (int k = c1; k < c2; ++k)
    std::swap((*a)[static_cast<std::size_t>(k)], (*b)[static_cast<std::size_t>(k)]);
}

}  // namespace

const char* MutationProfileName(MutationProfile profile) {
  return profile == MutationProfile::kPaper ? "paper" : "fine-doses";
}

MutationProfile ParseMutationProfile(const std::string& name) {
  if (name == "paper") return MutationProfile::kPaper;
  if (name == "fine-doses") return MutationProfile::kFineDoses;
  throw std::invalid_argument("unknown mutation profile '" + name + "' (use paper or fine-doses)");
}

Genome RandomGenome(const Shape& s, Rng& rng) {
  if (s.hormones < 1 || s.sensors < 1 || s.actuators < 1 || s.rules < 0 ||
      s.hormones > Ranges::kMaxHormones || s.rules > Ranges::kMaxRules ||
      s.sensors > Ranges::kMaxSlots || s.actuators > Ranges::kMaxSlots)
    throw std::invalid_argument("genome shape needs >= 1 hormone, sensor and actuator, >= 0 rules");
  Genome g;
  g.variant = s.variant;
  g.num_sensors = s.sensors;
  g.num_actuators = s.actuators;
  for (int h = 0; h < s.hormones; ++h) g.hormones.push_back(RandomHormone(rng));
  for (int r = 0; r < s.rules; ++r) {
    if (s.variant == Variant::kAhhs2)
      g.ahhs2_rules.push_back(RandomAhhs2Rule(s, rng));
    else
      g.ahhs1_rules.push_back(RandomAhhs1Rule(s, rng));
  }
  return g;
}

int Mutate(Genome* g, const MutationParams& params, Rng& rng) {
  const int genes = g->num_hormones() + g->num_rules();
  int mutated = 0;
  for (int gene = 0; gene < genes; ++gene) {
    if (!rng.Bernoulli(params.gene_rate)) continue;
    MutateGene(g, gene, params, rng);
    ++mutated;
  }
  return mutated;
}

void MutateOneGene(Genome* g, const MutationParams& params, Rng& rng) {
  MutateGene(g, rng.UniformInt(g->num_hormones() + g->num_rules()), params, rng);
}

std::pair<Genome, Genome> Crossover(const Genome& a, const Genome& b, Rng& rng) {
  if (a.shape() != b.shape())
    throw std::invalid_argument("crossover needs two genomes of the same shape");
  std::pair<Genome, Genome> children{a, b};
  CrossList(&children.first.hormones, &children.second.hormones, rng);
  if (a.variant == Variant::kAhhs2)
    CrossList(&children.first.ahhs2_rules, &children.second.ahhs2_rules, rng);
  else
    CrossList(&children.first.ahhs1_rules, &children.second.ahhs1_rules, rng);
  return children;
}

}  // namespace ahhs::modules
