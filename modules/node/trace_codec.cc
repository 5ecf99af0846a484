#include "modules/node/trace_codec.h"

namespace ahhs::modules {

module_trace_t TraceMessage(const CompartmentState& state, const std::vector<double>& sensors,
                            const std::vector<bool>& present, std::int64_t episode,
                            std::int64_t tick, int module, double hinge_angle,
                            std::vector<std::uint64_t>* previous_activity) {
  module_trace_t m{};
  m.episode = episode;
  m.tick = tick;
  m.module = module;
  m.num_sensors = static_cast<std::int16_t>(sensors.size());
  m.sensors = sensors;
  m.sensor_present.assign(present.begin(), present.end());
  m.num_hormones = static_cast<std::int16_t>(state.hormones.size());
  m.hormones.assign(state.hormones.data(), state.hormones.data() + state.hormones.size());
  m.num_actuators = static_cast<std::int16_t>(state.actuators.size());
  m.actuators.assign(state.actuators.data(), state.actuators.data() + state.actuators.size());
  m.hinge_angle = hinge_angle;
  m.num_rules = static_cast<std::int16_t>(state.rule_activity.size());
  previous_activity->resize(state.rule_activity.size(), 0);
  for (std::size_t r = 0; r < state.rule_activity.size(); ++r) {
    m.rule_active.push_back(state.rule_activity[r] != (*previous_activity)[r] ? 1 : 0);
    (*previous_activity)[r] = state.rule_activity[r];
  }
  return m;
}

}  // namespace ahhs::modules
