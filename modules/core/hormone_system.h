// The hormone system of one compartment (docs/model.md, "One tick").
// Controller is the const model compiled from a genome; CompartmentState is the mutable data of
// one compartment. Step() allocates nothing, touches no globals and does no I/O.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "modules/core/genome.h"

namespace ahhs::modules {

// Columns of CompartmentState::part_activity. AHHS1 rules count in the column of their type.
enum ActivityColumn : int { kActSensor = 0, kActLinear = 1, kActNonlinear = 2, kActActuator = 3 };
inline constexpr int kActivityColumns = 4;

// Docking ports of a module: the diffusion denominator P of docs/model.md.
inline constexpr int kDefaultPorts = 4;

struct TickInput;
struct CompartmentState;

class Controller {
 public:
  // Throws std::invalid_argument when CheckGenome(genome) fails or ports < 1.
  explicit Controller(Genome genome, int ports = kDefaultPorts);

  const Genome& genome() const { return genome_; }
  int num_hormones() const { return genome_.num_hormones(); }
  int num_sensors() const { return genome_.num_sensors; }
  int num_actuators() const { return genome_.num_actuators; }
  int num_rules() const { return genome_.num_rules(); }
  int ports() const { return ports_; }

  // An AHHS2 rule with its floating indices resolved: inputs read floor(x); outputs split
  // between items k = floor(x) and (k+1) mod n with weights 1-f and f.
  struct CompiledRule {
    double w_sensor, w_linear, w_nonlinear, w_actuator;
    double zeta, inv_eta, kappa, lambda;
    int sensor, input;
    int out0, out1;
    double out_w0, out_w1;
    int act0, act1;
    double act_w0, act_w1;
  };

 private:
  friend void Step(const Controller&, const TickInput&, CompartmentState*);

  Genome genome_;
  int ports_;
  std::vector<CompiledRule> rules2_;
  Eigen::VectorXd alpha_;
  Eigen::VectorXd mu_;
  Eigen::VectorXd diffusion_per_port_;  // D_h / P
  std::unique_ptr<bool[]> no_sensors_;  // num_sensors x false: the mask when no sensors are given
};

// What one compartment sees in one tick.
struct TickInput {
  const double* sensors = nullptr;  // num_sensors values in [0, 1] (nullptr: every slot absent)
  // Ownership masks, num_sensors / num_actuators entries; nullptr = every slot present. A rule
  // part that reads an absent sensor or writes an absent actuator contributes nothing.
  const bool* sensor_present = nullptr;
  const bool* actuator_present = nullptr;
  int num_neighbours = 0;  // docked neighbours this tick, <= ports (each gets one packet)
};

struct CompartmentState {
  Eigen::VectorXd hormones;   // H, concentrations in [0, 1] after every Step
  Eigen::VectorXd actuators;  // A of the last tick, in [-1, 1]; 0 where absent
  Eigen::VectorXd outflow;    // q: amount sent to EACH docked neighbour in the last tick
  Eigen::VectorXd delta;      // scratch: dH of the current tick
  // Ticks in which each rule part triggered (row-major, num_rules x kActivityColumns), and
  // ticks in which any part of the rule triggered.
  std::vector<std::uint64_t> part_activity;
  std::vector<std::uint64_t> rule_activity;
  std::int64_t ticks = 0;
};

// A compartment at rest: every concentration 0, nothing sent, counters 0.
CompartmentState MakeState(const Controller& controller);

// Step 1 of a tick: adds one received diffusion packet (num_hormones amounts). Call once per
// packet, in increasing order of the sender's id, before Step().
void ReceiveHormones(const double* amounts, CompartmentState* state);

// Steps 2-6: evaluate every rule on start-of-tick values, production/decay/clamp, diffusion
// (state->outflow is what each of input.num_neighbours neighbours must receive next tick; it has
// already left state->hormones), actuators into state->actuators.
void Step(const Controller& controller, const TickInput& input, CompartmentState* state);

// The AHHS2 trigger (paper eq. 2): max(0, 1 - |x - zeta| / eta).
inline double Tent(double x, double zeta, double eta) {
  const double d = x > zeta ? x - zeta : zeta - x;
  return d < eta ? 1.0 - d / eta : 0.0;
}

// Values closer than this to an AHHS1 threshold count as equal to it. Concentrations that are
// equal in exact arithmetic can differ by a few units in the last place once diffusion has
// summed them in different orders (a saturated middle module gets 1 - 2q + q + q = 1 - 1e-16):
// without a tie band a "below tau = 1" rule would fire there and not in an end module.
constexpr double kThresholdTie = 1e-12;

// The AHHS1 trigger: 1 when x is above (below) tau by more than kThresholdTie, else 0.
inline bool Threshold(double x, double tau, Direction dir) {
  return dir == Direction::kAbove ? x > tau + kThresholdTie : x < tau - kThresholdTie;
}

}  // namespace ahhs::modules
