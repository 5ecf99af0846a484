// Genomes by reference on the evaluation farm (docs/protocol.md, "Evaluation farm"): the evolver
// cuts a genome's encoding into pieces small enough for one UDP datagram without IP fragments
// (EVAL/GENOME) and sends them once; a request names the genome by hash. Workers keep what they
// hear in a GenomeCache and ask for the pieces they miss (EVAL/WANT). Pure logic: no LCM.
//
// Rules:
// - Pieces are at most kGenomePieceBytes; a genome's pieces in index order are its encoding.
// - A piece that contradicts the pieces already held for its hash (count, total size) starts
//   that genome over; a genome whose pieces add up to another size is dropped when complete.
// - The cache holds at most `max_bytes` of genomes, complete or not; the oldest go first.
// - The hash is not checked here: the codec decodes the bytes and compares (Drop on mismatch).
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <vector>

namespace ahhs::evolver {

// 1200 bytes: what every IPv4 or IPv6 path carries in one datagram with room for LCM's header
// and the piece's own fields (the size QUIC assumes).
inline constexpr int kGenomePieceBytes = 1200;
inline constexpr int kMaxPieceBytes = 32767;  // genome_chunk_t.size is an int16_t
// The largest genome encoding a worker assembles (AHHS1-300 is about 17 kB).
inline constexpr int kMaxGenomeBytes = 4 << 20;

struct GenomePiece {
  std::uint64_t genome_hash = 0;
  int genome_bytes = 0;  // size of the whole encoding
  int index = 0;
  int count = 0;
  std::vector<std::uint8_t> data;
};

// The pieces of `bytes`, each at most `piece_bytes` (1 .. kMaxPieceBytes); one empty piece for
// an empty encoding.
std::vector<GenomePiece> SplitGenome(std::uint64_t hash, const std::vector<std::uint8_t>& bytes,
                                     int piece_bytes = kGenomePieceBytes);

// "" when a piece is well-formed on its own (sizes and index in range), else why not.
const char* CheckPiece(const GenomePiece& piece);

class GenomeCache {
 public:
  explicit GenomeCache(std::size_t max_bytes = 64u << 20) : max_bytes_(max_bytes) {}

  // Keeps a well-formed piece (see CheckPiece); returns true when it completed its genome.
  bool Add(const GenomePiece& piece);
  // The whole encoding of `hash`, or nullptr while pieces are missing.
  const std::vector<std::uint8_t>* Find(std::uint64_t hash) const;
  // The indexes of the pieces of `hash` not held yet, out of `count` (all when none is held).
  std::vector<int> Missing(std::uint64_t hash, int count) const;
  // Forgets `hash` (its bytes did not decode to it): it is assembled again from new pieces.
  void Drop(std::uint64_t hash);

  std::size_t bytes() const { return bytes_; }
  std::size_t genomes() const { return entries_.size(); }

 private:
  struct Entry {
    int genome_bytes = 0;
    int count = 0;
    int held = 0;
    std::vector<std::vector<std::uint8_t>> pieces;  // by index; complete: [0] is the whole
    std::vector<bool> have;
    bool complete = false;
  };
  void Evict();

  std::size_t max_bytes_;
  std::size_t bytes_ = 0;
  std::map<std::uint64_t, Entry> entries_;
  std::deque<std::uint64_t> order_;  // oldest first
};

}  // namespace ahhs::evolver
