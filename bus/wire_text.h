// Text on the wire. Every string field of every message is text: valid UTF-8, no NUL byte, at
// most kMaxWireText bytes. Decode (bus/codec.h) rejects a message whose strings are not, so no
// node ever sees one; Encode refuses to build one, so a send of such a message fails (and is
// counted and logged by PublishTyped). Senders pass free text (error messages) through
// ToWireText, which always gives valid text.
#pragma once

#include <ahhs/eval_request_t.hpp>
#include <ahhs/eval_result_t.hpp>
#include <ahhs/fitness_t.hpp>
#include <ahhs/genome_want_t.hpp>
#include <ahhs/module_status_t.hpp>
#include <ahhs/sim_control_t.hpp>
#include <ahhs/worker_status_t.hpp>
#include <array>
#include <cstddef>
#include <string>
#include <string_view>

namespace ahhs::bus {

inline constexpr std::size_t kMaxWireText = 1024;  // bytes

// Whether `text` is valid UTF-8 without NUL and at most kMaxWireText bytes long.
bool IsWireText(std::string_view text);

// `text` made wire text: NUL bytes and invalid UTF-8 sequences become U+FFFD, and text longer
// than kMaxWireText is cut at a character boundary and ends in "...".
std::string ToWireText(std::string_view text);

// The string fields of a message, for the checks above. A type without strings has none; a new
// string field in a type must be listed here (tests/bus/codec_test.cc compares these lists with
// lcmtypes/*.lcm).
template <class Msg>
std::array<const std::string*, 0> TextFields(const Msg&) {
  return {};
}
inline std::array<const std::string*, 4> TextFields(const eval_request_t& m) {
  return {&m.run, &m.worker, &m.scenario, &m.physics};
}
inline std::array<const std::string*, 3> TextFields(const eval_result_t& m) {
  return {&m.run, &m.worker, &m.message};
}
inline std::array<const std::string*, 1> TextFields(const fitness_t& m) { return {&m.message}; }
inline std::array<const std::string*, 2> TextFields(const genome_want_t& m) {
  return {&m.run, &m.worker};
}
inline std::array<const std::string*, 1> TextFields(const module_status_t& m) {
  return {&m.message};
}
inline std::array<const std::string*, 2> TextFields(const sim_control_t& m) {
  return {&m.scenario, &m.physics};
}
inline std::array<const std::string*, 3> TextFields(const worker_status_t& m) {
  return {&m.worker, &m.host, &m.run};
}

template <class Msg>
bool HasWireText(const Msg& msg) {
  for (const std::string* s : TextFields(msg))
    if (!IsWireText(*s)) return false;
  return true;
}

}  // namespace ahhs::bus
