#include "tools/bench/bench_controller.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "modules/core/hormone_system.h"
#include "modules/core/random.h"
#include "modules/core/variation.h"

namespace cli = ahhs::base::cli;

namespace ahhs::bench {
namespace {
namespace am = ahhs::modules;
using Clock = std::chrono::steady_clock;

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

}  // namespace

cli::App* ControllerBench::Add(cli::App& app) {
  auto* sub = app.add_subcommand("controller", "one compartment tick of the hormone system");
  sub->add_option("--ticks", ticks, "ticks per repeat")
      ->check(cli::PositiveNumber)
      ->capture_default_str();
  sub->add_option("--repeats", repeats, "repeats (the median is reported)")
      ->check(cli::Range(1, 1000))
      ->capture_default_str();
  sub->add_option("--seed", seed, "genome seed")->check(am::SeedTextError)->capture_default_str();
  sub->add_option("--only", only, "run only the cases whose name contains this text");
  return sub;
}

void ControllerBench::Run() const {
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

}  // namespace ahhs::bench
