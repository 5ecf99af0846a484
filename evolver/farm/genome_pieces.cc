#include "evolver/farm/genome_pieces.h"

#include <algorithm>

namespace ahhs::evolver {

std::vector<GenomePiece> SplitGenome(std::uint64_t hash, const std::vector<std::uint8_t>& bytes,
                                     int piece_bytes) {
  const std::size_t step = static_cast<std::size_t>(std::clamp(piece_bytes, 1, kMaxPieceBytes));
  const std::size_t count = std::max<std::size_t>(1, (bytes.size() + step - 1) / step);
  std::vector<GenomePiece> pieces(count);
  for (std::size_t k = 0; k < count; ++k) {
    GenomePiece& p = pieces[k];
    p.genome_hash = hash;
    p.genome_bytes = static_cast<int>(bytes.size());
    p.index = static_cast<int>(k);
    p.count = static_cast<int>(count);
    const std::size_t begin = std::min(bytes.size(), k * step);
    const std::size_t end = std::min(bytes.size(), begin + step);
    p.data.assign(bytes.begin() + static_cast<std::ptrdiff_t>(begin),
                  bytes.begin() + static_cast<std::ptrdiff_t>(end));
  }
  return pieces;
}

const char* CheckPiece(const GenomePiece& p) {
  if (p.genome_bytes < 0 || p.genome_bytes > kMaxGenomeBytes) return "genome size out of range";
  if (p.count < 1 || p.count > std::max(1, p.genome_bytes)) return "piece count out of range";
  if (p.index < 0 || p.index >= p.count) return "piece index out of range";
  if (p.data.size() > static_cast<std::size_t>(p.genome_bytes)) return "piece larger than genome";
  if (p.data.size() > static_cast<std::size_t>(kMaxPieceBytes)) return "piece too large";
  return "";
}

bool GenomeCache::Add(const GenomePiece& p) {
  if (*CheckPiece(p) != '\0') return false;
  auto it = entries_.find(p.genome_hash);
  if (it != entries_.end()) {
    if (it->second.complete) return false;
    if (it->second.count != p.count || it->second.genome_bytes != p.genome_bytes)
      Drop(p.genome_hash);  // contradicts what we hold: start over with this piece
  }
  it = entries_.find(p.genome_hash);
  if (it == entries_.end()) {
    Entry e;
    e.genome_bytes = p.genome_bytes;
    e.count = p.count;
    e.pieces.resize(static_cast<std::size_t>(p.count));
    e.have.assign(static_cast<std::size_t>(p.count), false);
    it = entries_.emplace(p.genome_hash, std::move(e)).first;
    order_.push_back(p.genome_hash);
  }
  Entry& e = it->second;
  const auto index = static_cast<std::size_t>(p.index);
  if (e.have[index]) return false;
  e.have[index] = true;
  e.pieces[index] = p.data;
  ++e.held;
  bytes_ += p.data.size();
  if (e.held < e.count) {
    Evict();
    return false;
  }
  std::vector<std::uint8_t> whole;
  whole.reserve(static_cast<std::size_t>(e.genome_bytes));
  for (const auto& piece : e.pieces) whole.insert(whole.end(), piece.begin(), piece.end());
  if (whole.size() != static_cast<std::size_t>(e.genome_bytes)) {
    Drop(p.genome_hash);
    return false;
  }
  e.pieces.assign(1, std::move(whole));
  e.complete = true;
  Evict();
  return entries_.count(p.genome_hash) > 0;
}

const std::vector<std::uint8_t>* GenomeCache::Find(std::uint64_t hash) const {
  const auto it = entries_.find(hash);
  return it != entries_.end() && it->second.complete ? &it->second.pieces[0] : nullptr;
}

std::vector<int> GenomeCache::Missing(std::uint64_t hash, int count) const {
  std::vector<int> missing;
  const auto it = entries_.find(hash);
  if (it != entries_.end() && it->second.complete) return missing;
  const bool known = it != entries_.end() && it->second.count == count;
  for (int k = 0; k < count; ++k)
    if (!known || !it->second.have[static_cast<std::size_t>(k)]) missing.push_back(k);
  return missing;
}

void GenomeCache::Drop(std::uint64_t hash) {
  const auto it = entries_.find(hash);
  if (it == entries_.end()) return;
  for (const auto& piece : it->second.pieces) bytes_ -= piece.size();
  entries_.erase(it);
  order_.erase(std::find(order_.begin(), order_.end(), hash));
}

void GenomeCache::Evict() {
  while (bytes_ > max_bytes_ && order_.size() > 1) Drop(order_.front());
}

}  // namespace ahhs::evolver
