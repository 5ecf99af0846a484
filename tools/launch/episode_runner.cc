#include "tools/launch/episode_runner.h"

#include <unistd.h>

#include <ahhs/fitness_t.hpp>
#include <ahhs/module_status_t.hpp>
#include <ahhs/sim_clock_t.hpp>
#include <ahhs/sim_control_t.hpp>
#include <memory>
#include <set>
#include <vector>

#include "bus/channels.h"
#include "bus/make_bus.h"
#include "bus/typed.h"
#include "evolver/fitness/fitness_node.h"
#include "modules/core/organism.h"
#include "modules/node/genome_codec.h"
#include "modules/node/module_node.h"
#include "sim/node/sim_node.h"

namespace ahhs::launch {

using Clock = std::chrono::steady_clock;

std::string CheckGenomeFits(const modules::Genome& g, const sim::ScenarioConfig& config) {
  auto probe = sim::MakeScenario(config);
  if (g.num_sensors != probe->num_sensors() || g.num_actuators != probe->num_actuators()) {
    return "the genome has " + std::to_string(g.num_sensors) + " sensors and " +
           std::to_string(g.num_actuators) + " actuators, but the " +
           sim::ScenarioName(config.kind) + " scenario gives each module " +
           std::to_string(probe->num_sensors()) + " sensors and " +
           std::to_string(probe->num_actuators()) +
           " actuators (make one with: ahhs-genome random --sensors " +
           std::to_string(probe->num_sensors()) + " --actuators " +
           std::to_string(probe->num_actuators()) + " ...)";
  }
  return "";
}

EpisodeResult RunEpisode(bus::Bus& bus, const EpisodeSpec& spec,
                         const std::function<void(std::chrono::microseconds)>& pump,
                         const std::function<bool(std::string*)>& alive) {
  EpisodeResult result;
  const bus::ArenaChannels ch(spec.arena);
  const int modules =
      spec.config.kind == sim::ScenarioKind::kPendulum ? 2 : spec.config.num_modules;
  std::set<int> ready;
  bool sim_ready = false, monitor_ready = false;
  std::optional<fitness_t> final_fitness;
  std::int8_t run_state = -1;
  const std::int64_t ep = spec.episode;
  std::vector<int> subs;
  auto on_status = [&](const std::string&, const module_status_t& s) {
    if (s.episode == ep &&
        (s.state == module_status_t::READY || s.state == module_status_t::RUNNING))
      ready.insert(s.module);
    if (s.episode == ep && s.state == module_status_t::ERROR && result.error.empty())
      result.error = "module " + std::to_string(s.module) + " refused the episode: " + s.message;
  };
  // One exact channel per module rather than a regex: over udpm:// the bus's socket filter then
  // keeps the per-tick traffic of the modules out of the launcher.
  for (int m = 0; m < modules; ++m)
    subs.push_back(bus::SubscribeTyped<module_status_t>(bus, ch.Status(m), on_status));
  subs.push_back(bus::SubscribeTyped<sim_clock_t>(bus, ch.SimClock(),
                                                  [&](const std::string&, const sim_clock_t& c) {
                                                    if (c.episode != ep) return;
                                                    run_state = c.run_state;
                                                    if (c.run_state == sim_clock_t::RESET)
                                                      sim_ready = true;
                                                  }));
  subs.push_back(bus::SubscribeTyped<fitness_t>(bus, ch.Fitness(),
                                                [&](const std::string&, const fitness_t& f) {
                                                  if (f.episode != ep) return;
                                                  monitor_ready = true;
                                                  if (f.is_final) final_fitness = f;
                                                }));
  auto finish = [&](EpisodeResult r) {
    for (int id : subs) bus.Unsubscribe(id);
    return r;
  };

  sim_control_t c{};
  c.episode = ep;
  c.seed = static_cast<std::int64_t>(spec.seed);  // LCM has no unsigned type: the same 64 bits
  c.scenario = sim::ScenarioName(spec.config.kind);
  c.num_modules = modules;
  c.joints = spec.config.joints == sim::Joints::kFixed ? sim_control_t::JOINTS_FIXED
                                                       : sim_control_t::JOINTS_DAMPED;
  c.duration = spec.config.duration;
  c.clock_mode = spec.realtime ? sim_control_t::MODE_REALTIME : sim_control_t::MODE_LOCKSTEP;
  const genome_t genome = modules::GenomeMessage(spec.genome, ep);

  // Handshake: RESET + GENOME, repeated until the sim, every module and the monitor answered.
  const auto handshake_start = Clock::now();
  const auto handshake_end = handshake_start + spec.handshake_timeout;
  auto next_send = Clock::now();
  std::string why;
  auto modules_ok = [&] {
    if (static_cast<int>(ready.size()) == modules) return true;
    return spec.realtime && !ready.empty() &&
           Clock::now() > handshake_start + spec.realtime_join_wait;
  };
  while (!(sim_ready && monitor_ready && modules_ok())) {
    if (!alive(&why)) return finish({false, 0, 0, why, 0});
    if (!result.error.empty()) return finish(result);
    if (Clock::now() > handshake_end) {
      std::string missing = sim_ready ? "" : " the sim,";
      if (!monitor_ready) missing += " the fitness monitor,";
      for (int m = 0; m < modules; ++m)
        if (!ready.count(m)) missing += " module " + std::to_string(m) + ",";
      missing.pop_back();
      return finish({false, 0, 0, "no answer to the episode handshake from" + missing, 0});
    }
    if (Clock::now() >= next_send) {
      c.command = sim_control_t::RESET;
      c.utime = bus::NowUtime();
      bus::PublishTyped(bus, ch.SimControl(), c);
      auto g = genome;
      g.utime = bus::NowUtime();
      bus::PublishTyped(bus, ch.Genome(), g);
      next_send = Clock::now() + std::chrono::milliseconds(50);
    }
    pump(std::chrono::milliseconds(5));
  }

  // START, repeated until the sim's clock shows the episode running (a lost START must not
  // leave everyone waiting; the sim ignores repeats).
  c.command = sim_control_t::START;
  const auto episode_end = Clock::now() + spec.episode_timeout;
  auto next_genome = Clock::now() + std::chrono::seconds(1);
  auto next_start = Clock::now();
  while (!final_fitness) {
    if (!alive(&why)) return finish({false, 0, 0, why, 0});
    if (run_state == sim_clock_t::RESET && Clock::now() >= next_start) {
      c.utime = bus::NowUtime();
      bus::PublishTyped(bus, ch.SimControl(), c);
      next_start = Clock::now() + std::chrono::milliseconds(100);
    }
    if (Clock::now() > episode_end)
      return finish({false, 0, 0, "the episode did not end in time", 0});
    if (spec.realtime && Clock::now() >= next_genome) {  // lets a module that starts late join
      auto g = genome;
      g.utime = bus::NowUtime();
      bus::PublishTyped(bus, ch.Genome(), g);
      next_genome = Clock::now() + std::chrono::seconds(1);
    }
    pump(std::chrono::milliseconds(20));
  }
  if (final_fitness->status != fitness_t::OK) {
    EpisodeResult failed{false, 0, 0, final_fitness->message, 0};
    failed.episode_failed = true;
    return finish(failed);
  }
  return finish(
      {true, final_fitness->fitness, final_fitness->cost, "", final_fitness->states_missed});
}

EpisodeResult RunFused(const EpisodeSpec& spec) {
  EpisodeResult refused;
  if (!bus::IsInProcessUrl(spec.fused_url)) {
    refused.error = "the fused arena runs on inproc:// or memq://, not on '" + spec.fused_url + "'";
    return refused;
  }
  std::unique_ptr<bus::Bus> bus_owner;
  try {
    bus_owner = bus::OpenBus(spec.fused_url);
  } catch (const bus::BusError& e) {
    refused.error = e.what();
    return refused;
  }
  bus::Bus& bus = *bus_owner;
  sim::SimNodeOptions sim_options;
  sim_options.arena = spec.arena;
  sim::SimNode sim_node(&bus, sim_options);
  evolver::FitnessNode fitness_node(&bus, spec.arena);
  std::vector<std::unique_ptr<modules::ModuleNode>> nodes;
  const int modules =
      spec.config.kind == sim::ScenarioKind::kPendulum ? 2 : spec.config.num_modules;
  for (int m = 0; m < modules; ++m) {
    modules::ModuleNodeOptions o;
    o.id = m;
    o.arena = spec.arena;
    nodes.push_back(std::make_unique<modules::ModuleNode>(&bus, o));
  }
  // One shared bus: one Handle() dispatches to every node, then each node acts on what it got.
  // Two rounds per call follow the lockstep (commands -> sim publishes SENSORS -> modules step
  // and publish HINGE and HORMONE); on memq:// a Handle per node would cost a syscall each.
  auto pump = [&](std::chrono::microseconds wait) {
    bus.Handle(std::chrono::microseconds(0));
    sim_node.Process();
    bus.Handle(std::chrono::microseconds(0));
    for (auto& n : nodes) n->Process();
    if (spec.realtime) bus.Handle(std::min(wait, std::chrono::microseconds(1000)));
  };
  return RunEpisode(bus, spec, pump, [](std::string*) { return true; });
}

EpisodeResult RunDirectEpisode(const EpisodeSpec& spec, const DirectObserver& observer) {
  auto scenario = sim::MakeScenario(spec.config);
  scenario->Reset(spec.seed);
  const int n = scenario->num_compartments();
  std::vector<std::vector<int>> links(static_cast<std::size_t>(n));
  for (auto [a, b] : scenario->Docking()) {
    links[static_cast<std::size_t>(a)].push_back(b);
    links[static_cast<std::size_t>(b)].push_back(a);
  }
  const modules::Controller controller(spec.genome);
  modules::Organism organism(controller, links);
  const auto ns = static_cast<std::size_t>(scenario->num_sensors());
  const auto na = static_cast<std::size_t>(scenario->num_actuators());
  std::vector<std::vector<double>> sensors(static_cast<std::size_t>(n), std::vector<double>(ns));
  std::vector<std::unique_ptr<bool[]>> sensor_masks, actuator_masks;
  std::vector<modules::TickInput> inputs(static_cast<std::size_t>(n));
  for (int c = 0; c < n; ++c) {
    sensor_masks.emplace_back(new bool[ns]);
    actuator_masks.emplace_back(new bool[na]);
    for (std::size_t j = 0; j < ns; ++j)
      sensor_masks.back()[j] = scenario->sensor_owned(c, static_cast<int>(j));
    for (std::size_t a = 0; a < na; ++a)
      actuator_masks.back()[a] = scenario->actuator_owned(c, static_cast<int>(a));
  }
  while (true) {
    for (int c = 0; c < n; ++c) {
      const auto i = static_cast<std::size_t>(c);
      scenario->ReadSensors(c, sensors[i].data());
      inputs[i] = {sensors[i].data(), sensor_masks[i].get(), actuator_masks[i].get(), 0};
    }
    organism.Step(inputs);
    for (int c = 0; c < n; ++c) scenario->SetActuators(c, organism.state(c).actuators.data());
    const sim::StepStatus status = scenario->Step();
    if (observer && status != sim::StepStatus::kFailed)
      observer({scenario->tick() - 1, scenario.get(), &organism, &sensors});
    if (status == sim::StepStatus::kFailed) {
      EpisodeResult failed{false, 0, 0, scenario->error(), 0};
      failed.episode_failed = true;
      return failed;
    }
    if (status == sim::StepStatus::kFinished) break;
  }
  return {true, scenario->Fitness(), scenario->Cost(), "", 0};
}

double RunDirect(const EpisodeSpec& spec) { return RunDirectEpisode(spec).fitness; }

std::string ExecutableDir() {
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return ".";
  const std::string path(buf, static_cast<std::size_t>(n));
  return path.substr(0, path.rfind('/'));
}

}  // namespace ahhs::launch
