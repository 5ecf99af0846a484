// ahhs-bench: speed figures for docs/performance.md. Benchmarks, not tests: they print
// numbers and never fail on them.
//   ahhs-bench controller [--ticks N] [--repeats R] [--seed S]
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <set>
#include <thread>
#include <vector>

#include "base/children.h"
#include "base/cli.h"
#include "base/temp_files.h"
#include "episode/arena/direct_arena.h"
#include "episode/arena/episode.h"
#include "episode/arena/fused_arena.h"
#include "episode/arena/process_arena.h"
#include "modules/core/genome_json.h"
#include "modules/core/hormone_system.h"
#include "modules/core/random.h"
#include "modules/core/variation.h"
#include "sim/core/drive.h"
#include "sim/core/gait.h"
#include "sim/core/scenario.h"

namespace am = ahhs::modules;
using Clock = std::chrono::steady_clock;

namespace {

struct ControllerCase {
  const char* name;
  am::Shape shape;
};

// Nanoseconds per tick of one compartment: receive one neighbour packet, step, with sensor
// values that change every tick (precomputed so drawing them is not measured).
void BenchController(const ControllerCase& c, bool smooth, long ticks, int repeats,
                     std::uint64_t seed) {
  am::Rng rng(seed);
  const am::Controller controller(am::RandomGenome(c.shape, rng));
  auto state = am::MakeState(controller);
  const int table = 1024;
  std::vector<double> sensors(static_cast<std::size_t>(table * c.shape.sensors));
  // iid: a fresh uniform value every tick (worst case for the CPU's branch predictor);
  // smooth: slow sine waves, as the readings of a physical robot sampled at 20 Hz change.
  for (int t = 0; t < table; ++t)
    for (int k = 0; k < c.shape.sensors; ++k)
      sensors[static_cast<std::size_t>(t * c.shape.sensors + k)] =
          smooth ? 0.5 + 0.5 * std::sin(2 * M_PI * (t / double(table)) * (k + 1) + k)
                 : rng.Uniform();
  std::vector<double> packet(static_cast<std::size_t>(c.shape.hormones), 0.001);

  std::vector<double> ns_per_tick;
  std::uint64_t fired = 0;
  for (int rep = 0; rep < repeats; ++rep) {
    state = am::MakeState(controller);
    const auto t0 = Clock::now();
    for (long t = 0; t < ticks; ++t) {
      am::TickInput in;
      in.sensors = &sensors[static_cast<std::size_t>((t % table) * c.shape.sensors)];
      in.num_neighbours = 2;
      am::ReceiveHormones(packet.data(), &state);
      am::Step(controller, in, &state);
    }
    const double ns = std::chrono::duration<double, std::nano>(Clock::now() - t0).count();
    ns_per_tick.push_back(ns / static_cast<double>(ticks));
    fired = 0;
    for (auto n : state.part_activity) fired += n;
  }
  std::sort(ns_per_tick.begin(), ns_per_tick.end());
  const double median = ns_per_tick[ns_per_tick.size() / 2];
  std::printf("%-26s %-6s %9.1f ns/tick  (min %.1f, max %.1f; %.2f rule parts fired per tick)\n",
              c.name, smooth ? "smooth" : "iid", median, ns_per_tick.front(), ns_per_tick.back(),
              static_cast<double>(fired) / static_cast<double>(ticks));
}

// Wall time of physics-only episodes with the built-in drive, one core: for each seed the median
// of `repeats` runs, then the median over the seeds. Each seed is a different trajectory of a
// chaotic system (ODE's solver order is seeded), and the cost of a physics step follows the
// number of ground contacts, so one seed alone is a poor estimate.
void BenchSim(const ahhs::sim::ScenarioConfig& config, const char* drive_name, int repeats,
              std::uint64_t first_seed, int seeds, bool chain_solver) {
  namespace as = ahhs::sim;
  const as::DriveKind drive = as::ParseDrive(drive_name);
  std::unique_ptr<as::Scenario> sim;
  if (!chain_solver && config.kind == as::ScenarioKind::kGait) {
    as::GaitConstants constants;
    constants.solver = as::GaitSolver::kDantzig;
    sim = std::make_unique<as::GaitScenario>(config, constants);
  } else {
    sim = as::MakeScenario(config);
  }
  std::vector<double> per_seed, fitnesses;
  std::vector<double> command(static_cast<std::size_t>(sim->num_actuators()));
  for (int k = 0; k < seeds; ++k) {
    std::vector<double> walls;
    for (int rep = 0; rep < repeats; ++rep) {
      const auto t0 = Clock::now();
      sim->Reset(first_seed + static_cast<std::uint64_t>(k));
      while (true) {
        for (int c = 0; c < sim->num_compartments(); ++c) {
          as::DriveCommand(drive, *sim, c, command.data());
          sim->SetActuators(c, command.data());
        }
        if (sim->Step() != as::StepStatus::kRunning) break;
      }
      walls.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    }
    std::sort(walls.begin(), walls.end());
    per_seed.push_back(walls[walls.size() / 2]);
    fitnesses.push_back(sim->Fitness());
  }
  std::vector<double> sorted = per_seed;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted[sorted.size() / 2];
  std::printf(
      "%-8s %-6s %-6s %2d modules %6.1f s simulated: %7.1f ms wall (seeds: min %.1f, max %.1f), "
      "%5.0fx real time, fitness %.4f",
      as::ScenarioName(config.kind),
      config.kind == as::ScenarioKind::kGait ? as::JointsName(config.joints) : "-", drive_name,
      sim->num_compartments(), sim->sim_time(), 1e3 * median, 1e3 * sorted.front(),
      1e3 * sorted.back(), sim->sim_time() / median, fitnesses.front());
  if (seeds > 1) {
    std::sort(fitnesses.begin(), fitnesses.end());
    std::printf(" (seeds: %.4f-%.4f)", fitnesses.front(), fitnesses.back());
  }
  std::printf("\n");
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? std::nan("") : v[v.size() / 2];
}

// Wall time (s) of one call of f() -> fitness, and that fitness.
template <class F>
std::pair<double, double> Timed(F&& f) {
  const auto t0 = Clock::now();
  const double fitness = f();
  return {std::chrono::duration<double>(Clock::now() - t0).count(), fitness};
}

// One gait episode six ways. The multi-process arena is timed as evolution uses it (processes
// already running, as in `ahhs-worker --arena-kind processes`); starting them and a whole
// `ahhs-launch` run are printed apart. All are timed in rounds, one after the other, and
// the ratios are taken within a round: this machine's speed drifts by tens of per cent over
// seconds, which would otherwise show up as a ratio.
void BenchArena(const std::string& url, std::uint64_t seed, int repeats) {
  namespace as = ahhs::sim;
  namespace ep = ahhs::episode;
  as::ScenarioConfig config;  // gait, 5 modules, damped, 60 s at 20 Hz
  am::Rng rng(seed);
  const am::Genome genome = am::RandomGenome({am::Variant::kAhhs2, 5, 30, 4, 1}, rng);
  auto physics_only = [&] {
    auto sim = as::MakeScenario(config);
    sim->Reset(seed);
    double a[1];
    while (true) {
      for (int c = 0; c < sim->num_compartments(); ++c) {
        as::DriveCommand(as::DriveKind::kWave, *sim, c, a);
        sim->SetActuators(c, a);
      }
      if (sim->Step() != as::StepStatus::kRunning) break;
    }
    return sim->Fitness();
  };
  ep::EpisodeSpec spec;
  spec.config = config;
  spec.genome = genome;
  spec.seed = seed;
  // The same episode's physics without controllers: the hinge commands the controllers gave,
  // recorded once from the loop without a bus, are replayed tick by tick.
  std::vector<std::vector<double>> commands;  // [tick][compartment * actuators + a]
  ep::RunDirectEpisode(spec, [&](const ep::DirectTick& t) {
    std::vector<double> row;
    for (int c = 0; c < t.scenario->num_compartments(); ++c) {
      const auto& a = t.organism->state(c).actuators;
      row.insert(row.end(), a.begin(), a.end());
    }
    commands.push_back(std::move(row));
  });
  auto physics_replay = [&] {
    auto sim = as::MakeScenario(config);
    sim->Reset(seed);
    const int na = sim->num_actuators();
    for (const auto& row : commands) {
      for (int c = 0; c < sim->num_compartments(); ++c)
        sim->SetActuators(c, row.data() + static_cast<std::ptrdiff_t>(c * na));
      if (sim->Step() != as::StepStatus::kRunning) break;
    }
    return sim->Fitness();
  };

  // One way of running the episode: its wall times and the last fitness it gave.
  struct Way {
    std::vector<double> seconds;
    double fitness = std::nan("");
    void Add(std::pair<double, double> timed) {
      seconds.push_back(timed.first);
      fitness = timed.second;
    }
    double median() const { return Median(seconds); }
  };
  // Ratios are taken within a round (this VM's speed drifts), then the median over the rounds.
  struct Ratio {
    std::vector<double> values;
    void Add(const Way& a, const Way& b) { values.push_back(a.seconds.back() / b.seconds.back()); }
    double median() const { return Median(values); }
  };
  Way physics, replay, direct, fused, memq, warm, viewed;
  Ratio fused_ratio, fused_replay_ratio, memq_ratio, memq_replay_ratio, warm_ratio, viewed_ratio;
  // Every fitness any run gave: one value, or the arenas disagree (a bug, not noise).
  std::set<double> fitnesses;
  ep::EpisodeSpec memq_spec = spec;
  memq_spec.fused_url = "memq://";
  double start_s = std::nan("");
  std::string failure;
  std::unique_ptr<ep::ProcessArena> processes;
  const std::string options_arena = "AHHSBENCH" + std::to_string(getpid());
  try {  // sim, 5 modules and the fitness monitor as long-lived processes
    const auto t0 = Clock::now();
    ep::ProcessArenaOptions options;
    options.url = url;
    options.arena = options_arena;
    options.num_modules = config.num_modules;
    processes = std::make_unique<ep::ProcessArena>(options);
    start_s = std::chrono::duration<double>(Clock::now() - t0).count();
  } catch (const std::exception& e) {
    failure = e.what();
  }
  for (int r = 0; r < repeats; ++r) {
    physics.Add(Timed(physics_only));
    replay.Add(Timed(physics_replay));
    direct.Add(Timed([&] { return ep::RunDirect(spec); }));
    fused.Add(Timed([&] { return ep::RunFused(spec).fitness; }));
    memq.Add(Timed([&] { return ep::RunFused(memq_spec).fitness; }));
    fused_ratio.Add(fused, direct);
    fused_replay_ratio.Add(fused, replay);
    memq_ratio.Add(memq, direct);
    memq_replay_ratio.Add(memq, replay);
    fitnesses.insert({replay.fitness, direct.fitness, fused.fitness, memq.fitness});
    if (processes && failure.empty()) {
      warm.Add(Timed([&] {
        ep::EpisodeSpec next = spec;
        next.episode = r + 1;  // every episode on the bus has its own id
        const auto result = processes->Run(next, [](std::string*) { return true; });
        if (!result.ok) failure = result.error;
        return result.ok ? result.fitness : std::nan("");
      }));
      warm_ratio.Add(warm, fused);
      if (!std::isnan(warm.fitness)) fitnesses.insert(warm.fitness);
      // The same with ahhs-view following the arena (no page attached: the viewer's own cost,
      // receiving the arena's states, fitness and clock and turning them into view events).
      std::vector<pid_t> viewer{
          ahhs::base::SpawnChild({ahhs::base::ExecutableDir() + "/ahhs-view", "--lcm-url", url,
                                  "--arena", options_arena, "--port", "0"},
                                 true)};
      std::this_thread::sleep_for(std::chrono::milliseconds(500));  // subscribed
      viewed.Add(Timed([&] {
        ep::EpisodeSpec next = spec;
        next.episode = 1000 + r;
        const auto result = processes->Run(next, [](std::string*) { return true; });
        if (!result.ok) failure = result.error;
        return result.ok ? result.fitness : std::nan("");
      }));
      ahhs::base::StopChildren(&viewer, std::chrono::seconds(2));
      viewed_ratio.Add(viewed, warm);
      if (!std::isnan(viewed.fitness)) fitnesses.insert(viewed.fitness);
    }
  }
  processes.reset();
  // Multi-process, cold: one whole ahhs-launch run (process start, handshake, episode, exit).
  const ahhs::base::TempDir scratch("ahhs-bench-");
  const std::string path = scratch.path() + "/genome.json";
  am::SaveGenomeFile(path, genome);
  const std::string out = scratch.path() + "/launch.out";
  const std::string cmd = ahhs::base::ExecutableDir() + "/ahhs-launch --scenario gait --genome " +
                          path + " --seed " + std::to_string(seed) + " --lcm-url '" + url + "' > " +
                          out + " 2>/dev/null";
  const auto cold = Timed([&] {
    if (std::system(cmd.c_str()) != 0) return std::nan("");
    std::ifstream in(out);
    std::string line, last;
    while (std::getline(in, line)) last = line;
    return last.rfind("fitness: ", 0) == 0 ? std::stod(last.substr(9)) : std::nan("");
  });
  std::printf(
      "gait, 5 modules, damped, 60 s at 20 Hz, AHHS2 5 hormones x 30 rules, seed %llu, median "
      "of %d rounds\n",
      static_cast<unsigned long long>(seed), repeats);
  std::printf("  physics only (wave drive)      %7.3f s   (another trajectory)\n",
              physics.median());
  std::printf("  physics only (same episode)    %7.3f s   fitness %.17g   (recorded commands)\n",
              replay.median(), replay.fitness);
  std::printf("  physics + controllers, no bus  %7.3f s   fitness %.17g\n", direct.median(),
              direct.fitness);
  std::printf(
      "  fused arena (inproc://)        %7.3f s   fitness %.17g   %.2fx physics+controllers, "
      "%.2fx physics only\n",
      fused.median(), fused.fitness, fused_ratio.median(), fused_replay_ratio.median());
  std::printf(
      "  fused arena on LCM's memq://   %7.3f s   fitness %.17g   %.2fx physics+controllers, "
      "%.2fx physics only\n",
      memq.median(), memq.fitness, memq_ratio.median(), memq_replay_ratio.median());
  std::printf("  multi-process arena (udpm)     %7.3f s   fitness %.17g   %.2fx fused\n",
              warm.median(), warm.fitness, warm_ratio.median());
  std::printf("    (starting its 7 processes    %7.3f s, once per arena)\n", start_s);
  std::printf("  the same, watched by ahhs-view %7.3f s   fitness %.17g   %.3fx unwatched\n",
              viewed.median(), viewed.fitness, viewed_ratio.median());
  std::printf("  ahhs-launch, whole run         %7.3f s   fitness %.17g   %.2fx fused\n",
              cold.first, cold.second, cold.first / fused.median());
  if (!std::isnan(cold.second)) fitnesses.insert(cold.second);
  if (fitnesses.size() == 1) {
    std::printf("  every run gave the same fitness to the bit\n");
  } else {
    std::printf("  WARNING: the runs gave %zu different fitness values:", fitnesses.size());
    for (double f : fitnesses) std::printf(" %.17g", f);
    std::printf("\n");
  }
  if (!failure.empty() || std::isnan(cold.second))
    std::printf(
        "  (a multi-process run failed%s%s: run under tools/ahhs-netns, or give --lcm-url)\n",
        failure.empty() ? "" : ": ", failure.c_str());
}

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

int main(int argc, char** argv) {
  CLI::App app{"ahhs-bench: speed figures (see docs/performance.md)"};
  app.require_subcommand(1);
  auto* controller = app.add_subcommand("controller", "one compartment tick of the hormone system");
  long ticks = 2000000;
  int repeats = 7;
  std::uint64_t seed = 1;
  controller->add_option("--ticks", ticks, "ticks per repeat")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  controller->add_option("--repeats", repeats, "repeats (the median is reported)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  controller->add_option("--seed", seed, "genome seed")
      ->check(ahhs::modules::SeedTextError)
      ->capture_default_str();
  std::string only;
  controller->add_option("--only", only, "run only the cases whose name contains this text");
  auto* sim = app.add_subcommand("sim", "physics-only episodes with built-in drives");
  int sim_repeats = 5;
  sim->add_option("--repeats", sim_repeats, "repeats (the median is reported)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  sim->add_option("--seed", seed, "first episode seed")
      ->check(ahhs::modules::SeedTextError)
      ->capture_default_str();
  int sim_seeds = 1;
  sim->add_option("--seeds", sim_seeds,
                  "seeds seed, seed+1, ... (the median over them is reported)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  std::string solver = "chain";
  sim->add_option("--solver", solver,
                  "the gait's solver: chain (this build's physics, sim/core/chain_step.h) or ode "
                  "(ODE's dWorldStep, the same model, the physics of 2026-12-01)")
      ->check(CLI::IsMember({"ode", "chain"}))
      ->capture_default_str();
  auto* arena =
      app.add_subcommand("arena", "one gait episode: physics only, fused and multi-process arenas");
  std::string arena_url = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";
  arena->add_option("--lcm-url", arena_url, "URL for the multi-process arena")
      ->capture_default_str();
  arena->add_option("--seed", seed, "genome and episode seed")
      ->check(ahhs::modules::SeedTextError)
      ->capture_default_str();
  int arena_repeats = 3;
  arena->add_option("--repeats", arena_repeats, "repeats of each (the median is reported)")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  auto* evolve = app.add_subcommand(
      "evolve", "whole evolution runs at the paper's scale through ahhs-evolve (minutes)");
  std::string evolve_task = "all",
              evolve_url = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";
  int evolve_generations = 200, evolve_workers = -1, evolve_trials = 1;
  std::string evolve_envelope = "none";
  evolve->add_option("--task", evolve_task,
                     "pendulum, gait-damped, gait-fixed, all, or main-job (the README's: ahhs-evolve "
                     "with neither --config nor --scenario, its post-evaluation included; "
                     "--trials and --envelope do not apply)")
      ->check(CLI::IsMember({"pendulum", "gait-damped", "gait-fixed", "all", "main-job"}))
      ->capture_default_str();
  evolve->add_option("--generations", evolve_generations, "generations per run (paper: 200)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  evolve->add_option("--workers", evolve_workers, "local workers (default: one per core)");
  evolve->add_option("--trials", evolve_trials, "episodes per individual (robust evolution)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  evolve->add_option("--envelope", evolve_envelope, "envelope of noise: none, paper or wide")
      ->check(CLI::IsMember({"none", "paper", "wide"}))
      ->capture_default_str();
  evolve->add_option("--lcm-url", evolve_url, "LCM URL of the farm")->capture_default_str();
  if (const int code = ahhs::cli::Parse(app, argc, argv); code >= 0) return code;

  if (evolve->parsed()) {
    std::printf("evolution runs through ahhs-evolve, %s workers, seed 1\n",
                evolve_workers < 0 ? "one per core" : std::to_string(evolve_workers).c_str());
    const std::string common =
        " --seed 1 --trials " + std::to_string(evolve_trials) + " --envelope " + evolve_envelope;
    if (evolve_trials > 1 || evolve_envelope != "none")
      std::printf("robust: %d trials per individual, envelope %s\n", evolve_trials,
                  evolve_envelope.c_str());
    if (evolve_task == "main-job")
      BenchEvolve("the README's main job (robust damped)", "--seed 1", evolve_generations,
                  evolve_url, evolve_workers);
    if (evolve_task == "pendulum" || evolve_task == "all")
      BenchEvolve(
          "pendulum AHHS2 15 H x 15 R, pop 200",
          "--scenario pendulum --variant ahhs2 --hormones 15 --rules 15 --population 200" + common,
          evolve_generations, evolve_url, evolve_workers);
    if (evolve_task == "pendulum" || evolve_task == "all")
      BenchEvolve(
          "pendulum AHHS1 15 H x 60 R, pop 200",
          "--scenario pendulum --variant ahhs1 --hormones 15 --rules 60 --population 200" + common,
          evolve_generations, evolve_url, evolve_workers);
    for (const char* joints : {"damped", "fixed"})
      if (evolve_task == "all" || evolve_task == std::string("gait-") + joints)
        BenchEvolve(std::string("gait ") + joints + " AHHS2 5 H x 30 R, pop 20",
                    std::string("--scenario gait --joints ") + joints +
                        " --variant ahhs2 --hormones 5 --rules 30 --population 20" + common,
                    evolve_generations, evolve_url, evolve_workers);
  }
  if (arena->parsed()) BenchArena(arena_url, seed, arena_repeats);
  if (sim->parsed()) {
    namespace as = ahhs::sim;
    std::printf(
        "physics-only episodes, median of %d runs per seed, seeds %llu-%llu, %s solver\n",
        sim_repeats, static_cast<unsigned long long>(seed),
        static_cast<unsigned long long>(seed) + static_cast<unsigned long long>(sim_seeds) - 1,
        solver.c_str());
    for (const char* drive : {"wave", "zero"}) {
      for (as::Joints joints : {as::Joints::kDamped, as::Joints::kFixed}) {
        as::ScenarioConfig gait;
        gait.joints = joints;
        BenchSim(gait, drive, sim_repeats, seed, sim_seeds, solver == "chain");
      }
    }
    as::ScenarioConfig pendulum;
    pendulum.kind = as::ScenarioKind::kPendulum;
    BenchSim(pendulum, "wave", sim_repeats, seed, sim_seeds, false);
  }

  if (controller->parsed()) {
    const ControllerCase cases[] = {
        {"gait AHHS2 5 H x 30 R", {am::Variant::kAhhs2, 5, 30, 4, 1}},
        {"gait AHHS1 5 H x 120 R", {am::Variant::kAhhs1, 5, 120, 4, 1}},
        {"pendulum AHHS2 15 H x 15 R", {am::Variant::kAhhs2, 15, 15, 10, 2}},
        {"pendulum AHHS1 15 H x 60 R", {am::Variant::kAhhs1, 15, 60, 10, 2}},
    };
    std::printf("controller tick (receive one packet + step), %ld ticks x %d repeats, seed %llu\n",
                ticks, repeats, static_cast<unsigned long long>(seed));
    for (bool smooth : {true, false})
      for (const auto& c : cases)
        if (std::string(c.name).find(only) != std::string::npos)
          BenchController(c, smooth, ticks, repeats, seed);
  }
  return 0;
}
