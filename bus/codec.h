// Pure encode/decode of LCM message types (any lcm-gen C++ type), no transport.
// Decode never throws and never crashes on hostile bytes: a wrong fingerprint, a truncated or
// garbage buffer, absurd array lengths, or a string field that is not wire text (NUL, invalid
// UTF-8, too long: bus/wire_text.h) all return false. Encode refuses such strings alike, so
// whatever one peer can send, every peer can decode and send again.
#pragma once

#include <cstddef>
#include <cstdint>
#include <exception>
#include <limits>
#include <vector>

#include "bus/wire_text.h"

namespace ahhs::bus {

// Encodes `msg` (fingerprint + payload); empty when a string field is not wire text.
// Precondition: every array's length field equals the size of its vector, as lcm-gen's encoder
// trusts it. Our codec functions keep this invariant.
template <class Msg>
std::vector<std::uint8_t> Encode(const Msg& msg) {
  if (!HasWireText(msg)) return {};
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
    return used == static_cast<int>(size) && HasWireText(*out);
  } catch (...) {  // negative array lengths make std::vector/std::string throw
    return false;
  }
}

}  // namespace ahhs::bus
