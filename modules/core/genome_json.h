// Genome files: versioned JSON (docs/genome.md). Loading validates everything and either yields
// a complete, valid genome or throws GenomeFileError naming the offending field.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "modules/core/genome.h"

namespace ahhs::modules {

inline constexpr const char* kGenomeFormat = "ahhs-genome";
inline constexpr int kGenomeFormatVersion = 1;
inline std::string GenomeFormatLine() {  // for --version
  return std::string("genome file ") + kGenomeFormat + " " + std::to_string(kGenomeFormatVersion);
}

class GenomeFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Canonical JSON of a genome. Doubles are written with 17 significant digits, so a genome
// survives a save/load round trip bit for bit. `meta` (an object or null) is stored verbatim.
nlohmann::json GenomeToJson(const Genome& genome, const nlohmann::json& meta = nullptr);

// Throws GenomeFileError("<field>: <problem>") for any structural or range error.
Genome GenomeFromJson(const nlohmann::json& doc);

// Parses text; `source` names it in error messages (e.g. the file name).
Genome ParseGenome(const std::string& text, const std::string& source);

// Reads and validates a genome file. Throws GenomeFileError with the path in the message.
Genome LoadGenomeFile(const std::string& path);
// The same, and the file's "meta" object into *meta (null when the file has none).
Genome LoadGenomeFile(const std::string& path, nlohmann::json* meta);

// The evaluation seed a genome file stores (meta.eval_seed, written by ahhs-evolve for best.json
// and best/gen-NNNN.json), if it has one: an unsigned 64-bit integer.
std::optional<std::uint64_t> StoredEvalSeed(const nlohmann::json& meta);

// Writes a genome file atomically (temporary file + rename): never half a file.
void SaveGenomeFile(const std::string& path, const Genome& genome,
                    const nlohmann::json& meta = nullptr);

}  // namespace ahhs::modules
