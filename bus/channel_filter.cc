#include "bus/channel_filter.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace ahhs::bus {

namespace {

bool IsLiteral(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '/' ||
         c == '_' || c == '-' || c == ':' || c == ' ';
}

constexpr std::uint32_t kShortMagic = 0x4c433032;  // "LC02", big-endian on the wire
constexpr unsigned kChannelOffset = 8;             // after magic and sequence number
constexpr std::uint32_t kAccept = 0xffffffffu;     // keep the whole datagram
constexpr std::uint32_t kDrop = 0;
constexpr std::size_t kMaxInstructions = 4096;  // BPF_MAXINSNS
constexpr std::size_t kMaxJump = 255;           // conditional jumps are 8-bit

sock_filter Stmt(std::uint16_t code, std::uint32_t k) { return {code, 0, 0, k}; }
sock_filter Jump(std::uint16_t code, std::uint32_t k, std::uint8_t jt, std::uint8_t jf) {
  return {code, jt, jf, k};
}

// The compare instructions of one prefix: load 4, 2 or 1 bytes at a time (big-endian, as BPF
// loads them) and jump to the block's end on the first difference. `fail_to_end` is filled in
// once the block's length is known.
std::vector<sock_filter> PrefixBlock(const std::string& prefix, unsigned payload_offset) {
  std::vector<sock_filter> block;
  std::size_t i = 0;
  while (i < prefix.size()) {
    const std::size_t left = prefix.size() - i;
    const std::size_t width = left >= 4 ? 4 : (left >= 2 ? 2 : 1);
    std::uint32_t value = 0;
    for (std::size_t b = 0; b < width; ++b)
      value = (value << 8) | static_cast<std::uint8_t>(prefix[i + b]);
    const std::uint16_t size = width == 4 ? BPF_W : (width == 2 ? BPF_H : BPF_B);
    block.push_back(Stmt(BPF_LD | size | BPF_ABS,
                         static_cast<std::uint32_t>(payload_offset + kChannelOffset + i)));
    block.push_back(Jump(BPF_JMP | BPF_JEQ | BPF_K, value, 0, 0));
    i += width;
  }
  block.push_back(Stmt(BPF_RET | BPF_K, kAccept));
  // Every failed compare jumps past the block's accept, to the next block.
  for (std::size_t k = 0; k < block.size(); ++k) {
    if (block[k].code == (BPF_JMP | BPF_JEQ | BPF_K))
      block[k].jf = static_cast<std::uint8_t>(std::min(block.size() - k - 1, kMaxJump));
  }
  return block;
}

}  // namespace

std::string ChannelPrefix(const std::string& regex) {
  std::size_t n = 0;
  while (n < regex.size() && IsLiteral(regex[n])) ++n;
  if (n == regex.size()) return regex + std::string(1, '\0');  // an exact channel name
  const char special = regex[n];
  if (special == '|') return "";  // an alternation: the prefix says nothing
  if ((special == '?' || special == '*' || special == '{' || special == '+') && n > 0) --n;
  // Any later '|' at the top level would also make the prefix meaningless.
  if (regex.find('|', n) != std::string::npos) return "";
  return regex.substr(0, n);
}

std::vector<sock_filter> BuildChannelFilter(const std::vector<std::string>& prefixes,
                                            unsigned payload_offset) {
  std::vector<std::string> sorted = prefixes;
  for (const auto& p : sorted) {
    if (p.empty()) return {};
  }
  // Shortest first: a load past a short datagram's end stops the program (and drops the
  // datagram), which is right only when every later prefix is at least as long.
  std::sort(sorted.begin(), sorted.end(), [](const std::string& a, const std::string& b) {
    return a.size() != b.size() ? a.size() < b.size() : a < b;
  });
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());

  std::vector<sock_filter> program;
  program.push_back(Stmt(BPF_LD | BPF_W | BPF_ABS, payload_offset));  // the magic
  program.push_back(Jump(BPF_JMP | BPF_JEQ | BPF_K, kShortMagic, 1, 0));
  program.push_back(Stmt(BPF_RET | BPF_K, kAccept));  // not a short message: let LCM decide
  for (const auto& prefix : sorted) {
    const auto block = PrefixBlock(prefix, payload_offset);
    if (block.size() > kMaxJump) return {};
    program.insert(program.end(), block.begin(), block.end());
  }
  program.push_back(Stmt(BPF_RET | BPF_K, kDrop));
  if (program.size() > kMaxInstructions) return {};
  return program;
}

}  // namespace ahhs::bus
