// The strict LCM log reader (bus/log_reader.h) that ahhs-replay and ahhs-view read logs with:
// any bytes give events or a LogFileError; every event parsed moves the offset forward and
// stays inside the buffer; the events' payloads then go through every decoder.
#include <ahhs/fitness_t.hpp>
#include <ahhs/genome_t.hpp>
#include <ahhs/hinge_command_t.hpp>
#include <ahhs/module_sensors_t.hpp>
#include <ahhs/module_trace_t.hpp>
#include <ahhs/sim_state_t.hpp>
#include <ahhs/topology_t.hpp>
#include <cstddef>
#include <cstdint>

#include "bus/codec.h"
#include "bus/log_reader.h"
#include "tests/fuzz/fuzz_contract.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ahhs;
  std::size_t offset = 0;
  bus::LogEvent event;
  try {
    while (true) {
      const std::size_t before = offset;
      if (!bus::ParseLogEvent("fuzz.log", data, size, &offset, &event)) break;
      FUZZ_CONTRACT(offset > before && offset <= size, "an event did not move inside the log");
      const auto* d = event.data.data();
      const auto n = event.data.size();
      sim_state_t state;
      module_sensors_t sensors;
      hinge_command_t hinge;
      module_trace_t trace;
      topology_t topology;
      genome_t genome;
      fitness_t fitness;
      (void)bus::Decode(d, n, &state);
      (void)bus::Decode(d, n, &sensors);
      (void)bus::Decode(d, n, &hinge);
      (void)bus::Decode(d, n, &trace);
      (void)bus::Decode(d, n, &topology);
      (void)bus::Decode(d, n, &genome);
      (void)bus::Decode(d, n, &fitness);
    }
  } catch (const bus::LogFileError&) {
  }
  return 0;
}
