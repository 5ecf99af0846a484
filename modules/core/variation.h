// Random initialisation, mutation and crossover of genomes (spec: ahhs-model.md, "Initialisation"
// and "Variation"). Every draw comes from the Rng passed in; the same seed gives the same genome.
#pragma once

#include <utility>

#include "modules/core/genome.h"
#include "modules/core/random.h"

namespace ahhs::modules {

struct MutationParams {
  double gene_rate = 0.15;  // probability that one gene (a rule or a hormone) mutates
  double max_change = 0.1;  // m: largest absolute change of a real field
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
