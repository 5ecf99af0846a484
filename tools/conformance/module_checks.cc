#include "tools/conformance/module_checks.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <sstream>

#include "modules/core/hormone_system.h"
#include "modules/node/genome_codec.h"

namespace ahhs::conformance {

namespace {

std::string Exact(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

using Key = std::pair<std::int64_t, std::int64_t>;  // (episode, tick)

// The first output per (episode, tick), and how many came.
struct Outputs {
  std::map<Key, const ModuleOutput*> first;
  std::map<Key, int> count;
  explicit Outputs(const std::vector<ModuleOutput>& all) {
    for (const ModuleOutput& o : all) {
      const Key k{o.episode, o.tick};
      if (++count[k] == 1) first[k] = &o;
    }
  }
  const ModuleOutput* Find(std::int64_t episode, std::int64_t tick) const {
    const auto it = first.find({episode, tick});
    return it == first.end() ? nullptr : it->second;
  }
};

// "" when the output equals the model's values to the bit, else the first difference.
std::string Compare(const char* what, const std::vector<double>& got,
                    const Eigen::VectorXd& expected) {
  if (got.size() != static_cast<std::size_t>(expected.size()))
    return std::string(what) + " has " + std::to_string(got.size()) + " values, the model " +
           std::to_string(expected.size());
  for (std::size_t k = 0; k < got.size(); ++k)
    if (!SameBits(got[k], expected[static_cast<Eigen::Index>(k)]))
      return std::string(what) + "[" + std::to_string(k) + "] = " + Exact(got[k]) +
             ", the model's " + Exact(expected[static_cast<Eigen::Index>(k)]);
  return "";
}

// Sizes and values of one HINGE or HORMONE; "" when fine.
std::string HingeProblem(const ModuleOutput& h, const modules::Genome& g) {
  if (h.values.size() != static_cast<std::size_t>(g.num_actuators) ||
      h.present.size() != h.values.size())
    return "HINGE with " + std::to_string(h.values.size()) + " values for " +
           std::to_string(g.num_actuators) + " actuators";
  for (double v : h.values)
    if (!std::isfinite(v) || v < -1 || v > 1) return "a HINGE value outside [-1, 1]";
  for (bool p : h.present)
    if (!p) return "HINGE present[] is not the SENSORS' actuator_present (all owned)";
  if (!(std::abs(h.target_angle - M_PI / 2 * h.values[0]) <= 1e-9))
    return "HINGE target_angle " + Exact(h.target_angle) + " is not pi/2 x values[0]";
  return "";
}

std::string HormoneProblem(const ModuleOutput& p, const PlayedEpisode& e) {
  if (p.to_modules != e.neighbours) return "HORMONE to_modules is not the docked neighbours";
  if (p.values.size() != static_cast<std::size_t>(e.genome.num_hormones()))
    return "HORMONE with " + std::to_string(p.values.size()) + " amounts for " +
           std::to_string(e.genome.num_hormones()) + " hormones";
  for (double a : p.values)
    if (!std::isfinite(a) || a < 0 || a > 1) return "a HORMONE amount outside [0, 1]";
  return "";
}

}  // namespace

std::vector<Check> JudgeModule(const ModuleRecord& r, const Budget& budget,
                               double lost_packet_limit) {
  std::vector<Check> checks;
  const Outputs hinges(r.hinges), hormones(r.hormones);

  // Handshake.
  {
    bool pass = !r.episodes.empty();
    std::string evidence;
    for (std::size_t k = 0; k < r.episodes.size(); ++k) {
      const PlayedEpisode& e = r.episodes[k];
      const std::uint64_t hash = modules::GenomeHash(e.genome);
      std::string line = "episode " + std::to_string(k + 1) + " (" +
                         modules::VariantName(e.genome.variant) + "): ";
      if (e.ready_at < 0) {
        line += "no READY";
        pass = false;
      } else if (!modules::GenomeHashMatches(e.ready_hash, hash)) {
        std::ostringstream s;
        s << "READY with hash " << std::hex << static_cast<std::uint64_t>(e.ready_hash)
          << ", the genome's " << hash;
        line += s.str();
        pass = false;
      } else {
        line += "READY with its hash";
      }
      evidence += (k ? "; " : "") + line;
    }
    checks.push_back(
        {"handshake: READY for GENOME and TOPOLOGY, with the genome's hash", pass, evidence});
  }
  {
    int asked = 0, answered = 0;
    for (const PlayedEpisode& e : r.episodes) {
      asked += e.repeat_asked;
      answered += e.repeat_asked && e.repeat_answered;
    }
    checks.push_back({"a repeated GENOME before the first tick is answered with READY again",
                      asked > 0 && answered == asked,
                      std::to_string(answered) + " of " + std::to_string(asked) + " answered"});
  }

  // One HINGE and one HORMONE per tick; sizes and values.
  {
    std::set<Key> played;
    for (const PlayedEpisode& e : r.episodes)
      for (const PlayedTick& t : e.ticks) played.insert({e.episode, t.tick});
    int missing_h = 0, missing_p = 0, several = 0, unplayed = 0, foreign = 0;
    for (const Key& k : played) {
      missing_h += hinges.count.count(k) == 0;
      missing_p += hormones.count.count(k) == 0;
    }
    const std::set<std::int64_t> foreign_ids(r.foreign_episodes.begin(), r.foreign_episodes.end());
    for (const auto* outputs : {&hinges, &hormones})
      for (const auto& [k, n] : outputs->count) {
        several += n > 1;
        if (foreign_ids.count(k.first))
          ++foreign;
        else if (!played.count(k))
          ++unplayed;
      }
    checks.push_back(
        {"one HINGE and one HORMONE per tick, with its episode and tick",
         missing_h + missing_p + several + unplayed + foreign == 0,
         std::to_string(played.size()) + " ticks played: " + std::to_string(missing_h) +
             " without HINGE, " + std::to_string(missing_p) + " without HORMONE, " +
             std::to_string(several) + " with several, " + std::to_string(unplayed) +
             " of no played tick, " + std::to_string(foreign) + " of the foreign episode"});
    int bad = 0;
    std::string first;
    for (const PlayedEpisode& e : r.episodes)
      for (const PlayedTick& t : e.ticks) {
        std::string problem;
        if (const ModuleOutput* h = hinges.Find(e.episode, t.tick)) {
          problem = HingeProblem(*h, e.genome);
          if (problem.empty() && h->module != r.id) problem = "HINGE names another module";
        }
        if (const ModuleOutput* p = hormones.Find(e.episode, t.tick); p && problem.empty())
          problem = HormoneProblem(*p, e);
        if (!problem.empty() && ++bad == 1) first = problem;
      }
    checks.push_back(
        {"sizes and values (HINGE in [-1, 1], target pi/2 A0; HORMONE to the "
         "docked neighbours, amounts in [0, 1])",
         bad == 0,
         bad == 0 ? std::to_string(r.hinges.size() + r.hormones.size()) + " messages checked"
                  : std::to_string(bad) + " ticks wrong, first: " + first});
  }

  // Equality to the model, segment by segment. After the first difference the module's state
  // is not the model's any more: later segments say so instead of repeating it.
  {
    std::string first_difference;
    for (const PlayedEpisode& e : r.episodes) {
      std::vector<int> ticks(e.segments.size(), 0), moving(e.segments.size(), 0);
      std::vector<std::string> problem(e.segments.size());
      const modules::Controller controller(e.genome);
      modules::CompartmentState state = modules::MakeState(controller);
      std::string episode_difference;
      for (const PlayedTick& t : e.ticks) {
        auto& seg_problem = problem[static_cast<std::size_t>(t.segment)];
        ++ticks[static_cast<std::size_t>(t.segment)];
        for (const auto& packet : t.packets) modules::ReceiveHormones(packet.second.data(), &state);
        modules::TickInput in;
        in.sensors = t.sensors.data();
        in.num_neighbours = static_cast<int>(e.neighbours.size());
        modules::Step(controller, in, &state);
        moving[static_cast<std::size_t>(t.segment)] += state.actuators[0] != 0.0;
        if (!seg_problem.empty()) continue;
        if (!episode_difference.empty()) {
          seg_problem = "differs since " + episode_difference;
          continue;
        }
        const ModuleOutput* h = hinges.Find(e.episode, t.tick);
        const ModuleOutput* p = hormones.Find(e.episode, t.tick);
        std::string d;
        if (h == nullptr)
          d = "no HINGE";
        else
          d = Compare("HINGE values", h->values, state.actuators);
        if (d.empty() && !e.neighbours.empty())
          d = p == nullptr ? "no HORMONE" : Compare("HORMONE amounts", p->values, state.outflow);
        if (!d.empty()) {
          seg_problem = "tick " + std::to_string(t.tick) + ": " + d;
          episode_difference = "tick " + std::to_string(t.tick);
        }
      }
      for (std::size_t s = 0; s < e.segments.size(); ++s)
        checks.push_back({"equals the model bit for bit: " + e.segments[s], problem[s].empty(),
                          problem[s].empty()
                              ? std::to_string(ticks[s]) + (ticks[s] == 1 ? " tick" : " ticks") +
                                    ", actuators and outflows equal (actuator not 0 in " +
                                    std::to_string(moving[s]) + ")"
                              : problem[s]});
    }
  }

  // The withheld packet, and the latency of every other tick.
  {
    std::vector<double> latencies;
    std::string lost;
    bool lost_pass = false, lost_played = false;
    for (const PlayedEpisode& e : r.episodes)
      for (const PlayedTick& t : e.ticks) {
        const ModuleOutput* h = hinges.Find(e.episode, t.tick);
        if (t.lost_packet) {
          lost_played = true;
          if (h == nullptr) {
            lost = "no HINGE for tick " + std::to_string(t.tick);
          } else {
            const double wait = h->arrival - t.last_input;
            lost_pass = wait <= lost_packet_limit;
            lost = "HINGE " + Ms(wait) + " after SENSORS (limit " + Ms(lost_packet_limit) + ")";
          }
        } else if (h != nullptr) {
          latencies.push_back(h->arrival - t.last_input);
        }
      }
    if (lost_played)
      checks.push_back(
          {"a lost neighbour packet: steps without it after its hormone timeout", lost_pass, lost});
    std::sort(latencies.begin(), latencies.end());
    const double worst = latencies.empty() ? 0 : latencies.back();
    checks.push_back({"within the real-time budget (HINGE " + Ms(budget.latency) +
                          " after the tick's last input)",
                      !latencies.empty() && worst <= budget.latency,
                      latencies.empty() ? std::string("no HINGE to time")
                                        : "median " + Ms(latencies[latencies.size() / 2]) +
                                              ", worst " + Ms(worst)});
  }

  // STATUS.
  {
    int own = 0, other = 0, running = 0;
    for (const ModuleStatusSeen& s : r.statuses) {
      (s.module == r.id ? own : other) += 1;
      running += s.module == r.id && s.state == 2;  // module_status_t::RUNNING
    }
    checks.push_back({"STATUS on its channel with its id, RUNNING once stepping",
                      own > 0 && other == 0 && running > 0,
                      std::to_string(own) + " statuses, " + std::to_string(running) + " RUNNING, " +
                          std::to_string(other) + " naming another module"});
  }
  return checks;
}

}  // namespace ahhs::conformance
