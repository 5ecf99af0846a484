// run-controller: a hormone controller, linked from an installed AHHS, driven by recorded
// sensor readings. Its output is `ahhs-genome run`'s, to the last bit, for a CSV that gives
// every compartment a row every tick.
//   run-controller GENOME.json SENSORS.csv COMPARTMENTS
// SENSORS.csv: "tick,compartment,s0,...,s(n-1)" per line, n the genome's sensors, values in
// [0, 1]; a first line starting with "tick" is a header.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "modules/core/genome_json.h"
#include "modules/core/hormone_system.h"
#include "modules/core/organism.h"

namespace am = ahhs::modules;

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: run-controller GENOME.json SENSORS.csv COMPARTMENTS\n";
    return 2;
  }
  try {
    const am::Genome genome = am::LoadGenomeFile(argv[1]);
    const int compartments = std::stoi(argv[3]);
    const auto n = static_cast<std::size_t>(genome.num_sensors);

    // (tick, compartment) -> readings
    std::map<std::pair<long, int>, std::vector<double>> rows;
    long last_tick = -1;
    std::ifstream in(argv[2]);
    if (!in) throw std::runtime_error(std::string(argv[2]) + ": cannot open");
    for (std::string line; std::getline(in, line);) {
      if (line.empty() || line.rfind("tick", 0) == 0) continue;
      std::istringstream cells(line);
      std::string cell;
      std::getline(cells, cell, ',');
      const long tick = std::stol(cell);
      std::getline(cells, cell, ',');
      const int c = std::stoi(cell);
      std::vector<double> values;
      while (std::getline(cells, cell, ',')) values.push_back(std::stod(cell));
      if (values.size() != n || c < 0 || c >= compartments)
        throw std::runtime_error(std::string(argv[2]) + ": bad line '" + line + "'");
      rows[{tick, c}] = values;
      if (tick > last_tick) last_tick = tick;
    }

    const am::Controller controller(genome);
    am::Organism organism(controller, am::Organism::Chain(compartments));
    std::vector<std::vector<double>> current(static_cast<std::size_t>(compartments),
                                             std::vector<double>(n, 0.0));
    std::vector<am::TickInput> inputs(static_cast<std::size_t>(compartments));
    std::printf("tick,compartment");
    for (int h = 0; h < genome.num_hormones(); ++h) std::printf(",h%d", h);
    for (int a = 0; a < genome.num_actuators; ++a) std::printf(",a%d", a);
    std::printf("\n");
    for (long t = 0; t <= last_tick; ++t) {
      for (int c = 0; c < compartments; ++c) {
        const auto cu = static_cast<std::size_t>(c);
        const auto it = rows.find({t, c});
        if (it != rows.end()) current[cu] = it->second;
        inputs[cu].sensors = current[cu].data();
      }
      organism.Step(inputs);
      for (int c = 0; c < compartments; ++c) {
        const am::CompartmentState& s = organism.state(c);
        std::printf("%ld,%d", t, c);
        for (int h = 0; h < genome.num_hormones(); ++h) std::printf(",%.17g", s.hormones[h]);
        for (int a = 0; a < genome.num_actuators; ++a) std::printf(",%.17g", s.actuators[a]);
        std::printf("\n");
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "run-controller: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
