// Pure encode/decode of LCM message types (any lcm-gen C++ type), no transport.
// Decode never throws and never crashes on hostile bytes: a wrong fingerprint, a truncated or
// garbage buffer, or absurd array lengths all return false.
#pragma once

#include <cstddef>
#include <cstdint>
#include <exception>
#include <limits>
#include <vector>

namespace ahhs::bus {

// Encodes `msg` (fingerprint + payload). Precondition: every array's length field equals the
// size of its vector, as lcm-gen's encoder trusts it. Our codec functions keep this invariant.
template <class Msg>
std::vector<std::uint8_t> Encode(const Msg& msg) {
  const int size = msg.getEncodedSize();
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
  if (msg.encode(bytes.data(), 0, size) != size) bytes.clear();
  return bytes;
}

// Decodes `size` bytes into *out. Returns false (and leaves *out unspecified) when the bytes
// are not exactly one valid message of type Msg.
template <class Msg>
bool Decode(const void* data, std::size_t size, Msg* out) noexcept {
  if (data == nullptr || size < 8 ||
      size > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    return false;
  try {
    const int used = out->decode(data, 0, static_cast<int>(size));
    return used == static_cast<int>(size);
  } catch (...) {  // negative array lengths make std::vector/std::string throw
    return false;
  }
}

}  // namespace ahhs::bus
