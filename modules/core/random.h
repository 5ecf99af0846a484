// The one source of randomness of the core: a seeded 64-bit Mersenne Twister with our own
// uniform mappings, so a seed gives the same draws with any standard library (the
// std::*_distribution classes are implementation-defined; std::mt19937_64's output is not).
#pragma once

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>

namespace ahhs::modules {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}

  // Uniform in [0, 1), 53 random bits.
  double Uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  // Uniform in [lo, hi).
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  // Uniform integer in [0, n), n >= 1, without modulo bias.
  int UniformInt(int n) {
    const std::uint64_t range = static_cast<std::uint64_t>(n);
    const std::uint64_t limit = UINT64_MAX - UINT64_MAX % range;
    std::uint64_t draw;
    do draw = engine_();
    while (draw >= limit);
    return static_cast<int>(draw % range);
  }
  bool Bernoulli(double p) { return Uniform() < p; }
  // +1 or -1 with equal probability.
  double Sign() { return (engine_() >> 63) != 0 ? 1.0 : -1.0; }
  std::uint64_t Next() { return engine_(); }

 private:
  std::mt19937_64 engine_;
};

// Derives an independent seed from a parent seed and a stream of ids (SplitMix64 finaliser),
// e.g. DeriveSeed(run_seed, {generation, individual}).
inline std::uint64_t DeriveSeed(std::uint64_t seed, std::initializer_list<std::uint64_t> ids) {
  auto mix = [](std::uint64_t z) {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  };
  std::uint64_t h = mix(seed);
  for (std::uint64_t id : ids) h = mix(h ^ mix(id));
  return h;
}

// Seeds are unsigned 64-bit numbers end to end. For a command-line check: "" if `text` is a
// whole number from 0 to 2^64-1 written in decimal digits, else a message (no sign, no clamping:
// "-1" or "18446744073709551616" are refused, not wrapped or clamped).
inline std::string SeedTextError(const std::string& text) {
  static const std::string kMax = "18446744073709551615";
  const bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
  const std::string trimmed =
      digits ? text.substr(std::min(text.find_first_not_of('0'), text.size() - 1)) : text;
  if (digits &&
      (trimmed.size() < kMax.size() || (trimmed.size() == kMax.size() && trimmed <= kMax)))
    return "";
  return "a seed is a whole number from 0 to 18446744073709551615, not '" + text + "'";
}

}  // namespace ahhs::modules
