// The strict LCM log reader: a log written by LCM itself reads back event for event, and every
// kind of damage is an error that names the byte, never a shorter log.
#include "bus/log_reader.h"

#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using ahhs::bus::LogEvent;
using ahhs::bus::LogFileError;
using ahhs::bus::LogReader;
using Catch::Matchers::Contains;

namespace {

std::string Scratch(const std::string& name) {
  return (fs::temp_directory_path() / ("ahhs-log-reader-" + name)).string();
}

// Three events written by lcm::LogFile.
std::string WriteLcmLog(const std::string& name) {
  const std::string path = Scratch(name);
  lcm::LogFile log(path, "w");
  for (int i = 0; i < 3; ++i) {
    lcm::LogEvent e{};
    e.eventnum = i;
    e.timestamp = 1000 + i;
    e.channel = "AHHS/CH" + std::to_string(i);
    std::vector<std::uint8_t> data(static_cast<std::size_t>(10 + i), static_cast<std::uint8_t>(i));
    e.datalen = static_cast<std::int32_t>(data.size());
    e.data = data.data();
    log.writeEvent(&e);
  }
  return path;
}

std::vector<char> Bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void Put(const std::string& path, const std::vector<char>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string ReadAllError(const std::string& path) {
  try {
    LogReader r(path);
    LogEvent e;
    while (r.Next(&e)) {
    }
  } catch (const LogFileError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("a log written by LCM reads back event for event") {
  const std::string path = WriteLcmLog("good");
  LogReader r(path);
  LogEvent e;
  for (int i = 0; i < 3; ++i) {
    REQUIRE(r.Next(&e));
    CHECK(e.number == i);
    CHECK(e.utime == 1000 + i);
    CHECK(e.channel == "AHHS/CH" + std::to_string(i));
    CHECK(e.data == std::vector<std::uint8_t>(static_cast<std::size_t>(10 + i),
                                              static_cast<std::uint8_t>(i)));
  }
  CHECK_FALSE(r.Next(&e));
  CHECK(r.events_read() == 3);
  fs::remove(path);
}

TEST_CASE("a truncated log is an error naming the event, not a shorter log") {
  const std::string path = WriteLcmLog("truncated");
  auto bytes = Bytes(path);
  bytes.resize(bytes.size() - 5);
  Put(path, bytes);
  CHECK_THAT(ReadAllError(path), Contains("truncated at byte") && Contains("event 3 is cut short"));
  fs::remove(path);
}

TEST_CASE("garbage between events is an error naming its byte") {
  const std::string path = WriteLcmLog("garbage");
  auto bytes = Bytes(path);
  const std::size_t first = 4 + 8 + 8 + 4 + 4 + 8 + 10;         // header, "AHHS/CH0", 10 bytes
  bytes.insert(bytes.begin() + static_cast<long>(first), 'x');  // one stray byte after event 1
  Put(path, bytes);
  CHECK_THAT(ReadAllError(path), Contains("garbage at byte 46 (no LCM sync word after "
                                          "event 1"));
  fs::remove(path);
}

TEST_CASE("a file that is not a log, or is empty, is said to be so") {
  const std::string path = Scratch("text");
  Put(path, std::vector<char>{'h', 'e', 'l', 'l', 'o', ' ', 'w', 'o', 'r', 'l', 'd', '\n'});
  CHECK_THAT(ReadAllError(path), Contains("not an LCM log"));
  Put(path, {});
  CHECK_THAT(ReadAllError(path), Contains("empty file"));
  fs::remove(path);
  CHECK_THAT(ReadAllError(path), Contains("cannot open"));
}

TEST_CASE("an event header with an impossible length is corrupt, not a huge allocation") {
  const std::string path = WriteLcmLog("length");
  auto bytes = Bytes(path);
  bytes[24] = 0x7f;  // data length of event 1 becomes about 2 GB
  Put(path, bytes);
  CHECK_THAT(ReadAllError(path), Contains("corrupt event header at byte 0"));
  fs::remove(path);
}
