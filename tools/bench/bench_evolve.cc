#include "tools/bench/bench_evolve.h"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>

#include "base/children.h"
#include "base/temp_files.h"

namespace cli = ahhs::base::cli;

namespace ahhs::bench {
namespace {

// One evolution run through ahhs-evolve (real worker processes, real LCM traffic, the SQLite
// store), timed from the outside.
void BenchEvolve(const std::string& name, const std::string& options, int generations,
                 const std::string& url, int workers) {
  const ahhs::base::TempDir scratch("ahhs-bench-evolve-");
  const std::string& dir = scratch.path();
  const std::string command =
      ahhs::base::ExecutableDir() + "/ahhs-evolve " + options + " --generations " +
      std::to_string(generations) + " --lcm-url '" + url + "' --out " + dir + "/run" +
      (workers >= 0 ? " --workers " + std::to_string(workers) : "") + " 2>&1";
  const auto start = std::chrono::steady_clock::now();
  FILE* pipe = popen(command.c_str(), "r");
  std::string output, best = "?", held_out;
  char line[4096];
  while (pipe && std::fgets(line, sizeof line, pipe)) {
    output += line;
    if (std::strncmp(line, "best fitness: ", 14) == 0) best = std::string(line + 14);
    if (std::strncmp(line, "post-evaluation on ", 19) == 0) held_out = std::string(line);
  }
  const int status = pipe ? pclose(pipe) : -1;
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (status != 0) {
    std::printf("%s: ahhs-evolve failed:\n%s\n", name.c_str(), output.c_str());
    return;
  }
  if (!best.empty() && best.back() == '\n') best.pop_back();
  std::printf("%-36s %3d generations: %7.1f s wall (%.2f s per generation); best %s\n",
              name.c_str(), generations, wall, wall / generations, best.c_str());
  if (!held_out.empty()) std::printf("  %s", held_out.c_str());
  std::fflush(stdout);
}

}  // namespace

cli::App* EvolveBench::Add(cli::App& app) {
  auto* sub = app.add_subcommand(
      "evolve", "whole evolution runs at the paper's scale through ahhs-evolve (minutes)");
  sub->add_option("--task", task,
                  "pendulum, gait-damped, gait-fixed, all, or main-job (the README's: ahhs-evolve "
                  "with neither --config nor --scenario, its post-evaluation included; "
                  "--trials and --envelope do not apply)")
      ->check(cli::IsMember({"pendulum", "gait-damped", "gait-fixed", "all", "main-job"}))
      ->capture_default_str();
  sub->add_option("--generations", generations, "generations per run (paper: 200)")
      ->check(cli::Range(1, 100000))
      ->capture_default_str();
  sub->add_option("--workers", workers, "local workers (default: one per core)");
  sub->add_option("--trials", trials, "episodes per individual (robust evolution)")
      ->check(cli::Range(1, 64))
      ->capture_default_str();
  sub->add_option("--envelope", envelope, "envelope of noise: none, paper or wide")
      ->check(cli::IsMember({"none", "paper", "wide"}))
      ->capture_default_str();
  sub->add_option("--lcm-url", url, "LCM URL of the farm")->capture_default_str();
  return sub;
}

void EvolveBench::Run() const {
  std::printf("evolution runs through ahhs-evolve, %s workers, seed 1\n",
              workers < 0 ? "one per core" : std::to_string(workers).c_str());
  const std::string common =
      " --seed 1 --trials " + std::to_string(trials) + " --envelope " + envelope;
  if (trials > 1 || envelope != "none")
    std::printf("robust: %d trials per individual, envelope %s\n", trials, envelope.c_str());
  if (task == "main-job")
    BenchEvolve("the README's main job (robust damped)", "--seed 1", generations, url, workers);
  if (task == "pendulum" || task == "all")
    BenchEvolve(
        "pendulum AHHS2 15 H x 15 R, pop 200",
        "--scenario pendulum --variant ahhs2 --hormones 15 --rules 15 --population 200" + common,
        generations, url, workers);
  if (task == "pendulum" || task == "all")
    BenchEvolve(
        "pendulum AHHS1 15 H x 60 R, pop 200",
        "--scenario pendulum --variant ahhs1 --hormones 15 --rules 60 --population 200" + common,
        generations, url, workers);
  for (const char* docking : {"damped", "fixed"})
    if (task == "all" || task == std::string("gait-") + docking)
      BenchEvolve(std::string("gait ") + docking + " AHHS2 5 H x 30 R, pop 20",
                  std::string("--scenario gait --docking ") + docking +
                      " --variant ahhs2 --hormones 5 --rules 30 --population 20" + common,
                  generations, url, workers);
}

}  // namespace ahhs::bench
