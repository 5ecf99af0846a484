// ahhs-genome: make, vary, check, read and run hormone-controller genomes from the shell.
#include <CLI/CLI.hpp>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>

#include "base/cli.h"
#include "modules/app/sensor_csv.h"
#include "modules/core/genome_json.h"
#include "modules/core/organism.h"
#include "modules/core/random.h"
#include "modules/core/variation.h"

namespace am = ahhs::modules;
using nlohmann::json;

namespace {

void PrintGenomes(const std::vector<am::Genome>& genomes, const json& meta) {
  if (genomes.size() == 1) {
    std::cout << am::GenomeToJson(genomes[0], meta).dump(2) << '\n';
    return;
  }
  json list = json::array();
  for (const auto& g : genomes) list.push_back(am::GenomeToJson(g, meta));
  std::cout << list.dump(2) << '\n';
}

std::string Hex(std::uint64_t h) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%016" PRIx64, h);
  return buf;
}

void Show(const am::Genome& g) {
  std::printf("%s genome: %d hormones, %d rules, %d sensors, %d actuators; hash %s\n\n",
              am::VariantName(g.variant), g.num_hormones(), g.num_rules(), g.num_sensors,
              g.num_actuators, Hex(am::GenomeHash(g)).c_str());
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
      char dominant[32], window[40], out_h[24], out_a[24];
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

int Run(const am::Genome& genome, int compartments, const std::string& csv_path, long ticks_opt) {
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

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "ahhs-genome: make, vary, check, show and run AHHS hormone-controller genomes.\n"
      "Genome files are JSON (docs/genome.md)."};
  app.require_subcommand(1);
  am::MutationParams mutation;

  auto* random = app.add_subcommand("random", "Print a random genome as JSON");
  std::string variant = "ahhs2";
  am::Shape shape{am::Variant::kAhhs2, 5, 30, 4, 1};
  std::uint64_t seed = 1;
  random->add_option("--variant", variant, "ahhs1 or ahhs2")
      ->check(CLI::IsMember({"ahhs1", "ahhs2"}))
      ->capture_default_str();
  random->add_option("--hormones", shape.hormones, "number of hormones")
      ->check(CLI::Range(1, am::Ranges::kMaxHormones))
      ->capture_default_str();
  random->add_option("--rules", shape.rules, "number of rules")
      ->check(CLI::Range(0, am::Ranges::kMaxRules))
      ->capture_default_str();
  random->add_option("--sensors", shape.sensors, "sensor slots per compartment")
      ->check(CLI::Range(1, am::Ranges::kMaxSlots))
      ->capture_default_str();
  random->add_option("--actuators", shape.actuators, "actuator slots per compartment")
      ->check(CLI::Range(1, am::Ranges::kMaxSlots))
      ->capture_default_str();
  random->add_option("--seed", seed, "random seed (recorded in the genome's meta)")
      ->check(ahhs::modules::SeedTextError)
      ->required();

  auto* mutate =
      app.add_subcommand("mutate", "Print mutants of a genome (a JSON array when --count > 1)");
  std::string file, file_b;
  int count = 1;
  mutate->add_option("FILE", file, "genome file")->required()->check(CLI::ExistingFile);
  mutate->add_option("--seed", seed, "random seed")
      ->check(ahhs::modules::SeedTextError)
      ->required();
  mutate->add_option("--count", count, "number of independent mutants")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  mutate->add_option("--rate", mutation.gene_rate, "mutation probability per gene")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  mutate->add_option("--max-change", mutation.max_change, "largest change of a real field")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  bool single_gene = false;
  mutate->add_flag("--single-gene", single_gene,
                   "mutate exactly one gene (mutation-neighbourhood studies)");

  auto* crossover = app.add_subcommand(
      "crossover", "Print the two children of a two-point crossover (JSON array)");
  crossover->add_option("A", file, "first parent")->required()->check(CLI::ExistingFile);
  crossover->add_option("B", file_b, "second parent")->required()->check(CLI::ExistingFile);
  crossover->add_option("--seed", seed, "random seed")
      ->check(ahhs::modules::SeedTextError)
      ->required();

  auto* validate =
      app.add_subcommand("validate", "Exit 0 if FILE is a valid genome, else print why and exit 1");
  validate->add_option("FILE", file, "genome file")->required();

  auto* show = app.add_subcommand("show", "Print a genome's hormones and rules as tables");
  show->add_option("FILE", file, "genome file")->required();

  auto* run = app.add_subcommand(
      "run", "Run C compartments docked in a line open-loop on recorded sensor data; print CSV");
  int compartments = 1;
  std::string csv;
  long ticks = 0;
  run->add_option("FILE", file, "genome file")->required();
  run->add_option("--compartments", compartments, "compartments docked in a line")
      ->required()
      ->check(CLI::Range(1, 10000));
  run->add_option("--sensors", csv,
                  "sensor CSV: tick,compartment,s0,s1,... (empty cell = absent slot)")
      ->required();
  run->add_option("--ticks", ticks, "ticks to run (default: up to the CSV's last tick)")
      ->check(CLI::PositiveNumber);

  if (const int code = ahhs::cli::Parse(app, argc, argv); code >= 0) return code;

  try {
    if (random->parsed()) {
      shape.variant = variant == "ahhs1" ? am::Variant::kAhhs1 : am::Variant::kAhhs2;
      am::Rng rng(seed);
      PrintGenomes({am::RandomGenome(shape, rng)},
                   json{{"created_by", "ahhs-genome random"}, {"seed", seed}});
    } else if (mutate->parsed()) {
      const am::Genome parent = am::LoadGenomeFile(file);
      am::Rng rng(seed);
      std::vector<am::Genome> out;
      for (int k = 0; k < count; ++k) {
        am::Genome g = parent;
        if (single_gene)
          am::MutateOneGene(&g, mutation, rng);
        else
          am::Mutate(&g, mutation, rng);
        out.push_back(std::move(g));
      }
      PrintGenomes(out, json{{"created_by", "ahhs-genome mutate"},
                             {"seed", seed},
                             {"parent_hash", Hex(am::GenomeHash(parent))}});
    } else if (crossover->parsed()) {
      const am::Genome a = am::LoadGenomeFile(file);
      const am::Genome b = am::LoadGenomeFile(file_b);
      if (a.shape() != b.shape()) {
        std::cerr << "ahhs-genome crossover: " << file << " and " << file_b
                  << " differ in variant or size; crossover needs equal shapes\n";
        return 1;
      }
      am::Rng rng(seed);
      auto [c, d] = am::Crossover(a, b, rng);
      PrintGenomes({c, d}, json{{"created_by", "ahhs-genome crossover"}, {"seed", seed}});
    } else if (validate->parsed()) {
      const am::Genome g = am::LoadGenomeFile(file);
      std::printf("%s: valid %s genome, %d hormones, %d rules, %d sensors, %d actuators, hash %s\n",
                  file.c_str(), am::VariantName(g.variant), g.num_hormones(), g.num_rules(),
                  g.num_sensors, g.num_actuators, Hex(am::GenomeHash(g)).c_str());
    } else if (show->parsed()) {
      Show(am::LoadGenomeFile(file));
    } else if (run->parsed()) {
      return Run(am::LoadGenomeFile(file), compartments, csv, ticks);
    }
  } catch (const std::exception& e) {
    std::cerr << "ahhs-genome: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
