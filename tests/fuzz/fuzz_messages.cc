// Every message type's decode: hostile bytes never crash, and bytes that decode are a message
// every peer can send again: it encodes, and those bytes decode to a message that encodes to
// the same bytes (bus/codec.h). The input is tried as each of the 16 types (the fingerprint
// picks at most one).
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
#include <cstddef>
#include <cstdint>

#include "bus/codec.h"
#include "bus/typed.h"
#include "tests/fuzz/fuzz_contract.h"

namespace {

template <class Msg>
void RoundTrip(const std::uint8_t* data, std::size_t size) {
  Msg msg;
  ahhs::bus::ClearForDecode(&msg);
  if (!ahhs::bus::Decode(data, size, &msg)) return;
  const auto once = ahhs::bus::Encode(msg);
  FUZZ_CONTRACT(!once.empty(), "a decoded message does not encode again");
  Msg again;
  ahhs::bus::ClearForDecode(&again);
  FUZZ_CONTRACT(ahhs::bus::Decode(once.data(), once.size(), &again),
                "a re-encoded message does not decode");
  FUZZ_CONTRACT(ahhs::bus::Encode(again) == once, "encode(decode(bytes)) is not stable");
}

template <class... Msgs>
void All(const std::uint8_t* data, std::size_t size) {
  (RoundTrip<Msgs>(data, size), ...);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ahhs;
  All<module_sensors_t, hinge_command_t, hormone_packet_t, module_status_t, module_trace_t,
      topology_t, sim_control_t, sim_clock_t, sim_state_t, genome_t, fitness_t, eval_request_t,
      eval_result_t, worker_status_t, genome_chunk_t, genome_want_t>(data, size);
  return 0;
}
