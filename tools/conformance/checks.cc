#include "tools/conformance/checks.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

namespace ahhs::conformance {

namespace {

// The checks every clock-driven role shares: nothing before START, one message per tick of both
// phases with the clock's episode and tick, latency within the budget, sane sizes and values.
void JudgeTicks(const PlayedClock& clock, const std::vector<Observed>& seen, const Budget& budget,
                const char* what, std::vector<Check>* out) {
  std::map<std::int64_t, double> sent(clock.sent.begin(), clock.sent.end());
  int before_start = 0, foreign = 0, bad = 0;
  std::map<std::int64_t, int> per_tick;
  std::vector<double> latencies;
  std::string first_problem;
  for (const Observed& o : seen) {
    if (o.arrival < clock.started) ++before_start;
    const auto key = PlayedClock::Key(o.episode, o.tick);
    const auto it = sent.find(key);
    if (it == sent.end()) {
      ++foreign;
      continue;
    }
    ++per_tick[key];
    latencies.push_back(o.arrival - it->second);
    if (!o.problem.empty() && ++bad == 1) first_problem = o.problem;
  }
  out->push_back({std::string("no ") + what + " before START", before_start == 0,
                  std::to_string(before_start) + " before the first running clock"});
  int missing = 0, repeated = 0;
  for (const auto& [key, time] : sent) {
    (void)time;
    const auto it = per_tick.find(key);
    if (it == per_tick.end())
      ++missing;
    else if (it->second > 1)
      ++repeated;
  }
  out->push_back({std::string("one ") + what + " per tick, with the clock's episode and tick",
                  missing == 0 && repeated == 0 && foreign == 0,
                  std::to_string(sent.size()) + " ticks played: " + std::to_string(missing) +
                      " without, " + std::to_string(repeated) + " with several, " +
                      std::to_string(foreign) + " messages of no played (episode, tick)"});
  std::sort(latencies.begin(), latencies.end());
  const double worst = latencies.empty() ? 0 : latencies.back();
  const double median = latencies.empty() ? 0 : latencies[latencies.size() / 2];
  out->push_back({"within the real-time budget (" + Ms(budget.latency) + " after SIM/CLOCK)",
                  !latencies.empty() && worst <= budget.latency,
                  latencies.empty() ? std::string("no message of a played tick to time")
                                    : "median " + Ms(median) + ", worst " + Ms(worst)});
  out->push_back({"sizes and finite values", bad == 0,
                  bad == 0 ? std::to_string(seen.size()) + " messages checked"
                           : std::to_string(bad) + " wrong, first: " + first_problem});
  const bool joined = std::any_of(seen.begin(), seen.end(), [&](const Observed& o) {
    return o.episode == clock.late_episode && o.tick == clock.late_from;
  });
  out->push_back(
      {"joins a running episode (late start at tick " + std::to_string(clock.late_from) + ")",
       joined,
       std::string(joined ? "a " : "no ") + what + " for tick " + std::to_string(clock.late_from) +
           " of an episode first heard at that tick"});
}

}  // namespace

std::vector<Check> JudgeFirmware(const PlayedClock& clock, const std::vector<Observed>& readings,
                                 int id, double commanded, double foreign_target,
                                 const Budget& budget) {
  std::vector<Check> checks;
  JudgeTicks(clock, readings, budget, "reading", &checks);
  int wrong_module = 0;
  for (const Observed& o : readings) wrong_module += o.module != id;
  checks.push_back({"readings name module " + std::to_string(id), wrong_module == 0,
                    std::to_string(wrong_module) + " name another"});
  // The hinge at the end of phase 1 (after half a phase of one constant target).
  double last = std::nan("");
  for (const Observed& o : readings)
    if (o.episode == clock.episode) last = o.hinge_angle;
  std::ostringstream e;
  e << "last hinge_angle " << last << " rad, commanded " << commanded << ", foreign episode's "
    << foreign_target;
  checks.push_back({"follows HINGE of its episode, ignores a foreign episode's",
                    std::isfinite(last) && std::abs(last - commanded) < 0.1, e.str()});
  return checks;
}

std::vector<Check> JudgeTracker(const PlayedClock& clock, const std::vector<Observed>& states,
                                const Budget& budget) {
  std::vector<Check> checks;
  JudgeTicks(clock, states, budget, "state", &checks);
  return checks;
}

std::string Ms(double seconds) {
  std::ostringstream s;
  s.precision(1);
  s << std::fixed << seconds * 1000 << " ms";
  return s.str();
}

bool PrintChecklist(const std::vector<Check>& checks, std::string* text) {
  bool all = true;
  for (const Check& c : checks) {
    *text += std::string(c.pass ? "PASS " : "FAIL ") + c.name + ": " + c.evidence + "\n";
    all = all && c.pass;
  }
  return all;
}

}  // namespace ahhs::conformance
