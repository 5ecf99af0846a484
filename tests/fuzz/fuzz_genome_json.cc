// The genome file loader (modules/core/genome_json.h): any text gives a valid genome or a
// GenomeFileError naming the field (any other exception is a broken contract); a genome it
// accepts is saved and loaded again unchanged.
#include <cstddef>
#include <cstdint>
#include <string>

#include "modules/core/genome.h"
#include "modules/core/genome_json.h"
#include "tests/fuzz/fuzz_contract.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ahhs::modules;
  const std::string text(reinterpret_cast<const char*>(data), size);
  Genome genome;
  try {
    genome = ParseGenome(text, "fuzz.json");
  } catch (const GenomeFileError&) {
    return 0;
  }
  FUZZ_CONTRACT(CheckGenome(genome).empty(), "the loader accepted an invalid genome");
  Genome again;
  try {
    again = ParseGenome(GenomeToJson(genome).dump(), "again.json");
  } catch (const GenomeFileError&) {
    FUZZ_CONTRACT(false, "a genome the loader accepted is refused once written");
  }
  FUZZ_CONTRACT(GenomeHash(again) == GenomeHash(genome), "a genome changes through its file");
  return 0;
}
