#include "episode/arena/episode.h"

namespace ahhs::episode {

std::string CheckGenomeFits(const modules::Genome& g, const sim::ScenarioConfig& config) {
  const sim::ScenarioShape probe = sim::ShapeOf(config);
  if (g.num_sensors != probe.sensors || g.num_actuators != probe.actuators) {
    return "the genome has " + std::to_string(g.num_sensors) + " sensors and " +
           std::to_string(g.num_actuators) + " actuators, but the " +
           sim::ScenarioName(config.kind) + " scenario gives each module " +
           std::to_string(probe.sensors) + " sensors and " + std::to_string(probe.actuators) +
           " actuators (make one with: ahhs-genome random --sensors " +
           std::to_string(probe.sensors) + " --actuators " + std::to_string(probe.actuators) +
           " ...)";
  }
  return "";
}

}  // namespace ahhs::episode
