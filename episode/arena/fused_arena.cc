#include "episode/arena/fused_arena.h"

#include <memory>
#include <vector>

#include "bus/open_bus.h"
#include "episode/arena/launcher_role.h"
#include "episode/fitness/fitness_node.h"
#include "modules/node/module_node.h"
#include "sim/node/sim_node.h"

namespace ahhs::episode {

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
  episode::FitnessNode fitness_node(&bus, spec.arena);
  std::vector<std::unique_ptr<modules::ModuleNode>> nodes;
  const int modules = sim::ShapeOf(spec.config).compartments;
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
    fitness_node.Maintain();
    if (spec.realtime) bus.Handle(std::min(wait, std::chrono::microseconds(1000)));
  };
  return RunEpisode(bus, spec, pump, [](std::string*) { return true; });
}

}  // namespace ahhs::episode
