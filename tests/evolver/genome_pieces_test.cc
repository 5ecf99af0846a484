// Genomes by reference: SplitGenome and the workers' GenomeCache (evolver/farm/genome_pieces.h).
#include "evolver/farm/genome_pieces.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <numeric>

using namespace ahhs::evolver;

namespace {
std::vector<std::uint8_t> Bytes(std::size_t n, std::uint8_t first = 0) {
  std::vector<std::uint8_t> b(n);
  std::iota(b.begin(), b.end(), first);
  return b;
}
}  // namespace

TEST_CASE("a genome splits into pieces of at most 1200 bytes that concatenate to it") {
  const auto bytes = Bytes(17000);
  const auto pieces = SplitGenome(42, bytes);
  REQUIRE(pieces.size() == 15);  // ceil(17000 / 1200)
  std::vector<std::uint8_t> joined;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    CHECK(pieces[k].genome_hash == 42);
    CHECK(pieces[k].genome_bytes == 17000);
    CHECK(pieces[k].index == static_cast<int>(k));
    CHECK(pieces[k].count == 15);
    CHECK(pieces[k].data.size() <= 1200);
    CHECK(*CheckPiece(pieces[k]) == '\0');
    joined.insert(joined.end(), pieces[k].data.begin(), pieces[k].data.end());
  }
  CHECK(pieces.back().data.size() == 17000 - 14 * 1200);
  CHECK(joined == bytes);
  CHECK(SplitGenome(1, Bytes(1200)).size() == 1);
  CHECK(SplitGenome(1, Bytes(1201)).size() == 2);
  CHECK(SplitGenome(1, {}).size() == 1);
}

TEST_CASE("the cache assembles a genome from pieces in any order, duplicates ignored") {
  const auto bytes = Bytes(5000, 7);
  auto pieces = SplitGenome(9, bytes);
  std::reverse(pieces.begin(), pieces.end());
  GenomeCache cache;
  CHECK(cache.Missing(9, 5) == std::vector<int>{0, 1, 2, 3, 4});
  for (std::size_t k = 0; k + 1 < pieces.size(); ++k) {
    CHECK_FALSE(cache.Add(pieces[k]));
    CHECK_FALSE(cache.Add(pieces[k]));  // a repeat changes nothing
    CHECK(cache.Find(9) == nullptr);
  }
  CHECK(cache.Missing(9, 5) == std::vector<int>{0});
  CHECK(cache.Add(pieces.back()));
  REQUIRE(cache.Find(9) != nullptr);
  CHECK(*cache.Find(9) == bytes);
  CHECK(cache.Missing(9, 5).empty());
  CHECK_FALSE(cache.Add(pieces[0]));  // complete: nothing more to take
  CHECK(cache.bytes() == 5000);
}

TEST_CASE("a piece that contradicts the pieces held starts its genome over") {
  GenomeCache cache;
  const auto a = SplitGenome(9, Bytes(3000));  // 3 pieces
  const auto b = SplitGenome(9, Bytes(2000));  // 2 pieces: another count and size
  cache.Add(a[0]);
  cache.Add(a[1]);
  CHECK_FALSE(cache.Add(b[0]));
  CHECK(cache.Missing(9, 2) == std::vector<int>{1});
  CHECK(cache.Add(b[1]));
  CHECK(*cache.Find(9) == Bytes(2000));
}

TEST_CASE("pieces whose sizes do not add up to the genome's are dropped when complete") {
  GenomeCache cache;
  auto pieces = SplitGenome(5, Bytes(2400));
  pieces[1].data.pop_back();  // 2399 bytes in all
  CHECK_FALSE(cache.Add(pieces[0]));
  CHECK_FALSE(cache.Add(pieces[1]));
  CHECK(cache.Find(5) == nullptr);
  CHECK(cache.genomes() == 0);
  CHECK(cache.bytes() == 0);
}

TEST_CASE("malformed pieces are refused") {
  GenomePiece p;
  p.genome_hash = 1;
  p.genome_bytes = 10;
  p.count = 1;
  p.data = Bytes(10);
  CHECK(*CheckPiece(p) == '\0');
  auto bad = p;
  bad.index = 1;
  CHECK(*CheckPiece(bad) != '\0');
  bad = p;
  bad.count = 11;  // more pieces than bytes
  CHECK(*CheckPiece(bad) != '\0');
  bad = p;
  bad.genome_bytes = -1;
  CHECK(*CheckPiece(bad) != '\0');
  bad = p;
  bad.genome_bytes = kMaxGenomeBytes + 1;
  CHECK(*CheckPiece(bad) != '\0');
  bad = p;
  bad.data = Bytes(11);
  CHECK(*CheckPiece(bad) != '\0');
  GenomeCache cache;
  CHECK_FALSE(cache.Add(bad));
  CHECK(cache.genomes() == 0);
}

TEST_CASE("the cache keeps within its bound by forgetting the oldest genomes") {
  GenomeCache cache(10000);
  for (std::uint64_t h = 1; h <= 10; ++h)
    for (const auto& p : SplitGenome(h, Bytes(3000))) cache.Add(p);
  CHECK(cache.bytes() <= 10000);
  CHECK(cache.genomes() == 3);
  CHECK(cache.Find(7) == nullptr);
  CHECK(cache.Find(8) != nullptr);
  CHECK(cache.Find(10) != nullptr);
  cache.Drop(10);
  CHECK(cache.Find(10) == nullptr);
  CHECK(cache.bytes() == 6000);
}
