// Random initialisation, mutation and crossover of genomes (docs/model.md, "Initialisation"
// and "Variation"). Every draw comes from the Rng passed in; the same seed gives the same genome.
#pragma once

#include <string>
#include <utility>

#include "modules/core/genome.h"
#include "modules/core/random.h"

namespace ahhs::modules {

// Which step each field of a mutated gene takes (docs/model.md, "Variation").
// - paper: the paper's operator, "a maximal, absolute change of range 0.1" for every real field
//   of both variants: every real field, AHHS2 floating indices included, moves by +-U(0, m).
// - fine-doses: the operator of this project's first briefing, kept to compare against: AHHS2
//   lambda and kappa move by +-U(0, m / 50) and AHHS2 floating indices by +-U(0, 1); AHHS1 and
//   hormones as in paper. Runs stored before profiles existed used it.
enum class MutationProfile { kPaper, kFineDoses };

const char* MutationProfileName(MutationProfile profile);  // "paper" / "fine-doses"
// Throws std::invalid_argument naming the choices.
MutationProfile ParseMutationProfile(const std::string& name);

struct MutationParams {
  double gene_rate = 0.15;  // probability that one gene (a rule or a hormone) mutates
  double max_change = 0.1;  // m: largest absolute change of a real field
  MutationProfile profile = MutationProfile::kPaper;
};

// A random genome of the given shape. Throws std::invalid_argument for an impossible shape.
Genome RandomGenome(const Shape& shape, Rng& rng);

// Mutates each gene independently with probability params.gene_rate; a mutated gene gets exactly
// one field changed. Returns the number of mutated genes. Keeps every invariant of CheckGenome.
int Mutate(Genome* genome, const MutationParams& params, Rng& rng);

// Mutates exactly one gene, chosen uniformly (used for the paper's mutation-neighbourhood study).
void MutateOneGene(Genome* genome, const MutationParams& params, Rng& rng);

// Two-point crossover, done separately on the aligned hormone list and the aligned rule list:
// cut points c1 <= c2 uniform in [0, n]; the first child is a[0,c1) b[c1,c2) a[c2,n), the
// second its complement. Throws std::invalid_argument when the shapes differ.
std::pair<Genome, Genome> Crossover(const Genome& a, const Genome& b, Rng& rng);

}  // namespace ahhs::modules
