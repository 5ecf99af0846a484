// ahhs-genome's show and run subcommands: a genome as tables, and a genome driven by recorded
// sensor readings (modules/app/sensor_csv.h).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "modules/core/genome.h"

namespace ahhs::modules {

// Prints a genome's hormones and rules as tables.
void Show(const Genome& g);

// Runs `compartments` copies of the genome on the sensor readings of `csv_path` for `ticks`
// ticks (<= 0: as many as the file has); prints the actuators per tick. Returns the exit code.
int RunOnSensorCsv(const Genome& genome, int compartments, const std::string& csv_path,
                   long ticks_opt);

// The JSON document in `path` ("-": standard input). Throws std::runtime_error naming the file
// and what is wrong (missing, unreadable, not JSON).
nlohmann::json ReadVectorFile(const std::string& path);

}  // namespace ahhs::modules
