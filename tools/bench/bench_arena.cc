#include "tools/bench/bench_arena.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <set>
#include <thread>
#include <vector>

#include "base/children.h"
#include "base/temp_files.h"
#include "episode/arena/direct_arena.h"
#include "episode/arena/episode.h"
#include "episode/arena/fused_arena.h"
#include "episode/arena/process_arena.h"
#include "modules/core/genome_json.h"
#include "modules/core/random.h"
#include "modules/core/variation.h"
#include "sim/core/drive.h"
#include "sim/core/scenario.h"

namespace cli = ahhs::base::cli;

namespace ahhs::bench {
namespace {
namespace am = ahhs::modules;
using Clock = std::chrono::steady_clock;

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

}  // namespace

cli::App* ArenaBench::Add(cli::App& app) {
  auto* sub =
      app.add_subcommand("arena", "one gait episode: physics only, fused and multi-process arenas");
  sub->add_option("--lcm-url", url, "URL for the multi-process arena")->capture_default_str();
  sub->add_option("--seed", seed, "genome and episode seed")
      ->check(am::SeedTextError)
      ->capture_default_str();
  sub->add_option("--repeats", repeats, "repeats of each (the median is reported)")
      ->check(cli::Range(1, 100))
      ->capture_default_str();
  return sub;
}

void ArenaBench::Run() const { BenchArena(url, seed, repeats); }

}  // namespace ahhs::bench
