// Golden vectors of the hormone controller (docs/hardware.md, "Golden vectors"): genomes, the
// inputs of a run of ticks and the outputs modules/core computes from them, to the last bit, in a
// line format any language reads, so that a port checks itself offline against the exact
// evaluation order of docs/model.md. Pure: no LCM, no files.
//
// Format (version 1), one record per line, tokens separated by single spaces, every real number
// in "%.17g" (which reads back to the same double), '#' lines are comments:
//   ahhs-model-vectors 1
//   case NAME
//   genome VARIANT NH NS NA NR FIELDS_PER_RULE      VARIANT: 1 = AHHS1, 2 = AHHS2 (genome_t)
//   alpha NH values / mu NH values / diffusion NH values
//   rules NR * FIELDS_PER_RULE values               genome_t.rule_values, rule by rule
//   tick NUM_NEIGHBOURS                             a tick, on the state the previous one left
//   received NH values                              one packet, zero or more lines, in order
//   sensors NS tokens                               a value, or '-' for an absent sensor
//   actuators NA tokens                             1 present, 0 absent
//   expect_hormones NH values / expect_actuators NA / expect_outflow NH
//   end                                             of the case
// Every case starts from a compartment at rest (every concentration 0).
#pragma once

#include <string>

namespace ahhs::conformance {

inline constexpr int kModelVectorsVersion = 1;

// The vectors as modules/core computes them (a deterministic set of cases: random AHHS1 and AHHS2
// genomes of both scenarios' shapes and hand-made edge cases).
std::string WriteModelVectors();

// Reads `text` and runs every case through modules/core. Returns "" when every output matches to
// the bit, else one line naming the case, tick and value ("case ahhs2-gait tick 7:
// expect_hormones[3] is 0.1234..., modules/core gives 0.1234..."), or the line that does not
// parse.
std::string CheckModelVectors(const std::string& text);

}  // namespace ahhs::conformance
