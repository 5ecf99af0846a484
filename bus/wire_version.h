// What a program's messages look like on the wire, as one line for --version: LCM fingerprints
// every type from its fields (a type of other fields is another type), and this folds the
// fingerprints of all of package ahhs's types into one. Two programs whose lines agree speak the
// same wire format; docs/reference.md.
#pragma once

#include <cstdint>
#include <string>

namespace ahhs::bus {

// The fingerprints of every type of package ahhs, folded in name order (FNV-1a over their bytes).
std::uint64_t WireFingerprint();

// "wire: LCM package ahhs, 16 types, fingerprint 0123456789abcdef".
std::string WireVersionLine();

}  // namespace ahhs::bus
