#include "modules/app/sensor_csv.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace ahhs::modules {
namespace {

std::vector<std::string> SplitCells(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream s(line);
  while (std::getline(s, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

std::string Trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

bool ParseLong(const std::string& text, long* out) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  *out = std::strtol(text.c_str(), &end, 10);
  return errno == 0 && *end == '\0';
}

bool ParseDouble(const std::string& text, double* out) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  *out = std::strtod(text.c_str(), &end);
  return errno == 0 && *end == '\0' && std::isfinite(*out);
}

}  // namespace

SensorTable ReadSensorCsv(std::istream& in, const std::string& source, int num_sensors,
                          int num_compartments) {
  SensorTable table;
  std::string line;
  int line_no = 0;
  auto fail = [&](const std::string& what) {
    throw SensorCsvError(source + ":" + std::to_string(line_no) + ": " + what);
  };
  while (std::getline(in, line)) {
    ++line_no;
    line = Trim(line);
    if (line.empty() || line[0] == '#') continue;
    auto cells = SplitCells(line);
    for (auto& c : cells) c = Trim(c);
    if (line_no == 1 && cells[0] == "tick") continue;  // header
    if (static_cast<int>(cells.size()) != 2 + num_sensors)
      fail("expected " + std::to_string(2 + num_sensors) + " cells (tick,compartment and " +
           std::to_string(num_sensors) + " sensors), found " + std::to_string(cells.size()));
    long tick = 0, compartment = 0;
    if (!ParseLong(cells[0], &tick) || tick < 0)
      fail("tick '" + cells[0] + "' is not an integer >= 0");
    if (!ParseLong(cells[1], &compartment) || compartment < 0 || compartment >= num_compartments)
      fail("compartment '" + cells[1] + "' is not in [0, " + std::to_string(num_compartments) +
           ")");
    SensorRow row;
    row.values.assign(static_cast<std::size_t>(num_sensors), 0.0);
    row.present.assign(static_cast<std::size_t>(num_sensors), 0);
    for (int s = 0; s < num_sensors; ++s) {
      const std::string& cell = cells[static_cast<std::size_t>(2 + s)];
      if (cell.empty()) continue;  // absent slot
      double v = 0;
      if (!ParseDouble(cell, &v))
        fail("s" + std::to_string(s) + " '" + cell + "' is not a finite number");
      if (v < 0.0 || v > 1.0) fail("s" + std::to_string(s) + " = " + cell + " outside [0, 1]");
      row.values[static_cast<std::size_t>(s)] = v;
      row.present[static_cast<std::size_t>(s)] = 1;
    }
    const auto key = std::make_pair(tick, static_cast<int>(compartment));
    if (table.rows.count(key))
      fail("a second row for tick " + cells[0] + ", compartment " + cells[1]);
    table.rows.emplace(key, std::move(row));
    table.last_tick = std::max(table.last_tick, tick);
  }
  if (in.bad()) throw SensorCsvError(source + ": read error");
  if (table.rows.empty()) throw SensorCsvError(source + ": no sensor rows");
  return table;
}

}  // namespace ahhs::modules
