// Recorded sensor data for open-loop runs of a controller (`ahhs-genome run`).
// CSV rows: tick,compartment,s0,s1,...  An empty cell is an absent slot. An optional header
// line starts with "tick". Values must lie in [0, 1].
#pragma once

#include <istream>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace ahhs::modules {

struct SensorRow {
  std::vector<double> values;  // num_sensors entries (0 where absent)
  std::vector<char> present;   // 1 = slot owned and read
};

struct SensorTable {
  std::map<std::pair<long, int>, SensorRow> rows;  // (tick, compartment) -> row
  long last_tick = -1;
};

class SensorCsvError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws SensorCsvError("<source>:<line>: <problem>") on any malformed line.
SensorTable ReadSensorCsv(std::istream& in, const std::string& source, int num_sensors,
                          int num_compartments);

}  // namespace ahhs::modules
