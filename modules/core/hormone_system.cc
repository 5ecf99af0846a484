#include "modules/core/hormone_system.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ahhs::modules {
namespace {

// Splits a floating index x in [0, n) into items floor(x), (floor(x)+1) mod n and weights.
void SplitIndex(double x, int n, int* k0, int* k1, double* w0, double* w1) {
  const int k = std::min(static_cast<int>(std::floor(x)), n - 1);
  const double f = x - k;
  *k0 = k;
  *k1 = (k + 1) % n;
  *w0 = 1.0 - f;
  *w1 = f;
}

}  // namespace

Controller::Controller(Genome genome, int ports) : genome_(std::move(genome)), ports_(ports) {
  const std::string error = CheckGenome(genome_);
  if (!error.empty()) throw std::invalid_argument("invalid genome: " + error);
  if (ports < 1) throw std::invalid_argument("a module needs at least one docking port");
  const int nh = genome_.num_hormones();
  alpha_.resize(nh);
  mu_.resize(nh);
  diffusion_per_port_.resize(nh);
  for (int h = 0; h < nh; ++h) {
    const HormoneGene& g = genome_.hormones[static_cast<std::size_t>(h)];
    alpha_[h] = g.alpha;
    mu_[h] = g.mu;
    diffusion_per_port_[h] = g.diffusion / ports;
  }
  for (const Ahhs2Rule& r : genome_.ahhs2_rules) {
    CompiledRule c{};
    c.w_sensor = r.weights[kSensorPart];
    c.w_linear = r.weights[kLinearPart];
    c.w_nonlinear = r.weights[kNonlinearPart];
    c.w_actuator = r.weights[kActuatorPart];
    c.zeta = r.zeta;
    c.inv_eta = 1.0 / r.eta;
    c.kappa = r.kappa;
    c.lambda = r.lambda;
    c.sensor = static_cast<int>(std::floor(r.sensor));
    c.input = static_cast<int>(std::floor(r.input));
    SplitIndex(r.output, nh, &c.out0, &c.out1, &c.out_w0, &c.out_w1);
    SplitIndex(r.actuator, genome_.num_actuators, &c.act0, &c.act1, &c.act_w0, &c.act_w1);
    rules2_.push_back(c);
  }
  no_sensors_ =
      std::make_unique<bool[]>(static_cast<std::size_t>(genome_.num_sensors));  // all false
}

CompartmentState MakeState(const Controller& c) {
  CompartmentState s;
  s.hormones = Eigen::VectorXd::Zero(c.num_hormones());
  s.actuators = Eigen::VectorXd::Zero(c.num_actuators());
  s.outflow = Eigen::VectorXd::Zero(c.num_hormones());
  s.delta = Eigen::VectorXd::Zero(c.num_hormones());
  s.part_activity.assign(static_cast<std::size_t>(c.num_rules() * kActivityColumns), 0);
  s.rule_activity.assign(static_cast<std::size_t>(c.num_rules()), 0);
  return s;
}

void ReceiveHormones(const double* amounts, CompartmentState* s) {
  s->hormones += Eigen::Map<const Eigen::VectorXd>(amounts, s->hormones.size());
}

namespace {

// Tent value with a precomputed 1/eta.
inline double TentInv(double x, double zeta, double inv_eta) {
  const double t = 1.0 - std::fabs(x - zeta) * inv_eta;
  return t > 0.0 ? t : 0.0;
}

// kSensorMask / kActuatorMask: whether ownership masks are given; resolved once per tick so the
// rule loop does not test for them.
template <bool kSensorMask, bool kActuatorMask>
void StepAhhs2(const std::vector<Controller::CompiledRule>& rules, const TickInput& in,
               CompartmentState* s) {
  const double* H = s->hormones.data();
  double* dH = s->delta.data();
  double* A = s->actuators.data();
  std::uint64_t* parts = s->part_activity.data();
  std::uint64_t* any = s->rule_activity.data();
  for (std::size_t r = 0; r < rules.size(); ++r) {
    const auto& c = rules[r];
    std::uint64_t* p = parts + r * kActivityColumns;
    // The sensor and linear parts add to the same split output; sum them before touching dH.
    double v_out = 0.0;
    bool fired = false;
    // Sensor part: reads S[floor(s)] only if this compartment owns that sensor.
    if (c.w_sensor > 0 && (!kSensorMask || in.sensor_present[c.sensor])) {
      const double xs = in.sensors[c.sensor];
      const double ts = TentInv(xs, c.zeta, c.inv_eta);
      if (ts > 0) {
        v_out = c.w_sensor * ts * (c.lambda * xs + c.kappa);
        ++p[kActSensor];
        fired = true;
      }
    }
    // The hormone-triggered parts share x = H[floor(i)] and its tent value.
    const double x = H[c.input];
    const double t = TentInv(x, c.zeta, c.inv_eta);
    if (t > 0) {
      const double dose = c.lambda * x + c.kappa;
      if (c.w_linear > 0) {
        v_out += c.w_linear * t * dose;
        ++p[kActLinear];
        fired = true;
      }
      if (c.w_nonlinear > 0) {  // dx/dt = x*y: each target item uses its own concentration
        const double wt = c.w_nonlinear * t;
        dH[c.out0] += c.out_w0 * (v_out + wt * (c.lambda * x * H[c.out0] + c.kappa));
        dH[c.out1] += c.out_w1 * (v_out + wt * (c.lambda * x * H[c.out1] + c.kappa));
        v_out = 0.0;  // already added
        ++p[kActNonlinear];
        fired = true;
      }
      if (c.w_actuator > 0) {
        const double v = c.w_actuator * t * dose;
        const bool own0 = !kActuatorMask || in.actuator_present[c.act0];
        const bool own1 = !kActuatorMask || in.actuator_present[c.act1];
        if (own0) A[c.act0] += c.act_w0 * v;
        if (own1) A[c.act1] += c.act_w1 * v;
        if (own0 || own1) {
          ++p[kActActuator];
          fired = true;
        }
      }
    }
    if (v_out != 0.0) {
      dH[c.out0] += c.out_w0 * v_out;
      dH[c.out1] += c.out_w1 * v_out;
    }
    any[r] += fired ? 1 : 0;
  }
}

void StepAhhs1(const std::vector<Ahhs1Rule>& rules, const TickInput& in, CompartmentState* s) {
  const double* H = s->hormones.data();
  double* dH = s->delta.data();
  double* A = s->actuators.data();
  for (std::size_t r = 0; r < rules.size(); ++r) {
    const Ahhs1Rule& rule = rules[r];
    std::uint64_t* p = s->part_activity.data() + r * kActivityColumns;
    switch (rule.type) {
      case Ahhs1Type::kIdle:
        break;
      case Ahhs1Type::kSensor: {
        if (in.sensors == nullptr || (in.sensor_present && !in.sensor_present[rule.input])) break;
        const double x = in.sensors[rule.input];
        if (!Threshold(x, rule.tau, rule.direction)) break;
        dH[rule.output] += rule.lambda * x + rule.kappa;
        ++p[kActSensor];
        ++s->rule_activity[r];
        break;
      }
      case Ahhs1Type::kHormone: {
        const double x = H[rule.input];
        if (!Threshold(x, rule.tau, rule.direction)) break;
        dH[rule.output] += rule.lambda * x + rule.kappa;
        ++p[kActLinear];
        ++s->rule_activity[r];
        break;
      }
      case Ahhs1Type::kActuator: {
        if (in.actuator_present && !in.actuator_present[rule.output]) break;
        const double x = H[rule.input];
        if (!Threshold(x, rule.tau, rule.direction)) break;
        A[rule.output] += rule.lambda * x + rule.kappa;
        ++p[kActActuator];
        ++s->rule_activity[r];
        break;
      }
    }
  }
}

}  // namespace

void Step(const Controller& c, const TickInput& in, CompartmentState* s) {
  // 3. Every rule reads H and S as they are at the start of the tick; effects go to dH and A.
  std::fill(s->delta.data(), s->delta.data() + s->delta.size(), 0.0);
  std::fill(s->actuators.data(), s->actuators.data() + s->actuators.size(), 0.0);
  if (c.genome_.variant == Variant::kAhhs2) {
    // No sensor values at all means every sensor slot is absent.
    TickInput effective = in;
    if (in.sensors == nullptr) effective.sensor_present = c.no_sensors_.get();
    const bool sensor_mask = effective.sensor_present != nullptr;
    const bool actuator_mask = in.actuator_present != nullptr;
    if (sensor_mask && actuator_mask)
      StepAhhs2<true, true>(c.rules2_, effective, s);
    else if (sensor_mask)
      StepAhhs2<true, false>(c.rules2_, effective, s);
    else if (actuator_mask)
      StepAhhs2<false, true>(c.rules2_, effective, s);
    else
      StepAhhs2<false, false>(c.rules2_, effective, s);
  } else
    StepAhhs1(c.genome_.ahhs1_rules, in, s);

  // 4. Production, decay, rule effects; clamp. 5. Diffusion: q_h = D_h * H_h / P goes to each
  // docked neighbour and is gone from here. One plain loop: for the handful of hormones a
  // controller has, this beats Eigen's vectorised expression with its alignment prologue.
  const int nh = c.num_hormones();
  const double neighbours = static_cast<double>(in.num_neighbours);
  double* H = s->hormones.data();
  double* q = s->outflow.data();
  const double* dH = s->delta.data();
  for (int h = 0; h < nh; ++h) {
    const double v = H[h] + c.alpha_[h] - c.mu_[h] * H[h] + dH[h];
    const double clamped = v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v);
    q[h] = c.diffusion_per_port_[h] * clamped;
    H[h] = in.num_neighbours > 0 ? clamped - neighbours * q[h] : clamped;
  }
  double* A = s->actuators.data();
  for (int a = 0; a < c.num_actuators(); ++a) A[a] = A[a] < -1.0 ? -1.0 : (A[a] > 1.0 ? 1.0 : A[a]);
  ++s->ticks;
}

}  // namespace ahhs::modules
