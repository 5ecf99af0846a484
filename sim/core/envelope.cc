#include "sim/core/envelope.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "modules/core/random.h"

namespace ahhs::sim {

namespace {
// Stream ids under the episode seed (modules::DeriveSeed).
constexpr std::uint64_t kEnvelopeStream = 0x656e76656c6f7065;  // "envelope"
constexpr std::uint64_t kSensorNoiseStream = 0x73656e736f72;   // "sensor"
constexpr std::uint64_t kCommandDelayStream = 0x64656c6179;    // "delay"
}  // namespace

bool Envelope::operator==(const Envelope& o) const {
  for (const auto& k : EnvelopeKeys())
    if (this->*k.field != o.*k.field) return false;
  return true;
}

EnvelopeDraw DrawEnvelope(const Envelope& e, std::uint64_t seed, int modules) {
  modules::Rng rng(modules::DeriveSeed(seed, {kEnvelopeStream}));
  // Exactly 1 (or 0) for a zero width: never 1 + 0 * u computed in a way that could differ.
  auto scale = [&](double width) {
    const double u = rng.Uniform(-1.0, 1.0);
    return width > 0 ? 1.0 + width * u : 1.0;
  };
  auto offset = [&](double width) {
    const double u = rng.Uniform(-1.0, 1.0);
    return width > 0 ? width * u : 0.0;
  };
  EnvelopeDraw d;
  d.friction_scale = scale(e.friction);
  d.heading = offset(e.start_heading);
  d.offset_x = offset(e.start_offset);
  d.offset_y = offset(e.start_offset);
  d.start_angle = offset(e.start_angle);
  d.cart_speed_scale = scale(e.cart_speed);
  for (int m = 0; m < modules; ++m) {
    d.mass_scale.push_back(scale(e.mass));
    d.torque_scale.push_back(scale(e.servo_torque));
    d.speed_scale.push_back(scale(e.servo_speed));
  }
  for (int m = 0; m < modules; ++m) d.hinge.push_back(offset(e.start_hinge));
  return d;
}

std::uint64_t SensorNoiseSeed(std::uint64_t seed) {
  return modules::DeriveSeed(seed, {kSensorNoiseStream});
}

int CommandDelaySteps(std::uint64_t seed, std::int64_t tick, int module, int most) {
  if (most <= 0) return 0;
  const std::uint64_t h = modules::DeriveSeed(
      seed,
      {kCommandDelayStream, static_cast<std::uint64_t>(tick), static_cast<std::uint64_t>(module)});
  const double u = static_cast<double>(h >> 11) * 0x1.0p-53;  // [0, 1)
  return std::min(most, static_cast<int>(u * (most + 1)));
}

Envelope EnvelopePreset(const std::string& name) {
  Envelope e;
  if (name == "none") return e;
  double f = 0;
  if (name == "paper")
    f = 1;
  else if (name == "wide")
    f = 2;
  else
    throw std::invalid_argument("envelope: none, paper or wide, not '" + name + "'");
  e.friction = 0.05 * f;
  e.mass = 0.05 * f;
  e.servo_torque = 0.05 * f;
  e.servo_speed = 0.05 * f;
  e.start_heading = 0.05 * f;  // about 3 degrees
  e.start_offset = 0.005 * f;  // 5 mm
  e.sensor_noise = 0.023 * f;  // the paper's pendulum sensors
  e.start_angle = 0.05 * f;
  e.cart_speed = 0.05 * f;
  // command_delay and start_hinge stay 0 in every preset: the presets keep the meaning of the runs
  // made with them (docs/scenarios.md).
  return e;
}

Envelope ParseEnvelopeSpec(const std::string& spec) {
  const std::size_t comma = spec.find(',');
  Envelope e = EnvelopePreset(spec.substr(0, comma));
  for (std::size_t at = comma; at != std::string::npos;) {
    const std::size_t next = spec.find(',', at + 1);
    const std::string item = spec.substr(at + 1, next == std::string::npos ? next : next - at - 1);
    at = next;
    const std::size_t eq = item.find('=');
    const std::string name = "envelope." + item.substr(0, eq);
    const auto& keys = EnvelopeKeys();
    const auto key = std::find_if(keys.begin(), keys.end(),
                                  [&](const EnvelopeKey& k) { return name == k.name; });
    if (eq == std::string::npos || key == keys.end())
      throw std::invalid_argument("envelope: '" + item +
                                  "' is not KEY=W with a key such as friction");
    std::size_t used = 0;
    double w = 0;
    try {
      w = std::stod(item.substr(eq + 1), &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() - eq - 1)
      throw std::invalid_argument("envelope: '" + item + "' needs a number after '='");
    e.*key->field = w;
  }
  const std::string error = CheckEnvelope(e);
  if (!error.empty()) throw std::invalid_argument(error);
  return e;
}

std::string EnvelopeName(const Envelope& e) {
  for (const char* name : {"none", "paper", "wide"})
    if (e == EnvelopePreset(name)) return name;
  return "custom";
}

std::string CheckEnvelope(const Envelope& e) {
  for (const auto& k : EnvelopeKeys()) {
    const double w = e.*k.field;
    const std::string key = k.name;
    if (!std::isfinite(w) || w < 0) return key + ": a half-width of 0 or more";
    if (k.field == &Envelope::command_delay) {
      if (w >= 1) return key + ": below 1 tick";
      continue;
    }
    const bool scale = k.field != &Envelope::start_heading && k.field != &Envelope::start_offset &&
                       k.field != &Envelope::start_angle && k.field != &Envelope::start_hinge;
    if (scale && w >= 0.5) return key + ": below 0.5 (a factor from 1 - w to 1 + w)";
    if (!scale && k.field == &Envelope::start_offset && w > 0.1) return key + ": at most 0.1 m";
    if (!scale && k.field != &Envelope::start_offset && w > M_PI / 4)
      return key + ": at most pi/4 rad";
  }
  return "";
}

const std::vector<EnvelopeKey>& EnvelopeKeys() {
  static const std::vector<EnvelopeKey> keys = {
      {"envelope.friction", &Envelope::friction,
       "gait: friction coefficient x (1 + U(-w, w)), one factor per episode"},
      {"envelope.mass", &Envelope::mass, "gait: each module's mass x (1 + U(-w, w))"},
      {"envelope.servo-torque", &Envelope::servo_torque,
       "gait: each module's servo torque limit x (1 + U(-w, w))"},
      {"envelope.servo-speed", &Envelope::servo_speed,
       "gait: each module's servo speed limit x (1 + U(-w, w))"},
      {"envelope.start-heading", &Envelope::start_heading,
       "gait: the chain's start heading, U(-w, w) rad"},
      {"envelope.start-offset", &Envelope::start_offset,
       "gait: the chain's start position, U(-w, w) m along x and y"},
      {"envelope.sensor-noise", &Envelope::sensor_noise,
       "gait: U(-w, w) added to every proximity reading"},
      {"envelope.command-delay", &Envelope::command_delay,
       "gait: each new hinge target waits up to w ticks, in whole physics steps (w < 1)", false},
      {"envelope.start-hinge", &Envelope::start_hinge,
       "gait: each module's hinge angle at the start, U(-w, w) rad (the chain is put down bent)",
       false},
      {"envelope.start-angle", &Envelope::start_angle,
       "pendulum: the bob's start angle from hanging down, U(-w, w) rad"},
      {"envelope.cart-speed", &Envelope::cart_speed,
       "pendulum: the cart's top speed x (1 + U(-w, w))"},
  };
  return keys;
}

}  // namespace ahhs::sim
