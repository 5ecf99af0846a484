// Reads an LCM log file (written by lcm-logger, ahhs-logger, ahhs-launch --log, ahhs-replay --log)
// strictly, event by event. LCM's own reader (lcm_eventlog_read_next_event) skips garbage by
// searching for the next sync word and reports a cut-short event as the end of the file, so a
// damaged log would look like a shorter good one; this reader says what is wrong and where.
// Format (big-endian): u32 sync 0xEDA1DA01, i64 event number, i64 timestamp (us), i32 channel
// length, i32 data length, channel bytes, data bytes.
#pragma once

#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace ahhs::bus {

// "PATH: what is wrong at which byte", one line.
class LogFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct LogEvent {
  std::int64_t number = 0;
  std::int64_t utime = 0;
  std::string channel;
  std::vector<std::uint8_t> data;
};

inline constexpr std::uint32_t kLogSyncWord = 0xEDA1DA01;
inline constexpr std::int32_t kLogMaxChannel = 256;            // LCM allows 63; lenient
inline constexpr std::int32_t kLogMaxData = 64 * 1024 * 1024;  // far above any of our messages

// Parses the event at `*offset` of `bytes`: true and `*offset` past it, or false at the end.
// Throws LogFileError (prefixed `name`) for a missing sync word, a bad header or a cut-short event.
bool ParseLogEvent(const std::string& name, const std::uint8_t* bytes, std::size_t size,
                   std::size_t* offset, LogEvent* event);

class LogReader {
 public:
  // Throws LogFileError when the file cannot be opened, is empty or does not start like a log.
  explicit LogReader(const std::string& path);
  // The next event: true, or false at a clean end of file. Throws LogFileError.
  bool Next(LogEvent* event);
  std::uint64_t events_read() const { return events_; }

 private:
  std::string path_;
  std::ifstream in_;
  std::uint64_t offset_ = 0;
  std::uint64_t events_ = 0;
};

}  // namespace ahhs::bus
