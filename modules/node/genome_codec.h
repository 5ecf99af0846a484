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

// Whether a hash a peer reports (module_status_t.genome_hash) is `expected`: the same 64 bits,
// or, for peers that hold 64-bit integers as doubles (Lua 5.2's LCM), the same double.
bool GenomeHashMatches(std::int64_t reported, std::uint64_t expected);

// Decodes and validates (CheckGenome, and the hash it carries). Returns "" or why it is refused.
std::string GenomeFromMessage(const genome_t& msg, Genome* out);

}  // namespace ahhs::modules
