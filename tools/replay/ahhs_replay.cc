// ahhs-replay: re-runs one genome as one episode with everything recorded (docs/analysis.md):
//   ahhs-replay RUN_DIR [--generation G [--individual I]]   a stored individual (default: the
//                                                          run's best), with its stored seed
//   ahhs-replay --genome FILE --scenario ... --seed S       any genome
// --log FILE writes an LCM log (per tick: every module's SENSORS, HINGE and TRACE, and
// SIM/STATE; FITNESS at the end); --csv FILE the same trace as CSV, --rules-csv FILE how often
// each rule triggered in each module. --mutants N evaluates N single mutants of the genome (the
// paper's mutation neighbourhood) into --mutants-csv FILE. The replay uses the workers' direct
// arena, so a stored fitness is reproduced to the bit; the output says so, or by how much not.
#include <CLI/CLI.hpp>
#include <ahhs/fitness_t.hpp>
#include <ahhs/hinge_command_t.hpp>
#include <ahhs/module_trace_t.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <optional>

#include "bus/channels.h"
#include "bus/cli.h"
#include "bus/codec.h"
#include "evolver/arena/direct_arena.h"
#include "evolver/arena/episode.h"
#include "evolver/evolve/evolution.h"
#include "evolver/store/run_store.h"
#include "modules/core/genome_json.h"
#include "modules/core/random.h"
#include "modules/core/variation.h"
#include "sim/core/behaviour.h"
#include "sim/node/sim_codec.h"

namespace fs = std::filesystem;
namespace al = ahhs::arena;
namespace am = ahhs::modules;
namespace ev = ahhs::evolver;

namespace {

// An LCM log written to a temporary name and moved into place when complete.
class LogWriter {
 public:
  explicit LogWriter(const std::string& path) : path_(path), tmp_(path + ".tmp") {
    log_ = std::make_unique<lcm::LogFile>(tmp_, "w");
    if (!log_->good()) throw std::runtime_error("cannot write " + path);
  }
  template <class Msg>
  void Write(const std::string& channel, std::int64_t utime, const Msg& msg) {
    auto bytes = ahhs::bus::Encode(msg);
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

// A text file written to a temporary name and moved into place when complete.
class TextWriter {
 public:
  explicit TextWriter(const std::string& path) : path_(path), out_(path + ".tmp") {
    if (!out_) throw std::runtime_error("cannot write " + path);
  }
  std::ofstream& out() { return out_; }
  void Commit() {
    out_.close();
    if (!out_) throw std::runtime_error("cannot write " + path_);
    fs::rename(path_ + ".tmp", path_);
    done_ = true;
  }
  ~TextWriter() {
    if (!done_) {
      out_.close();
      std::error_code ignored;
      fs::remove(path_ + ".tmp", ignored);
    }
  }

 private:
  std::string path_;
  std::ofstream out_;
  bool done_ = false;
};

std::string Exact(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"ahhs-replay: one episode of a stored or given genome, with everything recorded"};
  std::string run_dir, genome_file, log_file, csv_file, rules_csv, mutants_csv;
  std::string scenario = "gait", joints = "damped";
  int modules = 5, generation = -1, individual = -1, mutants = 0;
  double duration = 0;
  std::uint64_t seed = 1;
  std::uint64_t mutant_seed = 1;
  app.add_option("run", run_dir, "run directory of ahhs-evolve");
  app.add_option("--generation", generation, "generation (default: the run's best individual)");
  app.add_option("--individual", individual,
                 "individual of --generation (default: that generation's best)");
  app.add_option("--genome", genome_file, "a genome file instead of a run")
      ->check(CLI::ExistingFile);
  app.add_option("--scenario", scenario, "with --genome: gait or pendulum")
      ->check(CLI::IsMember({"gait", "pendulum"}))
      ->capture_default_str();
  app.add_option("--joints", joints, "with --genome: damped or fixed")
      ->check(CLI::IsMember({"damped", "fixed"}))
      ->capture_default_str();
  app.add_option("--modules", modules, "with --genome: gait modules")->capture_default_str();
  app.add_option("--duration", duration, "with --genome: simulated seconds (0: the task's)");
  app.add_option("--seed", seed,
                 "evaluation seed, 0 to 2^64-1 (default: the stored one: the run's, or the genome "
                 "file's; else 1)")
      ->check(am::SeedTextError);
  app.add_option("--log", log_file, "write the episode as an LCM log");
  app.add_option("--csv", csv_file, "write the per-tick trace as CSV");
  app.add_option("--rules-csv", rules_csv, "write how often each rule triggered, per module");
  app.add_option("--mutants", mutants, "evaluate this many single mutants of the genome")
      ->check(CLI::Range(0, 100000));
  app.add_option("--mutants-csv", mutants_csv, "where --mutants writes its results");
  bool overwrite = false;
  app.add_flag("--overwrite", overwrite, "replace output files that exist");
  app.add_option("--mutant-seed", mutant_seed, "seed of the mutations")
      ->check(am::SeedTextError)
      ->capture_default_str();
  std::string mutation_profile;
  app.add_option("--mutation-profile", mutation_profile,
                 "operator of the mutants: paper or fine-doses (default: the run's, else paper)")
      ->check(CLI::IsMember({"paper", "fine-doses"}));
  if (const int code = ahhs::cli::Parse(app, argc, argv); code >= 0) return code;

  al::EpisodeSpec spec;
  am::MutationParams mutation;  // of the mutants: the run's, or the paper's
  std::optional<double> stored_fitness;
  std::string what;
  try {
    if (run_dir.empty() == genome_file.empty())
      throw std::invalid_argument("give either a run directory or --genome FILE");
    const std::string exists =
        ahhs::cli::RefuseExisting({log_file, csv_file, rules_csv, mutants_csv}, overwrite);
    if (!exists.empty()) {
      std::cerr << "ahhs-replay: " << exists << '\n';
      return ahhs::cli::kExitUsage;
    }
    if (mutants > 0 && mutants_csv.empty())
      throw std::invalid_argument("--mutants needs --mutants-csv FILE");
    if (!run_dir.empty()) {
      auto store = ev::RunStore::Open(run_dir, ev::StoreAccess::kRead);
      const ev::EvolveConfig config = ev::ConfigFromJson(store->config());
      ev::IndividualRecord record;
      if (generation < 0) {
        if (individual >= 0) throw std::invalid_argument("--individual needs --generation");
        record = store->Best();
      } else {
        if (generation > store->LastGeneration())
          throw std::invalid_argument("generation " + std::to_string(generation) +
                                      " is not stored (the run has generations 0-" +
                                      std::to_string(store->LastGeneration()) + ")");
        if (individual < 0) {
          for (const auto& g : store->LoadGenerationRecords())
            if (g.generation == generation) individual = g.stats.best_index;
        }
        record = store->LoadIndividual(generation, individual);
      }
      spec.config = config.scenario;
      mutation = config.ga.mutation;
      spec.genome = record.genome;
      spec.seed = app.count("--seed") ? seed : record.eval_seed;
      if (!app.count("--seed")) stored_fitness = record.evaluation.fitness;
      what = run_dir + ", generation " + std::to_string(record.generation) + ", individual " +
             std::to_string(record.index);
    } else {
      spec.config =
          ahhs::sim::MakeScenarioConfig(ahhs::sim::ParseScenarioKind(scenario),
                                        ahhs::sim::ParseJoints(joints), modules, duration);
      const std::string error = ahhs::sim::CheckConfig(spec.config);
      if (!error.empty()) throw std::invalid_argument(error);
      nlohmann::json meta;
      spec.genome = am::LoadGenomeFile(genome_file, &meta);
      const std::string fit = al::CheckGenomeFits(spec.genome, spec.config);
      if (!fit.empty()) throw std::invalid_argument(genome_file + ": " + fit);
      spec.seed = seed;
      what = genome_file;
      const auto stored_seed = am::StoredEvalSeed(meta);
      if (!app.count("--seed") && stored_seed) {
        spec.seed = *stored_seed;
        what += " (with the evaluation seed it stores)";
        if (meta.contains("fitness") && meta["fitness"].is_number())
          stored_fitness = meta["fitness"].get<double>();
      }
    }
    if (!mutation_profile.empty()) mutation.profile = am::ParseMutationProfile(mutation_profile);
  } catch (const std::exception& e) {
    std::cerr << "ahhs-replay: " << e.what() << '\n';
    return 1;
  }
  spec.episode = 1;

  try {
    const ahhs::bus::ArenaChannels ch(spec.arena);
    std::unique_ptr<LogWriter> log;
    std::unique_ptr<TextWriter> csv;
    if (!log_file.empty()) log = std::make_unique<LogWriter>(log_file);
    if (!csv_file.empty()) {
      csv = std::make_unique<TextWriter>(csv_file);
      auto& o = csv->out();
      o << "tick,time,module,hinge_angle";
      for (int j = 0; j < spec.genome.num_sensors; ++j) o << ",s" << j;
      for (int h = 0; h < spec.genome.num_hormones(); ++h) o << ",h" << h;
      for (int a = 0; a < spec.genome.num_actuators; ++a) o << ",a" << a;
      o << ",rules_active\n";
    }
    std::vector<std::vector<std::uint64_t>> last_activity;
    std::int64_t last_utime = 0;
    std::vector<ahhs::sim::BodyState> bodies;
    std::int64_t ticks_done = 0;
    double period = 0;
    const al::DirectObserver observer = [&](const al::DirectTick& t) {
      const auto& sc = *t.scenario;
      ticks_done = t.tick + 1;
      period = sc.control_period();
      const double time = static_cast<double>(t.tick + 1) * sc.control_period();
      const auto utime = static_cast<std::int64_t>(std::llround(time * 1e6));
      last_utime = utime;
      const int n = t.organism->size();
      last_activity.resize(static_cast<std::size_t>(n));
      for (int c = 0; c < n; ++c) {
        const auto& st = t.organism->state(c);
        auto& last = last_activity[static_cast<std::size_t>(c)];
        last.resize(st.rule_activity.size(), 0);
        ahhs::module_trace_t m;
        m.utime = utime;
        m.episode = spec.episode;
        m.tick = t.tick;
        m.module = c;
        const auto& s = (*t.sensors)[static_cast<std::size_t>(c)];
        m.num_sensors = static_cast<std::int16_t>(s.size());
        m.sensors = s;
        for (std::size_t j = 0; j < s.size(); ++j)
          m.sensor_present.push_back(sc.sensor_owned(c, static_cast<int>(j)));
        m.num_hormones = static_cast<std::int16_t>(st.hormones.size());
        m.hormones.assign(st.hormones.data(), st.hormones.data() + st.hormones.size());
        m.num_actuators = static_cast<std::int16_t>(st.actuators.size());
        m.actuators.assign(st.actuators.data(), st.actuators.data() + st.actuators.size());
        m.hinge_angle = sc.HingeAngle(c);
        m.num_rules = static_cast<std::int16_t>(st.rule_activity.size());
        int active = 0;
        for (std::size_t r = 0; r < st.rule_activity.size(); ++r) {
          const bool fired = st.rule_activity[r] != last[r];
          m.rule_active.push_back(fired ? 1 : 0);
          active += fired;
          last[r] = st.rule_activity[r];
        }
        if (log) {
          ahhs::module_sensors_t sensors = ahhs::sim::SensorsMessage(sc, c, spec.episode);
          sensors.utime = utime;
          sensors.tick = t.tick;
          sensors.values = s;
          log->Write(ch.Sensors(c), utime, sensors);
          ahhs::hinge_command_t hinge;
          hinge.utime = utime;
          hinge.episode = spec.episode;
          hinge.tick = t.tick;
          hinge.module = c;
          hinge.num_actuators = m.num_actuators;
          hinge.values = m.actuators;
          hinge.present.clear();
          for (int a = 0; a < m.num_actuators; ++a)
            hinge.present.push_back(sc.actuator_owned(c, a));
          log->Write(ch.Hinge(c), utime, hinge);
          log->Write(ch.Trace(c), utime, m);
        }
        if (csv) {
          auto& o = csv->out();
          o << t.tick << ',' << Exact(time) << ',' << c << ',' << Exact(m.hinge_angle);
          for (double v : s) o << ',' << Exact(v);
          for (double v : m.hormones) o << ',' << Exact(v);
          for (double v : m.actuators) o << ',' << Exact(v);
          o << ',' << active << '\n';
        }
      }
      if (log) {
        sc.Bodies(&bodies);
        if (t.tick % 20 == 0) {  // the static bodies, once per simulated second, as the sim does
          auto scene = bodies;
          ahhs::sim::KeepStaticBodies(&scene);
          log->Write(ch.SimScene(), utime,
                     ahhs::sim::StateMessage(scene, spec.episode, t.tick + 1, time));
        }
        ahhs::sim::KeepMovingBodies(&bodies);
        log->Write(ch.SimState(), utime,
                   ahhs::sim::StateMessage(bodies, spec.episode, t.tick + 1, time));
      }
    };
    std::vector<std::vector<std::uint64_t>> final_activity;
    ahhs::sim::BehaviourSummary behaviour;
    std::vector<double> commands;
    al::DirectObserver with_rules = [&](const al::DirectTick& t) {
      commands.clear();
      for (int c = 0; c < t.organism->size(); ++c) {
        const auto& a = t.organism->state(c).actuators;
        commands.insert(commands.end(), a.data(), a.data() + a.size());
      }
      behaviour.Observe(*t.scenario, commands);
      if (log || csv) observer(t);
      final_activity.clear();
      for (int c = 0; c < t.organism->size(); ++c)
        final_activity.push_back(t.organism->state(c).rule_activity);
    };
    const al::EpisodeResult result = al::RunDirectEpisode(spec, with_rules);
    if (log) {
      ahhs::fitness_t f{};
      f.episode = spec.episode;
      f.is_final = true;
      f.status = result.ok ? ahhs::fitness_t::OK : ahhs::fitness_t::ERROR;
      // As the live monitor reports it: the last state's tick, every state seen.
      f.tick = ticks_done;
      f.sim_time = static_cast<double>(ticks_done) * period;
      f.states_seen = static_cast<std::int32_t>(ticks_done);
      f.states_missed = 0;
      f.fitness = result.ok ? result.fitness : 0;
      f.cost = result.cost;
      f.message = result.error;
      f.utime = last_utime;
      log->Write(ch.Fitness(), last_utime, f);
      log->Commit();
    }
    if (csv) csv->Commit();
    if (!rules_csv.empty()) {
      TextWriter rules(rules_csv);
      rules.out() << "module,rule,ticks_active\n";
      for (std::size_t c = 0; c < final_activity.size(); ++c)
        for (std::size_t r = 0; r < final_activity[c].size(); ++r)
          rules.out() << c << ',' << r << ',' << final_activity[c][r] << '\n';
      rules.Commit();
    }
    if (mutants > 0) {
      TextWriter out(mutants_csv);
      out.out() << "mutant,fitness,genome_hash\n";
      out.out() << "original," << Exact(result.ok ? result.fitness : 0) << ','
                << am::GenomeHash(spec.genome) << '\n';
      am::Rng rng(mutant_seed);
      for (int k = 0; k < mutants; ++k) {
        al::EpisodeSpec mutant = spec;
        am::MutateOneGene(&mutant.genome, mutation, rng);
        const al::EpisodeResult r = al::RunDirectEpisode(mutant);
        out.out() << k << ',' << Exact(r.ok ? r.fitness : 0) << ',' << am::GenomeHash(mutant.genome)
                  << '\n';
      }
      out.Commit();
      std::printf("%d single mutants evaluated into %s\n", mutants, mutants_csv.c_str());
    }
    std::printf("replayed %s with seed %llu\n", what.c_str(),
                static_cast<unsigned long long>(spec.seed));
    if (!result.ok) {
      std::printf("the episode failed: %s (a failed episode scores 0 in a run)\n",
                  result.error.c_str());
    }
    if (result.ok) std::printf("behaviour: %s\n", behaviour.Describe().c_str());
    const double fitness = result.ok ? result.fitness : 0;
    if (stored_fitness) {
      if (*stored_fitness == fitness) {
        std::printf("stored fitness %s: reproduced exactly\n", Exact(*stored_fitness).c_str());
      } else {
        std::printf(
            "stored fitness %s: the replay differs by %.3g (the run was evaluated by a build "
            "whose physics or controller differ from this one)\n",
            Exact(*stored_fitness).c_str(), fitness - *stored_fitness);
      }
    }
    std::printf("fitness: %s\n", Exact(fitness).c_str());
  } catch (const std::exception& e) {
    std::cerr << "ahhs-replay: " << e.what() << '\n';
    return ahhs::cli::kExitFailure;
  }
  return 0;
}
