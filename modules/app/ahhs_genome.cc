// ahhs-genome: make, vary, check, read and run hormone-controller genomes from the shell.
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>

#include "base/cli.h"
#include "modules/app/genome_commands.h"
#include "modules/app/sensor_csv.h"
#include "modules/core/genome_json.h"
#include "modules/core/genome_vector.h"
#include "modules/core/organism.h"
#include "modules/core/random.h"
#include "modules/core/variation.h"

namespace cli = ahhs::base::cli;

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

}  // namespace

int main(int argc, char** argv) {
  cli::App app{
      "ahhs-genome: make, vary, check, show and run AHHS hormone-controller genomes.\n"
      "Genome files are JSON (docs/genome.md)."};
  app.require_subcommand(1);
  am::MutationParams mutation;

  auto* random = app.add_subcommand("random", "Print a random genome as JSON");
  std::string variant = "ahhs2";
  am::Shape shape{am::Variant::kAhhs2, 5, 30, 4, 1};
  std::uint64_t seed = 1;
  random->add_option("--variant", variant, "ahhs1 or ahhs2")
      ->check(cli::IsMember({"ahhs1", "ahhs2"}))
      ->capture_default_str();
  random->add_option("--hormones", shape.hormones, "number of hormones")
      ->check(cli::Range(1, am::Ranges::kMaxHormones))
      ->capture_default_str();
  random->add_option("--rules", shape.rules, "number of rules")
      ->check(cli::Range(0, am::Ranges::kMaxRules))
      ->capture_default_str();
  random->add_option("--sensors", shape.sensors, "sensor slots per compartment")
      ->check(cli::Range(1, am::Ranges::kMaxSlots))
      ->capture_default_str();
  random->add_option("--actuators", shape.actuators, "actuator slots per compartment")
      ->check(cli::Range(1, am::Ranges::kMaxSlots))
      ->capture_default_str();
  random->add_option("--seed", seed, "random seed (recorded in the genome's meta)")
      ->check(ahhs::modules::SeedTextError)
      ->required();

  auto* mutate =
      app.add_subcommand("mutate", "Print mutants of a genome (a JSON array when --count > 1)");
  std::string file, file_b;
  int count = 1;
  mutate->add_option("FILE", file, "genome file")->required()->check(cli::ExistingFile);
  mutate->add_option("--seed", seed, "random seed")
      ->check(ahhs::modules::SeedTextError)
      ->required();
  mutate->add_option("--count", count, "number of independent mutants")
      ->check(cli::Range(1, 100000))
      ->capture_default_str();
  mutate->add_option("--rate", mutation.gene_rate, "mutation probability per gene")
      ->check(cli::Range(0.0, 1.0))
      ->capture_default_str();
  mutate->add_option("--max-change", mutation.max_change, "largest change of a real field")
      ->check(cli::Range(0.0, 1.0))
      ->capture_default_str();
  bool single_gene = false;
  mutate->add_flag("--single-gene", single_gene,
                   "mutate exactly one gene (mutation-neighbourhood studies)");

  auto* crossover = app.add_subcommand(
      "crossover", "Print the two children of a two-point crossover (JSON array)");
  crossover->add_option("A", file, "first parent")->required()->check(cli::ExistingFile);
  crossover->add_option("B", file_b, "second parent")->required()->check(cli::ExistingFile);
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
      ->check(cli::Range(1, 10000));
  run->add_option("--sensors", csv,
                  "sensor CSV: tick,compartment,s0,s1,... (empty cell = absent slot)")
      ->required();
  run->add_option("--ticks", ticks, "ticks to run (default: up to the CSV's last tick)")
      ->check(cli::PositiveNumber);

  auto* to_vector = app.add_subcommand(
      "to-vector", "Print a genome as a flat vector of reals with bounds (JSON, docs/genome.md)");
  to_vector->add_option("FILE", file, "genome file")->required();
  auto* from_vector =
      app.add_subcommand("from-vector", "Print the genome a vector file gives (values clipped)");
  from_vector->add_option("FILE", file, "vector file (JSON; - for stdin)")->required();

  ahhs::base::SetVersion(app,
                         {ahhs::modules::GenomeFormatLine(), ahhs::modules::GenomeVectorLine()});
  if (const int code = ahhs::base::Parse(app, argc, argv); code >= 0) return code;

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
                             {"parent_hash", am::GenomeHashText(parent)}});
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
                  g.num_sensors, g.num_actuators, am::GenomeHashText(g).c_str());
    } else if (show->parsed()) {
      am::Show(am::LoadGenomeFile(file));
    } else if (to_vector->parsed()) {
      const am::Genome g = am::LoadGenomeFile(file);
      std::cout << am::VectorToJson(g.shape(), am::GenomeToVector(g)).dump(2) << '\n';
    } else if (from_vector->parsed()) {
      const json doc = am::ReadVectorFile(file);
      am::Shape vector_shape;
      const std::vector<double> x = am::VectorFromJson(doc, &vector_shape);
      PrintGenomes({am::GenomeFromVector(vector_shape, x)},
                   json{{"created_by", "ahhs-genome from-vector"}});
    } else if (run->parsed()) {
      return am::RunOnSensorCsv(am::LoadGenomeFile(file), compartments, csv, ticks);
    }
  } catch (const std::exception& e) {
    std::cerr << "ahhs-genome: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
