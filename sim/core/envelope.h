// An envelope of noise (Jakobi, "noise and the reality gap"): every episode perturbs the scenario
// by factors drawn from its seed, so a controller that scores well scores across the envelope, not
// on one trajectory that deterministic chaos favoured (docs/scenarios.md, "Envelope of noise").
// The draws are a pure function of (envelope, seed, modules), from a stream of their own: the
// same in every arena. An envelope of zeros is exactly the scenario without one, bit for bit.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ahhs::sim {

// Half-widths of uniform perturbations; 0 = none. Scale factors are 1 + U(-w, w).
struct Envelope {
  // The gait.
  double friction = 0;       // every contact's friction coefficient, one factor per episode
  double mass = 0;           // each module's mass, one factor per module
  double servo_torque = 0;   // each module's servo torque limit, one factor per module
  double servo_speed = 0;    // each module's servo speed limit, one factor per module
  double start_heading = 0;  // rad: the chain's heading at the start, U(-w, w)
  double start_offset = 0;   // m: the chain's start position, U(-w, w) along x and along y
  double sensor_noise = 0;   // added to every proximity reading, U(-w, w), then clamped to [0, 1]
  double command_delay = 0;  // ticks, below 1: each module's new target waits a whole number of
                             // physics steps, U{0 .. floor(w x steps per tick)}, every tick
  double start_hinge = 0;    // rad: each module's hinge angle at the start, U(-w, w)
  // The pendulum (its sensor noise is the scenario's own, +-2.3 %, with or without an envelope).
  double start_angle = 0;  // rad: the bob starts U(-w, w) away from hanging straight down
  double cart_speed = 0;   // the cart's top speed (the sensors keep their nominal scale)

  bool operator==(const Envelope& o) const;
  bool operator!=(const Envelope& o) const { return !(*this == o); }
  bool none() const { return *this == Envelope{}; }
};

// One episode's draws. With a zero half-width the factor is exactly 1 and the offset exactly 0.
struct EnvelopeDraw {
  double friction_scale = 1;
  std::vector<double> mass_scale, torque_scale, speed_scale;  // one per module
  double heading = 0, offset_x = 0, offset_y = 0;
  std::vector<double> hinge;  // one start angle per module, rad
  double start_angle = 0;     // pendulum
  double cart_speed_scale = 1;
};

// Every factor is drawn whatever the half-widths (a zero one is multiplied away), in a fixed
// order, so giving one key a width never changes another key's draw. Keys added later draw after
// all earlier ones, so that the earlier draws of a seed stay what they were.
EnvelopeDraw DrawEnvelope(const Envelope& envelope, std::uint64_t seed, int modules);

// The seed of the episode's sensor-noise stream (independent of the envelope's draws and of
// ODE's solver seed).
std::uint64_t SensorNoiseSeed(std::uint64_t seed);

// How many physics steps a module's new target waits at a tick: uniform on 0 .. most, a pure
// function of (seed, tick, module), from a stream of its own.
int CommandDelaySteps(std::uint64_t seed, std::int64_t tick, int module, int most);

// Presets: "none", "paper" (the paper's 2.3 % sensor noise, +-5 % physics, a few degrees and
// millimetres of start pose), "wide" (twice "paper"). Throws std::invalid_argument otherwise.
Envelope EnvelopePreset(const std::string& name);
// "PRESET[,KEY=W...]": a preset with single keys on top, KEY as in a run config's envelope table
// ("paper,command-delay=0.5"). Throws std::invalid_argument naming what is wrong, a bad width
// included (CheckEnvelope).
Envelope ParseEnvelopeSpec(const std::string& spec);
// The preset an envelope equals, or "custom".
std::string EnvelopeName(const Envelope& envelope);
// Checks every half-width (finite, >= 0, below what would make a scale factor reach 0, a pose
// beyond a quarter turn or a start offset beyond 0.1 m); returns "" or the bad key.
std::string CheckEnvelope(const Envelope& envelope);

// The named keys, for options and configs: "envelope.friction", ... in this order.
struct EnvelopeKey {
  const char* name;
  double Envelope::*field;
  const char* help;
  // A key added after runs were stored is written (configs, summaries, the service's hello) only
  // when it is not 0, so that what those runs stored stays what a new build writes for them.
  bool written_when_zero = true;
  bool Written(const Envelope& e) const { return written_when_zero || e.*field != 0; }
};
const std::vector<EnvelopeKey>& EnvelopeKeys();

}  // namespace ahhs::sim
