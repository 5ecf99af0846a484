#include "tools/conformance/sim_checks.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace ahhs::conformance {

namespace {

constexpr std::int8_t kReset = 0, kRunning = 1, kPaused = 2, kFinished = 3;  // sim_clock_t
constexpr std::int8_t kRealtime = 1;

// First arrival of a clock of `episode` in `state` (-1: none).
double FirstClock(const SimRecord& r, std::int64_t episode, std::int8_t state) {
  for (const ClockSeen& c : r.clocks)
    if (c.episode == episode && c.state == state) return c.arrival;
  return -1;
}

}  // namespace

std::vector<Check> JudgeSim(const SimRecord& r, const Budget& budget) {
  const SimPlayed& p = r.played;
  std::vector<Check> checks;

  // RESET -> SIM/CLOCK RESET and TOPOLOGY of the episode, before it runs.
  {
    bool pass = true;
    std::string evidence;
    for (const auto& [episode, sent] :
         {std::pair{p.full, p.full_reset_sent}, std::pair{p.stopped, p.stopped_reset_sent}}) {
      const double reset = FirstClock(r, episode, kReset);
      const double running = FirstClock(r, episode, kRunning);
      bool topology = false;
      for (const TopologySeen& t : r.topologies)
        topology = topology || (t.episode == episode && (running < 0 || t.arrival <= running));
      if (!evidence.empty()) evidence += "; ";
      if (reset < 0 || !topology) {
        pass = false;
        evidence += std::string(reset < 0 ? "no SIM/CLOCK RESET" : "no TOPOLOGY before it ran");
      } else {
        evidence += "clock RESET " + Ms(reset - sent) + " after the first RESET, with TOPOLOGY";
      }
    }
    checks.push_back(
        {"answers RESET with SIM/CLOCK RESET and TOPOLOGY of the episode", pass, evidence});
  }
  {
    int wrong = 0, while_running = 0;
    const double run_from = FirstClock(r, p.full, kRunning);
    const double run_to = FirstClock(r, p.full, kFinished);
    for (const TopologySeen& t : r.topologies) {
      wrong += !t.chain;
      while_running += t.episode == p.full && run_from >= 0 && t.arrival > run_from &&
                       (run_to < 0 || t.arrival < run_to);
    }
    const int wanted = p.ticks / 20 - 1;
    checks.push_back(
        {"TOPOLOGY is the chain of " + std::to_string(p.modules) +
             " modules (back port 2 of i to front port 0 of i + 1), repeated every 20 ticks",
         !r.topologies.empty() && wrong == 0 && while_running >= wanted,
         std::to_string(r.topologies.size()) + " seen, " + std::to_string(wrong) +
             " not the chain, " + std::to_string(while_running) + " while running (at least " +
             std::to_string(wanted) + " wanted)"});
  }

  // The full episode's clock.
  std::vector<const ClockSeen*> running;
  for (const ClockSeen& c : r.clocks)
    if (c.episode == p.full && c.state == kRunning) running.push_back(&c);
  {
    std::map<std::int64_t, int> per_tick;
    int bad_fields = 0;
    for (const ClockSeen* c : running) {
      ++per_tick[c->tick];
      bad_fields += c->mode != kRealtime || std::abs(c->control_period - p.period) > 1e-12 ||
                    std::abs(c->sim_time - static_cast<double>(c->tick) * p.period) > 1e-9;
    }
    int missing = 0, several = 0, outside = 0, out_of_order = 0;
    for (int t = 0; t < p.ticks; ++t) {
      const auto it = per_tick.find(t);
      missing += it == per_tick.end();
      several += it != per_tick.end() && it->second > 1;
    }
    for (const auto& [tick, n] : per_tick) outside += tick < 0 || tick >= p.ticks ? n : 0;
    for (std::size_t k = 1; k < running.size(); ++k)
      out_of_order += running[k]->tick <= running[k - 1]->tick;
    const bool from_zero = !running.empty() && running.front()->tick == 0;
    checks.push_back(
        {"START runs ticks 0 .. " + std::to_string(p.ticks - 1) +
             ": one SIM/CLOCK RUNNING each, in order, real-time mode, sim_time = tick x period",
         from_zero && missing + several + outside + out_of_order + bad_fields == 0,
         std::to_string(running.size()) + " running clocks: first tick " +
             (running.empty() ? std::string("none") : std::to_string(running.front()->tick)) +
             ", " + std::to_string(missing) + " ticks without, " + std::to_string(several) +
             " with several, " + std::to_string(outside) + " outside the episode, " +
             std::to_string(out_of_order) + " out of order, " + std::to_string(bad_fields) +
             " with a wrong mode, period or sim_time"});
    // Pace: each tick against the schedule its first tick set.
    double worst = 0;
    std::vector<double> intervals;
    for (std::size_t k = 0; k < running.size(); ++k) {
      const double due = running.front()->arrival +
                         static_cast<double>(running[k]->tick - running.front()->tick) * p.period;
      worst = std::max(worst, std::abs(running[k]->arrival - due));
      if (k > 0) intervals.push_back(running[k]->arrival - running[k - 1]->arrival);
    }
    std::sort(intervals.begin(), intervals.end());
    checks.push_back({"keeps real time (each tick within " + Ms(budget.latency) +
                          " of its schedule, period " + Ms(p.period) + ")",
                      intervals.size() >= 2 && worst <= budget.latency,
                      intervals.empty() ? std::string("fewer than two ticks")
                                        : "median interval " + Ms(intervals[intervals.size() / 2]) +
                                              ", worst off schedule " + Ms(worst)});
    int after = 0;
    bool held = false;
    for (const ClockSeen& c : r.clocks)
      if (c.episode == p.full && c.arrival > p.foreign_sent) {
        after += c.state == kRunning;
        held = held || c.state == kPaused || (c.state == kFinished && c.tick < p.ticks);
      }
    checks.push_back({"ignores another episode's PAUSE and STOP", !held && after > 0,
                      std::to_string(after) + " ticks ran after them" +
                          (held ? ", but the episode paused or ended early" : "")});
  }
  {
    int finished = 0, late_running = 0;
    std::int64_t end_tick = -1;
    const double end = FirstClock(r, p.full, kFinished);
    for (const ClockSeen& c : r.clocks) {
      if (c.episode != p.full) continue;
      if (c.state == kFinished) {
        ++finished;
        end_tick = c.tick;
      }
      late_running += end >= 0 && c.state == kRunning && c.arrival > end;
    }
    checks.push_back({"ends after " + std::to_string(p.ticks) +
                          " ticks: SIM/CLOCK FINISHED three times, nothing running after it",
                      finished >= 3 && end_tick == p.ticks && late_running == 0,
                      std::to_string(finished) + " FINISHED (tick " + std::to_string(end_tick) +
                          "), " + std::to_string(late_running) + " running clocks after"});
  }
  {
    const double end = FirstClock(r, p.stopped, kFinished);
    int late_running = 0;
    for (const ClockSeen& c : r.clocks)
      late_running += c.episode == p.stopped && c.state == kRunning && end >= 0 && c.arrival > end;
    const double limit = 2 * p.period + budget.latency;
    checks.push_back(
        {"STOP ends a running episode within two ticks",
         p.stop_sent >= 0 && end >= 0 && end - p.stop_sent <= limit && late_running == 0,
         end < 0 ? std::string("no FINISHED after STOP")
                 : "FINISHED " + Ms(end - p.stop_sent) + " after STOP (limit " + Ms(limit) + "), " +
                       std::to_string(late_running) + " running clocks after"});
  }
  {
    int answered = 0;
    for (const ClockSeen& c : r.clocks) answered += c.episode == p.bad;
    checks.push_back({"refuses a bad RESET (unknown scenario)", answered == 0,
                      std::to_string(answered) + " clocks of that episode"});
  }
  {
    std::map<std::pair<std::int64_t, int>, int> per;
    int foreign = 0;
    for (const SensorsSeen& s : r.sensors) {
      if (s.episode == p.full && s.tick >= 0 && s.tick < p.ticks && s.module >= 0 &&
          s.module < p.modules)
        ++per[{s.tick, s.module}];
      else if (s.episode != p.stopped)
        ++foreign;
    }
    int complete = 0;
    for (const auto& [key, n] : per) complete += n == 1;
    const int wanted = p.ticks * p.modules;
    const bool none = r.sensors.empty();
    checks.push_back(
        {"SENSORS: one per module and tick (a simulated body), or none (the firmware's)",
         none || (complete == wanted && static_cast<int>(per.size()) == wanted && foreign == 0),
         none ? std::string("none: an episode server")
              : std::to_string(complete) + " of " + std::to_string(wanted) +
                    " (tick, module) pairs once, " + std::to_string(foreign) + " foreign"});
  }
  return checks;
}

}  // namespace ahhs::conformance
