// Farm structs <-> LCM messages (eval_request_t, genome_chunk_t, genome_want_t, eval_result_t,
// worker_status_t), and a genome <-> the bytes its pieces carry. Pure functions.
#pragma once

#include <ahhs/eval_request_t.hpp>
#include <ahhs/eval_result_t.hpp>
#include <ahhs/genome_chunk_t.hpp>
#include <ahhs/genome_want_t.hpp>
#include <ahhs/worker_status_t.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "evolver/farm/farm_protocol.h"
#include "evolver/farm/genome_pieces.h"

namespace ahhs::evolver {

// A genome as EVAL/GENOME carries it: its hash and the LCM encoding of its genome_t.
struct EncodedGenome {
  std::uint64_t hash = 0;
  std::vector<std::uint8_t> bytes;
};
EncodedGenome EncodeGenome(const modules::Genome& genome);
// Decodes an assembled encoding and checks that it is the genome `hash` names. Returns "" or
// why it is unusable.
std::string DecodeGenome(const std::vector<std::uint8_t>& bytes, std::uint64_t hash,
                         modules::Genome* out);

// The request names the genome by job.genome_hash/genome_bytes/genome_chunks; job.genome is
// not sent.
eval_request_t RequestMessage(const FarmJob& job);
// Decodes and validates (scenario, genome reference); job.genome stays empty. Returns "" or why
// the request is unusable. The protocol version is copied, not checked: the worker answers a
// foreign version itself.
std::string JobFromMessage(const eval_request_t& msg, FarmJob* out);

// Why a worker of this build cannot evaluate the request at all: it names a physics version this
// build does not simulate (sim::CheckPhysics). "" otherwise, also for a request that is bad for
// another reason (JobFromMessage says why).
std::string PhysicsRefusal(const eval_request_t& msg);

genome_chunk_t PieceMessage(const GenomePiece& piece);
// Returns "" or why the piece is unusable (CheckPiece).
std::string PieceFromMessage(const genome_chunk_t& msg, GenomePiece* out);

genome_want_t WantMessage(const GenomeWant& want);
GenomeWant WantFromMessage(const genome_want_t& msg);

eval_result_t ResultMessage(const FarmResult& outcome);
FarmResult OutcomeFromMessage(const eval_result_t& msg);

worker_status_t StatusMessage(const WorkerStatus& status);
WorkerStatus StatusFromMessage(const worker_status_t& msg);

}  // namespace ahhs::evolver
