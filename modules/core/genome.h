// AHHS1 and AHHS2 genomes (docs/model.md): plain data shared by
// every compartment of a robot. Value ranges below are invariants that random initialisation,
// mutation, crossover and file loading all keep.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace ahhs::modules {

enum class Variant : int { kAhhs1 = 1, kAhhs2 = 2 };

// Per-hormone genes, all per controller tick.
struct HormoneGene {
  double alpha = 0;      // base production, [0, 0.1]
  double mu = 0;         // decay rate, [0, 1]
  double diffusion = 0;  // diffusion coefficient D, [0, 1]
};

// AHHS2 rule: every rule acts as every type at once, scaled by its type weight.
enum Ahhs2Part : int {
  kIdle = 0,
  kSensorPart = 1,
  kLinearPart = 2,
  kNonlinearPart = 3,
  kActuatorPart = 4
};
struct Ahhs2Rule {
  std::array<double, 5> weights{1, 0, 0, 0, 0};  // indexed by Ahhs2Part; >= 0, sum 1
  double zeta = 0;                               // trigger window centre, [-1, 1]
  double eta = 0.1;                              // trigger window width, [0.01, 0.5]
  double kappa = 0;                              // fixed dose, [-0.2, 0.2]
  double lambda = 0;                             // dependent dose, [-2, 2]
  double sensor = 0;    // floating input index into sensors, [0, num_sensors)
  double input = 0;     // floating input index into hormones, [0, num_hormones)
  double output = 0;    // floating output index into hormones, [0, num_hormones)
  double actuator = 0;  // floating output index into actuators, [0, num_actuators)
};

// AHHS1 rule: one discrete type, threshold trigger.
enum class Ahhs1Type : int { kIdle = 0, kSensor = 1, kHormone = 2, kActuator = 3 };
enum class Direction : int { kBelow = 0, kAbove = 1 };
struct Ahhs1Rule {
  Ahhs1Type type = Ahhs1Type::kIdle;
  int input = 0;     // sensor index (sensor rule) or hormone index (hormone, actuator rule)
  int output = 0;    // hormone index (sensor, hormone rule) or actuator index (actuator rule)
  double tau = 0.5;  // threshold, [0, 1]
  Direction direction = Direction::kAbove;
  double lambda = 0;  // [-2, 2]
  double kappa = 0;   // [-0.2, 0.2]
};

// Sizes a genome is made for.
struct Shape {
  Variant variant = Variant::kAhhs2;
  int hormones = 1;
  int rules = 0;
  int sensors = 1;
  int actuators = 1;
  bool operator==(const Shape& o) const {
    return variant == o.variant && hormones == o.hormones && rules == o.rules &&
           sensors == o.sensors && actuators == o.actuators;
  }
  bool operator!=(const Shape& o) const { return !(*this == o); }
};

struct Genome {
  Variant variant = Variant::kAhhs2;
  int num_sensors = 1;
  int num_actuators = 1;
  std::vector<HormoneGene> hormones;
  std::vector<Ahhs1Rule> ahhs1_rules;  // used when variant == kAhhs1
  std::vector<Ahhs2Rule> ahhs2_rules;  // used when variant == kAhhs2

  int num_hormones() const { return static_cast<int>(hormones.size()); }
  int num_rules() const {
    return static_cast<int>(variant == Variant::kAhhs1 ? ahhs1_rules.size() : ahhs2_rules.size());
  }
  Shape shape() const { return {variant, num_hormones(), num_rules(), num_sensors, num_actuators}; }
};

// Parameter ranges (docs/model.md).
struct Ranges {
  static constexpr double kAlphaMax = 0.1;
  static constexpr double kZetaMin = -1, kZetaMax = 1;
  static constexpr double kEtaMin = 0.01, kEtaMax = 0.5;
  static constexpr double kKappaMax = 0.2;   // kappa in [-kKappaMax, kKappaMax]
  static constexpr double kLambdaMax = 2.0;  // lambda in [-kLambdaMax, kLambdaMax]
  static constexpr double kWeightSumTolerance = 1e-9;
  static constexpr int kMaxHormones = 1000, kMaxRules = 10000, kMaxSlots = 1000;
};

// Checks every invariant; returns "" when valid, else a message naming the first bad field,
// e.g. "rules[3].weights: sum 1.2 is not 1".
std::string CheckGenome(const Genome& genome);

// FNV-1a 64 over the genome's shape and the exact bits of every value: equal hashes mean the
// same controller (used to check what a module runs).
std::uint64_t GenomeHash(const Genome& genome);
// A genome hash as files and messages show it: 16 lower-case hex digits.
std::string HashText(std::uint64_t hash);
std::string GenomeHashText(const Genome& genome);  // HashText(GenomeHash(genome))

const char* VariantName(Variant v);      // "ahhs1" / "ahhs2"
const char* Ahhs1TypeName(Ahhs1Type t);  // "idle", "sensor", "hormone", "actuator"
const char* Ahhs2PartName(int part);     // "idle", "sensor", "linear", "nonlinear", "actuator"

}  // namespace ahhs::modules
