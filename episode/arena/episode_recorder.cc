#include "episode/arena/episode_recorder.h"

#include <ahhs/fitness_t.hpp>
#include <ahhs/hinge_command_t.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <stdexcept>

#include "base/atomic_file.h"
#include "base/format.h"
#include "base/temp_files.h"
#include "bus/channels.h"
#include "bus/codec.h"
#include "bus/wire_text.h"
#include "modules/node/trace_codec.h"
#include "sim/core/gait.h"
#include "sim/core/pendulum.h"
#include "sim/node/sim_codec.h"

namespace ahhs::episode {

namespace fs = std::filesystem;

// Named, not anonymous: EpisodeRecorder::Files holds these, and a class with linkage must not
// hold a type of an anonymous namespace (GCC's -Wsubobject-linkage, in a unity build).
namespace recorder_files {

// An LCM log written to a temporary name and moved into place when complete.
class LogWriter {
 public:
  explicit LogWriter(const std::string& path) : path_(path), tmp_(base::CreateTempBeside(path)) {
    log_ = std::make_unique<lcm::LogFile>(tmp_, "w");
    if (!log_->good()) throw std::runtime_error("cannot write " + path);
  }
  template <class Msg>
  void Write(const std::string& channel, std::int64_t utime, const Msg& msg) {
    auto bytes = ahhs::bus::Encode(msg);
    if (bytes.empty())
      throw std::runtime_error("cannot write " + path_ + ": a " + channel +
                               " message is not encodable (a string is not wire text)");
    lcm::LogEvent e;
    e.eventnum = events_++;
    e.timestamp = utime;
    e.channel = channel;
    e.datalen = static_cast<std::int32_t>(bytes.size());
    e.data = bytes.data();
    if (log_->writeEvent(&e) != 0) throw std::runtime_error("cannot write " + path_);
  }
  void Commit() {
    log_.reset();
    fs::rename(tmp_, path_);
  }
  ~LogWriter() {
    if (log_) {
      log_.reset();
      std::error_code ignored;
      fs::remove(tmp_, ignored);
    }
  }

 private:
  std::string path_, tmp_;
  std::unique_ptr<lcm::LogFile> log_;
  std::int64_t events_ = 0;
};

using TextWriter = base::AtomicTextFile;

}  // namespace recorder_files
using recorder_files::LogWriter;
using recorder_files::TextWriter;

class EpisodeRecorder::Files {
 public:
  std::unique_ptr<LogWriter> log;
  std::unique_ptr<TextWriter> csv, body;
  std::string rules_csv;
  std::vector<sim::BodyState> bodies;
};

EpisodeRecorder::EpisodeRecorder(const EpisodeSpec& spec, const std::string& log_file,
                                 const std::string& csv_file, const std::string& rules_csv,
                                 const std::string& body_csv)
    : spec_(spec), files_(std::make_unique<Files>()) {
  if (!body_csv.empty()) {
    files_->body = std::make_unique<TextWriter>(body_csv);
    files_->body->out() << (spec.config.kind == sim::ScenarioKind::kPendulum
                                ? "tick,time,cart_x,pole_angle\n"
                                : "tick,time,centroid_x,centroid_y\n");
  }
  if (!log_file.empty()) files_->log = std::make_unique<LogWriter>(log_file);
  files_->rules_csv = rules_csv;
  if (!csv_file.empty()) {
    files_->csv = std::make_unique<TextWriter>(csv_file);
    auto& o = files_->csv->out();
    o << "tick,time,module,hinge_angle";
    for (int j = 0; j < spec.genome.num_sensors; ++j) o << ",s" << j;
    for (int h = 0; h < spec.genome.num_hormones(); ++h) o << ",h" << h;
    for (int a = 0; a < spec.genome.num_actuators; ++a) o << ",a" << a;
    o << ",rules_active\n";
  }
}

EpisodeRecorder::~EpisodeRecorder() = default;

void EpisodeRecorder::Observe(const DirectTick& t) {
  const auto& sc = *t.scenario;
  ticks_done_ = t.tick + 1;
  period_ = sc.control_period();
  const double time = static_cast<double>(t.tick + 1) * period_;
  const auto utime = static_cast<std::int64_t>(std::llround(time * 1e6));
  last_utime_ = utime;
  const int n = t.organism->size();
  last_activity_.resize(static_cast<std::size_t>(n));
  final_activity_.resize(static_cast<std::size_t>(n));
  const bus::ArenaChannels ch(spec_.arena);
  LogWriter* log = files_->log.get();
  if (log && sim::SceneDue(t.tick)) {  // the static bodies, as the sim sends them
    sc.Bodies(&files_->bodies);
    sim::KeepStaticBodies(&files_->bodies);
    const double start = static_cast<double>(t.tick) * period_;
    log->Write(ch.SimScene(), utime,
               sim::StateMessage(files_->bodies, spec_.episode, t.tick, start));
  }
  for (int c = 0; c < n; ++c) {
    const auto i = static_cast<std::size_t>(c);
    const auto& st = t.organism->state(c);
    final_activity_[i] = st.rule_activity;
    final_parts_.resize(static_cast<std::size_t>(n));
    final_parts_[i] = st.part_activity;
    const auto& s = (*t.sensors)[i];
    std::vector<bool> present;
    for (std::size_t j = 0; j < s.size(); ++j)
      present.push_back(sc.sensor_owned(c, static_cast<int>(j)));
    module_trace_t m = modules::TraceMessage(st, s, present, spec_.episode, t.tick, c,
                                             sc.HingeAngle(c), &last_activity_[i]);
    m.utime = utime;
    if (log) {
      module_sensors_t sensors = sim::SensorsMessage(sc, c, spec_.episode);
      sensors.utime = utime;
      sensors.tick = t.tick;
      sensors.values = s;
      log->Write(ch.Sensors(c), utime, sensors);
      hinge_command_t hinge;
      hinge.utime = utime;
      hinge.episode = spec_.episode;
      hinge.tick = t.tick;
      hinge.module = c;
      hinge.num_actuators = m.num_actuators;
      hinge.values = m.actuators;
      for (int a = 0; a < m.num_actuators; ++a) hinge.present.push_back(sc.actuator_owned(c, a));
      log->Write(ch.Hinge(c), utime, hinge);
      log->Write(ch.Trace(c), utime, m);
    }
    if (files_->csv) {
      int active = 0;
      for (auto fired : m.rule_active) active += fired;
      auto& o = files_->csv->out();
      o << t.tick << ',' << base::ExactDouble(time) << ',' << c << ','
        << base::ExactDouble(m.hinge_angle);
      for (double v : s) o << ',' << base::ExactDouble(v);
      for (double v : m.hormones) o << ',' << base::ExactDouble(v);
      for (double v : m.actuators) o << ',' << base::ExactDouble(v);
      o << ',' << active << '\n';
    }
  }
  if (files_->body) {
    auto& o = files_->body->out();
    o << t.tick << ',' << base::ExactDouble(time);
    if (const auto* p = dynamic_cast<const sim::PendulumScenario*>(&sc)) {
      o << ',' << base::ExactDouble(p->state().x) << ',' << base::ExactDouble(p->state().phi)
        << '\n';
    } else if (const auto* g = dynamic_cast<const sim::GaitScenario*>(&sc)) {
      const auto c = g->Centroid();
      o << ',' << base::ExactDouble(c[0]) << ',' << base::ExactDouble(c[1]) << '\n';
    }
  }
  if (log) {
    sc.Bodies(&files_->bodies);
    sim::KeepMovingBodies(&files_->bodies);
    log->Write(ch.SimState(), utime,
               sim::StateMessage(files_->bodies, spec_.episode, t.tick + 1, time));
    // The running fitness, as the live monitor reports it after every state (viewers show it).
    fitness_t f{};
    f.utime = utime;
    f.episode = spec_.episode;
    f.tick = t.tick + 1;
    f.sim_time = time;
    f.fitness = sc.Fitness();
    f.cost = sc.Cost();
    f.status = fitness_t::OK;
    f.states_seen = static_cast<std::int32_t>(t.tick + 1);
    log->Write(ch.Fitness(), utime, f);
  }
}

void EpisodeRecorder::Commit(const EpisodeResult& result) {
  if (files_->log) {
    fitness_t f{};
    f.episode = spec_.episode;
    f.is_final = true;
    f.status = result.ok ? fitness_t::OK : fitness_t::ERROR;
    // As the live monitor reports it: the last state's tick, every state seen.
    f.tick = ticks_done_;
    f.sim_time = static_cast<double>(ticks_done_) * period_;
    f.states_seen = static_cast<std::int32_t>(ticks_done_);
    f.states_missed = 0;
    f.fitness = result.ok ? result.fitness : 0;
    f.cost = result.cost;
    f.message = bus::ToWireText(result.error);
    f.utime = last_utime_;
    files_->log->Write(bus::ArenaChannels(spec_.arena).Fitness(), last_utime_, f);
    files_->log->Commit();
  }
  if (files_->csv) files_->csv->Commit();
  if (files_->body) files_->body->Commit();
  if (!files_->rules_csv.empty()) {
    TextWriter rules(files_->rules_csv);
    // Per rule: ticks in which any part triggered, then each part (AHHS1: its type's column).
    rules.out() << "module,rule,ticks_active,sensor,linear,nonlinear,actuator\n";
    for (std::size_t c = 0; c < final_activity_.size(); ++c)
      for (std::size_t r = 0; r < final_activity_[c].size(); ++r) {
        rules.out() << c << ',' << r << ',' << final_activity_[c][r];
        for (std::size_t k = 0; k < static_cast<std::size_t>(modules::kActivityColumns); ++k)
          rules.out()
              << ','
              << final_parts_[c][r * static_cast<std::size_t>(modules::kActivityColumns) + k];
        rules.out() << '\n';
      }
    rules.Commit();
  }
}

}  // namespace ahhs::episode
