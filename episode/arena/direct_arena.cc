#include "episode/arena/direct_arena.h"

#include <memory>

#include "episode/fitness/fitness_monitor.h"

namespace ahhs::episode {

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
  // The behaviour descriptor from the states the sim would publish, through the fitness
  // monitor, as the fused and process arenas have it: every arena kind gives the same bits. The
  // pendulum's needs every tick's state, the gait's the first and the last.
  const bool pendulum = spec.config.kind == sim::ScenarioKind::kPendulum;
  FitnessMonitor monitor(spec.config.kind, scenario->control_period(), scenario->total_ticks());
  std::vector<sim::BodyState> bodies;
  auto observe_state = [&] {
    scenario->Bodies(&bodies);
    monitor.Add(scenario->sim_time(), bodies);
  };
  observe_state();
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
      EpisodeResult failed = EpisodeResult::Failure(scenario->error());
      failed.episode_failed = true;
      return failed;
    }
    if (pendulum || status == sim::StepStatus::kFinished) observe_state();
    if (status == sim::StepStatus::kFinished) break;
  }
  EpisodeResult done;
  done.ok = true;
  done.fitness = scenario->Fitness();
  done.cost = scenario->Cost();
  done.descriptor = monitor.descriptor();
  return done;
}

double RunDirect(const EpisodeSpec& spec) { return RunDirectEpisode(spec).fitness; }

}  // namespace ahhs::episode
