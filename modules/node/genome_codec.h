// Genome <-> ahhs.genome_t (flat arrays, docs/protocol.md). Pure functions.
#pragma once

#include <ahhs/genome_t.hpp>
#include <string>

#include "modules/core/genome.h"

namespace ahhs::modules {

inline constexpr int kAhhs2FieldsPerRule =
    13;  // w_idle, w_S, w_L, w_N, w_A, zeta, eta, kappa, lambda, s, i, o, a
inline constexpr int kAhhs1FieldsPerRule = 7;  // type, in, out, tau, dir, lambda, kappa

genome_t GenomeMessage(const Genome& genome, std::int64_t episode);

// Decodes and validates (CheckGenome, and the hash it carries). Returns "" or why it is refused.
std::string GenomeFromMessage(const genome_t& msg, Genome* out);

}  // namespace ahhs::modules
