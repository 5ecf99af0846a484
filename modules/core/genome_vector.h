// A genome as a flat vector of reals with bounds, for continuous optimizers (CMA-ES and the like;
// docs/genome.md, "Genome vectors"). The layout depends on the shape alone, in this order:
//   per hormone: alpha [0, 0.1], mu [0, 1], diffusion [0, 1];
//   AHHS2, per rule: the five type weights [0, 1] (idle, sensor, linear, nonlinear, actuator),
//     zeta [-1, 1], eta [0.01, 0.5], kappa [-0.2, 0.2], lambda [-2, 2], and the floating indices
//     sensor [0, S], input [0, H], output [0, H], actuator [0, A];
//   AHHS1, per rule: type [0, 4], input [0, 1], output [0, 1], tau [0, 1], direction [0, 2],
//     lambda [-2, 2], kappa [-0.2, 0.2]. A discrete field is encoded, not kept fixed: the type is
//     the integer its value floors to (idle, sensor, hormone, actuator), the direction likewise
//     (below, above), and input and output are shares of their range, index floor(x * n) with n
//     the range of the rule's type (sensors or hormones in, hormones or actuators out).
// GenomeToVector puts every discrete field in the middle of its interval, so
// GenomeFromVector(GenomeToVector(g)) is g bit for bit.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "modules/core/genome.h"

namespace ahhs::modules {

struct VectorLayout {
  std::vector<std::string> names;  // "hormones[0].alpha", "rules[3].weights.linear", ...
  std::vector<double> lower, upper;
  std::size_t size() const { return names.size(); }
};

// The layout of every genome of `shape`.
VectorLayout GenomeVectorLayout(const Shape& shape);

// The genome's vector (real fields copied exactly, discrete ones at their intervals' middles).
std::vector<double> GenomeToVector(const Genome& genome);

// The genome of `shape` a vector gives. Every value is first clipped into its bounds (an
// optimizer's sample may leave them; a floating index to just below its upper bound), and AHHS2
// weights whose sum is not 1 (within the genomes' tolerance) are divided by their sum (all zero:
// an idle rule). Throws std::invalid_argument for a vector of the wrong length or a value that
// is not finite, naming the field.
Genome GenomeFromVector(const Shape& shape, const std::vector<double>& x);

inline constexpr int kGenomeVectorVersion = 1;
inline std::string GenomeVectorLine() {  // for --version
  return "genome vector " + std::to_string(kGenomeVectorVersion);
}

// A vector file (format "ahhs-genome-vector", version kGenomeVectorVersion): the shape (variant,
// hormones, rules, sensors, actuators), the values `x`, and the layout's `names`, `lower` and
// `upper`.
nlohmann::json VectorToJson(const Shape& shape, const std::vector<double>& x);
// Reads `shape` and `x` of a vector file (the layout's fields are not needed). Throws
// std::invalid_argument naming what is missing or wrong.
std::vector<double> VectorFromJson(const nlohmann::json& doc, Shape* shape);

}  // namespace ahhs::modules
