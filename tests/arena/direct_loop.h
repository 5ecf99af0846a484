// The reference loop of an arena: scenario and organism stepped directly, no bus.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "modules/core/organism.h"
#include "sim/core/scenario.h"

namespace ahhs::testing {

struct Episode {
  std::string scenario;
  int modules;
  double duration;
  std::int64_t seed;
};

inline sim::ScenarioConfig ConfigOf(const Episode& e) {
  sim::ScenarioConfig c;
  c.kind = sim::ParseScenarioKind(e.scenario);
  c.num_modules = e.modules;
  c.duration = e.duration;
  return c;
}

// The reference: scenario and organism stepped directly.
inline double DirectFitness(const Episode& e, const modules::Genome& genome) {
  auto scenario = sim::MakeScenario(ConfigOf(e));
  scenario->Reset(static_cast<std::uint64_t>(e.seed));
  const int n = scenario->num_compartments();
  std::vector<std::vector<int>> links(static_cast<std::size_t>(n));
  for (auto [a, b] : scenario->Docking()) {
    links[static_cast<std::size_t>(a)].push_back(b);
    links[static_cast<std::size_t>(b)].push_back(a);
  }
  const modules::Controller controller(genome);
  modules::Organism organism(controller, links);
  const auto ns = static_cast<std::size_t>(scenario->num_sensors());
  const auto na = static_cast<std::size_t>(scenario->num_actuators());
  std::vector<std::vector<double>> sensors(static_cast<std::size_t>(n), std::vector<double>(ns));
  std::vector<std::unique_ptr<bool[]>> smask, amask;
  std::vector<modules::TickInput> inputs(static_cast<std::size_t>(n));
  for (int c = 0; c < n; ++c) {
    smask.emplace_back(new bool[ns]);
    amask.emplace_back(new bool[na]);
    for (std::size_t j = 0; j < ns; ++j)
      smask.back()[j] = scenario->sensor_owned(c, static_cast<int>(j));
    for (std::size_t a = 0; a < na; ++a)
      amask.back()[a] = scenario->actuator_owned(c, static_cast<int>(a));
  }
  while (true) {
    for (int c = 0; c < n; ++c) {
      const auto i = static_cast<std::size_t>(c);
      scenario->ReadSensors(c, sensors[i].data());
      inputs[i] = {sensors[i].data(), smask[i].get(), amask[i].get(), 0};
    }
    organism.Step(inputs);
    for (int c = 0; c < n; ++c) scenario->SetActuators(c, organism.state(c).actuators.data());
    if (scenario->Step() != sim::StepStatus::kRunning) break;
  }
  return scenario->Fitness();
}

}  // namespace ahhs::testing
