#include "bus/wire_version.h"

#include <ahhs/eval_request_t.hpp>
#include <ahhs/eval_result_t.hpp>
#include <ahhs/fitness_t.hpp>
#include <ahhs/genome_chunk_t.hpp>
#include <ahhs/genome_t.hpp>
#include <ahhs/genome_want_t.hpp>
#include <ahhs/hinge_command_t.hpp>
#include <ahhs/hormone_packet_t.hpp>
#include <ahhs/module_sensors_t.hpp>
#include <ahhs/module_status_t.hpp>
#include <ahhs/module_trace_t.hpp>
#include <ahhs/sim_clock_t.hpp>
#include <ahhs/sim_control_t.hpp>
#include <ahhs/sim_state_t.hpp>
#include <ahhs/topology_t.hpp>
#include <ahhs/worker_status_t.hpp>
#include <cstdio>

namespace ahhs::bus {

namespace {
// Every type of package ahhs, in name order (a type added to lcmtypes/ is added here;
// tools:packages checks that --version counts as many types as lcmtypes/ has files).
const std::uint64_t kTypeHashes[] = {
    static_cast<std::uint64_t>(ahhs::eval_request_t::getHash()),
    static_cast<std::uint64_t>(ahhs::eval_result_t::getHash()),
    static_cast<std::uint64_t>(ahhs::fitness_t::getHash()),
    static_cast<std::uint64_t>(ahhs::genome_chunk_t::getHash()),
    static_cast<std::uint64_t>(ahhs::genome_t::getHash()),
    static_cast<std::uint64_t>(ahhs::genome_want_t::getHash()),
    static_cast<std::uint64_t>(ahhs::hinge_command_t::getHash()),
    static_cast<std::uint64_t>(ahhs::hormone_packet_t::getHash()),
    static_cast<std::uint64_t>(ahhs::module_sensors_t::getHash()),
    static_cast<std::uint64_t>(ahhs::module_status_t::getHash()),
    static_cast<std::uint64_t>(ahhs::module_trace_t::getHash()),
    static_cast<std::uint64_t>(ahhs::sim_clock_t::getHash()),
    static_cast<std::uint64_t>(ahhs::sim_control_t::getHash()),
    static_cast<std::uint64_t>(ahhs::sim_state_t::getHash()),
    static_cast<std::uint64_t>(ahhs::topology_t::getHash()),
    static_cast<std::uint64_t>(ahhs::worker_status_t::getHash()),
};
}  // namespace

std::uint64_t WireFingerprint() {
  std::uint64_t h = 14695981039346656037ULL;
  for (const std::uint64_t type_hash : kTypeHashes)
    for (int byte = 0; byte < 8; ++byte) {
      h ^= (type_hash >> (8 * byte)) & 0xffU;
      h *= 1099511628211ULL;
    }
  return h;
}

std::string WireVersionLine() {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(WireFingerprint()));
  return "wire: LCM package ahhs, " + std::to_string(sizeof kTypeHashes / sizeof kTypeHashes[0]) +
         " types, fingerprint " + hex;
}

}  // namespace ahhs::bus
