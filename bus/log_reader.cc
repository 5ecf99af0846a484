#include "bus/log_reader.h"

#include <cerrno>
#include <cstring>

namespace ahhs::bus {

namespace {

constexpr std::size_t kHeader = 4 + 8 + 8 + 4 + 4;

std::uint64_t BigEndian(const std::uint8_t* p, int n) {
  std::uint64_t v = 0;
  for (int i = 0; i < n; ++i) v = (v << 8) | p[i];
  return v;
}

struct Header {
  std::int64_t number, utime;
  std::int32_t channel_len, data_len;
};

// Checks and decodes a header; `at` is its byte offset in the file.
void CheckSync(const std::string& name, const std::uint8_t* h, std::uint64_t at,
               std::uint64_t index) {
  if (BigEndian(h, 4) != kLogSyncWord) {
    throw LogFileError(name + (index == 0 ? ": not an LCM log (no LCM sync word at byte 0)"
                                          : ": garbage at byte " + std::to_string(at) +
                                                " (no LCM sync word after event " +
                                                std::to_string(index) + "; the log is damaged)"));
  }
}

Header DecodeHeader(const std::string& name, const std::uint8_t* h, std::uint64_t at,
                    std::uint64_t index) {
  CheckSync(name, h, at, index);
  Header r;
  r.number = static_cast<std::int64_t>(BigEndian(h + 4, 8));
  r.utime = static_cast<std::int64_t>(BigEndian(h + 12, 8));
  r.channel_len = static_cast<std::int32_t>(static_cast<std::uint32_t>(BigEndian(h + 20, 4)));
  r.data_len = static_cast<std::int32_t>(static_cast<std::uint32_t>(BigEndian(h + 24, 4)));
  if (r.channel_len <= 0 || r.channel_len > kLogMaxChannel || r.data_len < 0 ||
      r.data_len > kLogMaxData) {
    throw LogFileError(name + ": corrupt event header at byte " + std::to_string(at) +
                       " (channel length " + std::to_string(r.channel_len) + ", data length " +
                       std::to_string(r.data_len) + ")");
  }
  return r;
}

LogFileError Truncated(const std::string& name, std::uint64_t at, std::uint64_t index) {
  return LogFileError(name + ": truncated at byte " + std::to_string(at) + " (event " +
                      std::to_string(index + 1) + " is cut short)");
}

}  // namespace

bool ParseLogEvent(const std::string& name, const std::uint8_t* bytes, std::size_t size,
                   std::size_t* offset, LogEvent* event) {
  const std::size_t at = *offset;
  if (at >= size) return false;
  // Index for messages: events before this one are not counted here; say "an event".
  if (size - at < kHeader) throw Truncated(name, at, 0);
  const Header h = DecodeHeader(name, bytes + at, at, at == 0 ? 0 : 1);
  const std::size_t need =
      kHeader + static_cast<std::size_t>(h.channel_len) + static_cast<std::size_t>(h.data_len);
  if (size - at < need) throw Truncated(name, at, 0);
  event->number = h.number;
  event->utime = h.utime;
  const std::uint8_t* p = bytes + at + kHeader;
  event->channel.assign(reinterpret_cast<const char*>(p), static_cast<std::size_t>(h.channel_len));
  p += h.channel_len;
  event->data.assign(p, p + h.data_len);
  *offset = at + need;
  return true;
}

LogReader::LogReader(const std::string& path) : path_(path), in_(path, std::ios::binary) {
  if (!in_) throw LogFileError(path + ": cannot open (" + std::strerror(errno) + ")");
  if (in_.peek() == std::ifstream::traits_type::eof())
    throw LogFileError(path + ": empty file, not an LCM log");
}

bool LogReader::Next(LogEvent* event) {
  std::uint8_t h[kHeader];
  in_.read(reinterpret_cast<char*>(h), kHeader);
  const auto got = static_cast<std::size_t>(in_.gcount());
  if (got == 0) {
    if (events_ == 0) throw LogFileError(path_ + ": empty file, not an LCM log");
    return false;
  }
  if (got < 4) throw Truncated(path_, offset_, events_);
  if (got < kHeader) {
    CheckSync(path_, h, offset_, events_);  // garbage is reported as such, not as truncation
    throw Truncated(path_, offset_, events_);
  }
  const Header hd = DecodeHeader(path_, h, offset_, events_);
  event->number = hd.number;
  event->utime = hd.utime;
  event->channel.resize(static_cast<std::size_t>(hd.channel_len));
  event->data.resize(static_cast<std::size_t>(hd.data_len));
  in_.read(event->channel.data(), hd.channel_len);
  if (in_.gcount() != hd.channel_len) throw Truncated(path_, offset_, events_);
  in_.read(reinterpret_cast<char*>(event->data.data()), hd.data_len);
  if (in_.gcount() != hd.data_len) throw Truncated(path_, offset_, events_);
  offset_ += kHeader + static_cast<std::uint64_t>(hd.channel_len) +
             static_cast<std::uint64_t>(hd.data_len);
  ++events_;
  return true;
}

}  // namespace ahhs::bus
