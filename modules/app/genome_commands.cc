#include "modules/app/genome_commands.h"

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <stdexcept>

#include "modules/app/sensor_csv.h"
#include "modules/core/genome_json.h"
#include "modules/core/organism.h"

namespace ahhs::modules {
namespace am = ahhs::modules;
void Show(const am::Genome& g) {
  std::printf("%s genome: %d hormones, %d rules, %d sensors, %d actuators; hash %s\n\n",
              am::VariantName(g.variant), g.num_hormones(), g.num_rules(), g.num_sensors,
              g.num_actuators, am::GenomeHashText(g).c_str());
  std::printf("%-8s %10s %10s %10s\n", "hormone", "alpha", "mu", "diffusion");
  for (int h = 0; h < g.num_hormones(); ++h) {
    const auto& x = g.hormones[static_cast<std::size_t>(h)];
    std::printf("H%-7d %10.4f %10.4f %10.4f\n", h, x.alpha, x.mu, x.diffusion);
  }
  std::printf("\n");
  if (g.variant == am::Variant::kAhhs2) {
    std::printf("%-5s %-16s %-17s %8s %8s %5s %5s %-11s %-11s\n", "rule", "dominant type",
                "trigger window", "kappa", "lambda", "S", "H in", "H out", "A out");
    for (int r = 0; r < g.num_rules(); ++r) {
      const auto& x = g.ahhs2_rules[static_cast<std::size_t>(r)];
      int best = 0;
      for (int p = 1; p < 5; ++p)
        if (x.weights[static_cast<std::size_t>(p)] > x.weights[static_cast<std::size_t>(best)])
          best = p;
      char dominant[32], window[40], out_h[48], out_a[48];
      std::snprintf(dominant, sizeof dominant, "%s %.2f", am::Ahhs2PartName(best),
                    x.weights[static_cast<std::size_t>(best)]);
      std::snprintf(window, sizeof window, "[%+.3f, %+.3f]", x.zeta - x.eta, x.zeta + x.eta);
      const int o = static_cast<int>(std::floor(x.output));
      const int a = static_cast<int>(std::floor(x.actuator));
      std::snprintf(out_h, sizeof out_h, "H%d/H%d %.2f", o, (o + 1) % g.num_hormones(),
                    x.output - o);
      std::snprintf(out_a, sizeof out_a, "A%d/A%d %.2f", a, (a + 1) % g.num_actuators,
                    x.actuator - a);
      std::printf("%-5d %-16s %-17s %8.4f %8.4f %5s %5s %-11s %-11s\n", r, dominant, window,
                  x.kappa, x.lambda, ("S" + std::to_string(static_cast<int>(x.sensor))).c_str(),
                  ("H" + std::to_string(static_cast<int>(x.input))).c_str(), out_h, out_a);
    }
    std::printf(
        "\nOutput indices split their effect: \"H1/H2 0.25\" sends 75%% to H1, 25%% to H2.\n");
  } else {
    std::printf("%-5s %-9s %-6s %-6s %-10s %8s %8s\n", "rule", "type", "in", "out", "trigger",
                "lambda", "kappa");
    for (int r = 0; r < g.num_rules(); ++r) {
      const auto& x = g.ahhs1_rules[static_cast<std::size_t>(r)];
      const bool reads_sensor = x.type == am::Ahhs1Type::kSensor;
      const bool writes_actuator = x.type == am::Ahhs1Type::kActuator;
      char trigger[24];
      std::snprintf(trigger, sizeof trigger, "%s %.3f",
                    x.direction == am::Direction::kAbove ? ">" : "<", x.tau);
      std::printf("%-5d %-9s %-6s %-6s %-10s %8.4f %8.4f\n", r, am::Ahhs1TypeName(x.type),
                  ((reads_sensor ? "S" : "H") + std::to_string(x.input)).c_str(),
                  ((writes_actuator ? "A" : "H") + std::to_string(x.output)).c_str(), trigger,
                  x.lambda, x.kappa);
    }
  }
}

int RunOnSensorCsv(const am::Genome& genome, int compartments, const std::string& csv_path,
                   long ticks_opt) {
  std::ifstream in(csv_path);
  if (!in) throw am::SensorCsvError(csv_path + ": cannot open");
  const am::SensorTable table = am::ReadSensorCsv(in, csv_path, genome.num_sensors, compartments);
  const long ticks = ticks_opt > 0 ? ticks_opt : table.last_tick + 1;

  const am::Controller controller(genome);
  am::Organism organism(controller, am::Organism::Chain(compartments));
  // Sample and hold: a compartment keeps its last row until a new one arrives; before its first
  // row every slot is absent.
  std::vector<am::SensorRow> current(static_cast<std::size_t>(compartments));
  for (auto& row : current) {
    row.values.assign(static_cast<std::size_t>(genome.num_sensors), 0.0);
    row.present.assign(static_cast<std::size_t>(genome.num_sensors), 0);
  }
  std::vector<std::unique_ptr<bool[]>> masks;
  std::vector<am::TickInput> inputs(static_cast<std::size_t>(compartments));
  for (int c = 0; c < compartments; ++c)
    masks.emplace_back(new bool[static_cast<std::size_t>(genome.num_sensors)]);

  std::printf("tick,compartment");
  for (int h = 0; h < genome.num_hormones(); ++h) std::printf(",h%d", h);
  for (int a = 0; a < genome.num_actuators; ++a) std::printf(",a%d", a);
  std::printf("\n");
  for (long t = 0; t < ticks; ++t) {
    for (int c = 0; c < compartments; ++c) {
      const auto cu = static_cast<std::size_t>(c);
      auto it = table.rows.find({t, c});
      if (it != table.rows.end()) current[cu] = it->second;
      for (int s = 0; s < genome.num_sensors; ++s)
        masks[cu][s] = current[cu].present[static_cast<std::size_t>(s)] != 0;
      inputs[cu].sensors = current[cu].values.data();
      inputs[cu].sensor_present = masks[cu].get();
    }
    organism.Step(inputs);
    for (int c = 0; c < compartments; ++c) {
      const auto& st = organism.state(c);
      std::printf("%ld,%d", t, c);
      for (int h = 0; h < genome.num_hormones(); ++h) std::printf(",%.17g", st.hormones[h]);
      for (int a = 0; a < genome.num_actuators; ++a) std::printf(",%.17g", st.actuators[a]);
      std::printf("\n");
    }
  }
  return 0;
}

nlohmann::json ReadVectorFile(const std::string& path) {
  std::ifstream file;
  if (path != "-") {
    file.open(path);
    if (!file) throw std::runtime_error(path + ": cannot open");
  }
  std::istream& in = path == "-" ? std::cin : file;
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error((path == "-" ? std::string("standard input") : path) + ": not JSON (" +
                             e.what() + ")");
  }
}

}  // namespace ahhs::modules
