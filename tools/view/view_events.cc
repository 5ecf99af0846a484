#include "tools/view/view_events.h"

#include <cctype>
#include <cmath>
#include <stdexcept>

#include "bus/codec.h"
#include "bus/log_reader.h"

namespace ahhs::view {

double Round(double v) {
  if (!std::isfinite(v) || v == 0) return std::isfinite(v) ? v : 0;
  const double scale = std::pow(10.0, 5 - std::floor(std::log10(std::fabs(v))));
  return std::round(v * scale) / scale;
}

namespace {

Json Numbers(const std::vector<double>& v) {
  Json a = Json::array();
  for (double x : v) a.push_back(Round(x));
  return a;
}

Json Bodies(const sim_state_t& m) {
  Json module = Json::array(), shape = Json::array(), size = Json::array(), pose = Json::array();
  for (std::size_t i = 0; i < static_cast<std::size_t>(m.num_bodies); ++i) {
    module.push_back(m.module[i]);
    shape.push_back(m.shape[i]);
    for (double v : {m.sx[i], m.sy[i], m.sz[i]}) size.push_back(Round(v));
    for (double v : {m.px[i], m.py[i], m.pz[i], m.qw[i], m.qx[i], m.qy[i], m.qz[i]})
      pose.push_back(Round(v));
  }
  return {{"module", module}, {"shape", shape}, {"size", size}, {"pose", pose}};
}

const char* RunState(std::int8_t s) {
  switch (s) {
    case sim_clock_t::RESET:
      return "reset";
    case sim_clock_t::RUNNING:
      return "running";
    case sim_clock_t::PAUSED:
      return "paused";
    case sim_clock_t::FINISHED:
      return "finished";
    case sim_clock_t::FAILED:
      return "failed";
    default:
      return "unknown";
  }
}

void Merge(Json* into, const Json& event) {
  for (const char* k : {"s", "sp", "h", "a", "g"})
    if (event.contains(k)) (*into)[k] = event[k];
}

}  // namespace

Json SceneEvent(const sim_state_t& m) {
  return {{"type", "scene"}, {"episode", m.episode}, {"tick", m.tick}, {"bodies", Bodies(m)}};
}

Json StateEvent(const sim_state_t& m) {
  return {{"type", "state"},
          {"episode", m.episode},
          {"tick", m.tick},
          {"time", Round(m.sim_time)},
          {"bodies", Bodies(m)}};
}

Json SensorsEvent(const module_sensors_t& m) {
  Json sp = Json::array();
  for (bool p : m.present) sp.push_back(p ? 1 : 0);
  return {{"type", "module"},       {"module", m.module}, {"tick", m.tick},
          {"s", Numbers(m.values)}, {"sp", sp},           {"g", Round(m.hinge_angle)}};
}

Json HingeEvent(const hinge_command_t& m) {
  return {{"type", "module"}, {"module", m.module}, {"tick", m.tick}, {"a", Numbers(m.values)}};
}

Json TraceEvent(const module_trace_t& m) {
  return {{"type", "module"},         {"module", m.module},       {"tick", m.tick},
          {"s", Numbers(m.sensors)},  {"h", Numbers(m.hormones)}, {"a", Numbers(m.actuators)},
          {"g", Round(m.hinge_angle)}};
}

Json FitnessEvent(const fitness_t& m) {
  return {{"type", "fitness"},
          {"episode", m.episode},
          {"tick", m.tick},
          {"time", Round(m.sim_time)},
          {"fitness", m.fitness},
          {"final", m.is_final},
          {"ok", m.status == fitness_t::OK},
          {"message", m.message}};
}

Json ClockEvent(const sim_clock_t& m) {
  return {
      {"type", "clock"},           {"episode", m.episode},       {"tick", m.tick},
      {"time", Round(m.sim_time)}, {"period", m.control_period}, {"state", RunState(m.run_state)}};
}

ArenaChannel ClassifyChannel(const std::string& arena, const std::string& channel) {
  ArenaChannel r;
  const std::string p = arena + "/";
  if (channel.compare(0, p.size(), p) != 0) return r;
  const std::string rest = channel.substr(p.size());
  if (rest == "SIM/STATE") r.kind = ArenaChannel::kState;
  if (rest == "SIM/SCENE") r.kind = ArenaChannel::kScene;
  if (rest == "SIM/CLOCK") r.kind = ArenaChannel::kClock;
  if (rest == "FITNESS") r.kind = ArenaChannel::kFitness;
  // MODULE<1-4 digits>/SENSORS|HINGE|TRACE
  const std::string m = "MODULE";
  if (rest.compare(0, m.size(), m) != 0) return r;
  std::size_t i = m.size();
  int module = 0, digits = 0;
  for (; i < rest.size() && std::isdigit(static_cast<unsigned char>(rest[i])) && digits < 5; ++i) {
    module = module * 10 + (rest[i] - '0');
    ++digits;
  }
  if (digits == 0 || digits > 4 || i >= rest.size() || rest[i] != '/') return r;
  const std::string what = rest.substr(i + 1);
  if (what == "SENSORS") r.kind = ArenaChannel::kSensors;
  if (what == "HINGE") r.kind = ArenaChannel::kHinge;
  if (what == "TRACE") r.kind = ArenaChannel::kTrace;
  if (r.kind != ArenaChannel::kOther) r.module = module;
  return r;
}

std::string ArenaOfStateChannel(const std::string& channel) {
  const std::string suffix = "/SIM/STATE";
  if (channel.size() <= suffix.size() ||
      channel.compare(channel.size() - suffix.size(), suffix.size(), suffix) != 0)
    return "";
  return channel.substr(0, channel.size() - suffix.size());
}

RecordingBuilder::Episode& RecordingBuilder::EpisodeFor(std::int64_t id) {
  for (auto& e : episodes_)
    if (e.id == id) return e;
  episodes_.emplace_back();
  episodes_.back().id = id;
  return episodes_.back();
}

void RecordingBuilder::Add(const std::string& channel, const std::vector<std::uint8_t>& data) {
  const ArenaChannel c = ClassifyChannel(arena_, channel);
  auto module_event = [&](const Json& e) { Merge(&pending_mods_[c.module], e); };
  switch (c.kind) {
    case ArenaChannel::kOther:
      return;
    case ArenaChannel::kState:
    case ArenaChannel::kScene: {
      sim_state_t m;
      if (!bus::Decode(data.data(), data.size(), &m)) break;
      Episode& e = EpisodeFor(m.episode);
      if (c.kind == ArenaChannel::kScene) {
        e.scene = SceneEvent(m);
        return;
      }
      Json b = Bodies(m);
      if (e.bodies.is_null())
        e.bodies = {{"module", b["module"]}, {"shape", b["shape"]}, {"size", b["size"]}};
      Json frame = {
          {"tick", m.tick}, {"time", Round(m.sim_time)}, {"pose", b["pose"]}, {"fitness", nullptr}};
      Json mods = Json::array();
      int n = 0;
      for (const auto& kv : pending_mods_) n = std::max(n, kv.first + 1);
      for (int i = 0; i < n; ++i) {
        auto it = pending_mods_.find(i);
        mods.push_back(it == pending_mods_.end() ? Json() : it->second);
      }
      pending_mods_.clear();
      frame["mods"] = mods;
      if (!e.frames.empty()) {
        const double dt = m.sim_time - e.frames.back()["time"].get<double>();
        if (e.period == 0 && dt > 0) e.period = Round(dt);
      }
      e.frame_of_tick[m.tick] = e.frames.size();
      e.frames.push_back(std::move(frame));
      return;
    }
    case ArenaChannel::kSensors: {
      module_sensors_t m;
      if (!bus::Decode(data.data(), data.size(), &m)) break;
      module_event(SensorsEvent(m));
      return;
    }
    case ArenaChannel::kHinge: {
      hinge_command_t m;
      if (!bus::Decode(data.data(), data.size(), &m)) break;
      module_event(HingeEvent(m));
      return;
    }
    case ArenaChannel::kTrace: {
      module_trace_t m;
      if (!bus::Decode(data.data(), data.size(), &m)) break;
      module_event(TraceEvent(m));
      return;
    }
    case ArenaChannel::kFitness: {
      fitness_t m;
      if (!bus::Decode(data.data(), data.size(), &m)) break;
      Episode& e = EpisodeFor(m.episode);
      if (m.is_final) {
        e.final_fitness = {
            {"fitness", m.fitness}, {"ok", m.status == fitness_t::OK}, {"message", m.message}};
      }
      if (m.status == fitness_t::OK) {
        auto it = e.frame_of_tick.find(m.tick);
        if (it != e.frame_of_tick.end()) e.frames[it->second]["fitness"] = m.fitness;
      }
      return;
    }
    case ArenaChannel::kClock:
      return;
  }
  ++undecodable_;
}

std::vector<Json> RecordingBuilder::Finish() {
  std::vector<Json> out;
  for (auto& e : episodes_) {
    if (e.frames.empty()) continue;
    Json r = {{"type", "recording"},     {"arena", arena_},  {"episode", e.id},
              {"period", e.period},      {"scene", e.scene}, {"bodies", e.bodies},
              {"final", e.final_fitness}};
    r["frames"] = std::move(e.frames);
    out.push_back(std::move(r));
  }
  episodes_.clear();
  return out;
}

std::vector<Json> LoadRecordings(const std::string& path, std::string* arena) {
  // Two passes would read a large log twice; instead keep the events of the first arena seen
  // until it is known (a state usually comes within the first tick).
  bus::LogReader reader(path);
  bus::LogEvent ev;
  std::vector<bus::LogEvent> before;
  std::unique_ptr<RecordingBuilder> builder;
  if (!arena->empty()) builder = std::make_unique<RecordingBuilder>(*arena);
  while (reader.Next(&ev)) {
    if (!builder) {
      const std::string a = ArenaOfStateChannel(ev.channel);
      if (a.empty()) {
        before.push_back(ev);
        continue;
      }
      *arena = a;
      builder = std::make_unique<RecordingBuilder>(a);
      for (const auto& b : before) builder->Add(b.channel, b.data);
      before.clear();
    }
    builder->Add(ev.channel, ev.data);
  }
  std::vector<Json> out;
  if (builder) out = builder->Finish();
  if (out.empty()) {
    throw std::runtime_error(path + ": an LCM log of " + std::to_string(reader.events_read()) +
                             " messages without any " +
                             (arena->empty() ? std::string("<ARENA>") : *arena) +
                             "/SIM/STATE: nothing to show");
  }
  return out;
}

}  // namespace ahhs::view
