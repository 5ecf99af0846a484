// What ahhs-view sends its page (docs/viewer.md): arena messages as JSON events, and whole
// recorded episodes. Pure translation, no bus, no server.
//
// Live events (one per message, each with "type"):
//   scene    {episode, tick, bodies: {module[], shape[], size[3n], pose[7n]}}   static bodies
//   state    {episode, tick, time, bodies: {...}}                 the moving bodies after a tick
//   module   {module, tick, s[], sp[], h[], a[], g}               a module's SENSORS, HINGE or
//            TRACE (fields present as the message has them: s sensors, sp which are its own,
//            h hormones, a actuators, g hinge angle in rad)
//   fitness  {episode, tick, time, fitness, final, ok, message}
//   clock    {episode, tick, time, state}                         state: reset|running|...
// A recording is one episode of a log: {type: "recording", arena, episode, period, scene,
// bodies (module/shape/size of the moving bodies), frames: [{tick, time, pose[7n], fitness,
// mods: [{s, sp, h, a, g} | null per module]}], final: {fitness, ok, message} | null}.
#pragma once

#include <ahhs/fitness_t.hpp>
#include <ahhs/hinge_command_t.hpp>
#include <ahhs/module_sensors_t.hpp>
#include <ahhs/module_trace_t.hpp>
#include <ahhs/sim_clock_t.hpp>
#include <ahhs/sim_state_t.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace ahhs::view {

using Json = nlohmann::json;

// Values sent to the page keep 6 significant decimals (10 um, 1e-6 of a hormone): a third of
// the bytes of full doubles, and nothing a viewer can see.
double Round(double v);

Json SceneEvent(const sim_state_t& m);
Json StateEvent(const sim_state_t& m);
Json SensorsEvent(const module_sensors_t& m);
Json HingeEvent(const hinge_command_t& m);
Json TraceEvent(const module_trace_t& m);
Json FitnessEvent(const fitness_t& m);
Json ClockEvent(const sim_clock_t& m);

// Which arena channel a name is, for one arena: kind and (for MODULE<i>/...) the module.
struct ArenaChannel {
  enum Kind { kOther, kState, kScene, kSensors, kHinge, kTrace, kFitness, kClock } kind = kOther;
  int module = -1;
};
ArenaChannel ClassifyChannel(const std::string& arena, const std::string& channel);

// The arena of a channel name "<ARENA>/SIM/STATE", or "" for any other channel.
std::string ArenaOfStateChannel(const std::string& channel);

// Builds recordings from a log's messages of one arena, in log order: every SIM/STATE starts a
// frame and takes the module messages seen since the previous one (the recorder writes a tick's
// SENSORS, HINGE and TRACE before its state), and a FITNESS goes to the frame of its tick.
// Messages that do not decode are counted, never fatal.
class RecordingBuilder {
 public:
  explicit RecordingBuilder(std::string arena) : arena_(std::move(arena)) {}
  void Add(const std::string& channel, const std::vector<std::uint8_t>& data);
  // One recording per episode that has at least one state, in order of first appearance.
  std::vector<Json> Finish();
  std::uint64_t undecodable() const { return undecodable_; }

 private:
  struct Episode {
    std::int64_t id = 0;
    double period = 0;
    Json scene;
    Json bodies;
    std::vector<Json> frames;
    std::map<std::int64_t, std::size_t> frame_of_tick;
    Json final_fitness;
  };
  Episode& EpisodeFor(std::int64_t id);
  std::string arena_;
  std::vector<Episode> episodes_;
  std::map<int, Json> pending_mods_;  // module -> what arrived since the last state
  std::uint64_t undecodable_ = 0;
};

// Reads the log at `path` (bus::LogReader; throws bus::LogFileError) and returns its recordings
// for `arena` ("" = the first arena with a SIM/STATE). Throws std::runtime_error "PATH: ..." when
// the log holds no SIM/STATE of that arena.
std::vector<Json> LoadRecordings(const std::string& path, std::string* arena);

}  // namespace ahhs::view
