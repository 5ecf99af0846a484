// The wire <-> domain translators of the farm, the genome and the sim: whatever decodes is
// either refused by the translator with a message or becomes a domain value that translates
// back into a message that encodes (a worker must always be able to answer what it was sent).
// A genome piece that completes a genome alone yields that genome or a refusal.
#include <ahhs/eval_request_t.hpp>
#include <ahhs/eval_result_t.hpp>
#include <ahhs/genome_chunk_t.hpp>
#include <ahhs/genome_t.hpp>
#include <ahhs/genome_want_t.hpp>
#include <ahhs/sim_control_t.hpp>
#include <ahhs/worker_status_t.hpp>
#include <cstddef>
#include <cstdint>

#include "bus/codec.h"
#include "evolver/farm/farm_codec.h"
#include "modules/core/genome.h"
#include "modules/node/genome_codec.h"
#include "sim/node/sim_codec.h"
#include "tests/fuzz/fuzz_contract.h"

using namespace ahhs;

namespace {

void Request(const std::uint8_t* data, std::size_t size) {
  eval_request_t m;
  if (!bus::Decode(data, size, &m)) return;
  if (!evolver::PhysicsRefusal(m).empty()) return;  // a worker refuses it with that message
  evolver::FarmJob job;
  if (!evolver::JobFromMessage(m, &job).empty()) return;
  FUZZ_CONTRACT(!bus::Encode(evolver::RequestMessage(job)).empty(),
                "an accepted request does not encode again");
  evolver::FarmResult answer;
  answer.run = job.run;
  answer.job = job.job;
  answer.worker = job.worker;
  answer.message = "bad request: " + m.scenario;
  FUZZ_CONTRACT(!bus::Encode(evolver::ResultMessage(answer)).empty(),
                "the answer to an accepted request does not encode");
}

void Piece(const std::uint8_t* data, std::size_t size) {
  genome_chunk_t m;
  if (!bus::Decode(data, size, &m)) return;
  evolver::GenomePiece piece;
  if (!evolver::PieceFromMessage(m, &piece).empty()) return;
  FUZZ_CONTRACT(!bus::Encode(evolver::PieceMessage(piece)).empty(),
                "an accepted genome piece does not encode again");
  evolver::GenomeCache cache(1 << 20);
  cache.Add(piece);
  FUZZ_CONTRACT(cache.bytes() <= (1u << 20) + piece.data.size(),
                "the genome cache outgrows its bound");
  const auto* whole = cache.Find(piece.genome_hash);
  if (whole == nullptr) return;
  modules::Genome g;
  if (!evolver::DecodeGenome(*whole, piece.genome_hash, &g).empty()) return;
  FUZZ_CONTRACT(evolver::EncodeGenome(g).hash == piece.genome_hash,
                "an assembled genome is not the genome its hash names");
}

void Want(const std::uint8_t* data, std::size_t size) {
  genome_want_t m;
  if (!bus::Decode(data, size, &m)) return;
  FUZZ_CONTRACT(!bus::Encode(evolver::WantMessage(evolver::WantFromMessage(m))).empty(),
                "a decoded genome want does not encode again");
}

void Result(const std::uint8_t* data, std::size_t size) {
  eval_result_t m;
  if (!bus::Decode(data, size, &m)) return;
  FUZZ_CONTRACT(!bus::Encode(evolver::ResultMessage(evolver::OutcomeFromMessage(m))).empty(),
                "a decoded result does not encode again");
}

void Status(const std::uint8_t* data, std::size_t size) {
  worker_status_t m;
  if (!bus::Decode(data, size, &m)) return;
  FUZZ_CONTRACT(!bus::Encode(evolver::StatusMessage(evolver::StatusFromMessage(m))).empty(),
                "a decoded worker status does not encode again");
}

void Genome(const std::uint8_t* data, std::size_t size) {
  genome_t m;
  if (!bus::Decode(data, size, &m)) return;
  modules::Genome g;
  if (!modules::GenomeFromMessage(m, &g).empty()) return;
  const auto bytes = bus::Encode(modules::GenomeMessage(g, m.episode));
  FUZZ_CONTRACT(!bytes.empty(), "an accepted genome does not encode again");
  genome_t again;
  FUZZ_CONTRACT(bus::Decode(bytes.data(), bytes.size(), &again), "a genome message round trip");
  modules::Genome g2;
  FUZZ_CONTRACT(modules::GenomeFromMessage(again, &g2).empty(), "a sent genome is refused");
  FUZZ_CONTRACT(modules::GenomeHash(g2) == modules::GenomeHash(g), "a genome changes on the wire");
}

void Control(const std::uint8_t* data, std::size_t size) {
  sim_control_t m;
  if (!bus::Decode(data, size, &m)) return;
  sim::ScenarioConfig config;
  (void)sim::ConfigFromReset(m, &config);  // a message or a config; never a crash
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Request(data, size);
  Piece(data, size);
  Want(data, size);
  Result(data, size);
  Status(data, size);
  Genome(data, size);
  Control(data, size);
  return 0;
}
