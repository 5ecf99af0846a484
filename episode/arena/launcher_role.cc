#include "episode/arena/launcher_role.h"

#include <ahhs/fitness_t.hpp>
#include <ahhs/module_status_t.hpp>
#include <ahhs/sim_clock_t.hpp>
#include <ahhs/sim_control_t.hpp>
#include <algorithm>
#include <cstdio>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "bus/channels.h"
#include "bus/typed.h"
#include "modules/node/genome_codec.h"
#include "sim/node/sim_codec.h"

namespace ahhs::episode {

using Clock = std::chrono::steady_clock;

namespace {
std::string HashText(std::int64_t hash) {  // a wire hash (int64) as files show it
  return modules::HashText(static_cast<std::uint64_t>(hash));
}
}  // namespace

EpisodeResult RunEpisode(bus::Bus& bus, const EpisodeSpec& spec,
                         const std::function<void(std::chrono::microseconds)>& pump,
                         const std::function<bool(std::string*)>& alive) {
  EpisodeResult result;
  const bus::ArenaChannels ch(spec.arena);
  const int modules = sim::ShapeOf(spec.config).compartments;
  std::set<int> ready;
  bool sim_ready = false, monitor_ready = false;
  std::optional<fitness_t> final_fitness;
  std::int8_t run_state = -1;
  // The stall watchdog: the furthest tick the sim's clock or the monitor showed, and when.
  std::int64_t progress_tick = -1;
  auto progress_at = Clock::now();
  auto progress = [&](std::int64_t tick) {
    if (tick <= progress_tick) return;
    progress_tick = tick;
    progress_at = Clock::now();
  };
  const std::int64_t ep = spec.episode;
  std::vector<bus::Subscription> subs;
  const genome_t genome = modules::GenomeMessage(spec.genome, ep);
  std::map<int, std::string> module_drops;  // each module's latest report of drops
  auto on_status = [&](const std::string&, const module_status_t& s) {
    if (s.episode == ep) {
      const auto at = s.message.find("dropped: ");
      if (at != std::string::npos) module_drops[s.module] = s.message.substr(at + 9);
    }
    if (s.episode == ep &&
        (s.state == module_status_t::READY || s.state == module_status_t::RUNNING)) {
      if (!modules::GenomeHashMatches(s.genome_hash,
                                      static_cast<std::uint64_t>(genome.genome_hash))) {
        if (result.error.empty())
          result.error = "module " + std::to_string(s.module) + " reports genome hash " +
                         HashText(s.genome_hash) + ", not the episode's " +
                         HashText(genome.genome_hash) + " (it runs another genome)";
        return;
      }
      ready.insert(s.module);
    }
    if (s.episode == ep && s.state == module_status_t::ERROR && result.error.empty())
      result.error = "module " + std::to_string(s.module) + " refused the episode: " + s.message;
  };
  // One exact channel per module rather than a regex: over udpm:// the bus's socket filter then
  // keeps the per-tick traffic of the modules out of the launcher.
  for (int m = 0; m < modules; ++m)
    subs.push_back(bus::SubscribeTyped<module_status_t>(bus, ch.Status(m), on_status));
  subs.push_back(bus::SubscribeTyped<sim_clock_t>(bus, ch.SimClock(),
                                                  [&](const std::string&, const sim_clock_t& c) {
                                                    if (c.episode != ep) return;
                                                    if (c.run_state != run_state)
                                                      progress_at = Clock::now();
                                                    progress(c.tick);
                                                    run_state = c.run_state;
                                                    if (c.run_state == sim_clock_t::RESET)
                                                      sim_ready = true;
                                                  }));
  subs.push_back(bus::SubscribeTyped<fitness_t>(bus, ch.Fitness(),
                                                [&](const std::string&, const fitness_t& f) {
                                                  if (f.episode != ep) return;
                                                  progress(f.tick);
                                                  monitor_ready = true;
                                                  if (f.is_final) final_fitness = f;
                                                }));
  auto finish = [&](EpisodeResult r) {
    subs.clear();  // unsubscribes
    for (const auto& [m, text] : module_drops)
      r.drops.push_back("module " + std::to_string(m) + ": " + text);
    if (final_fitness && final_fitness->message.rfind("dropped: ", 0) == 0)
      r.drops.push_back("fitness monitor: " + final_fitness->message.substr(9));
    return r;
  };

  sim_control_t c{};
  c.episode = ep;
  c.seed = static_cast<std::int64_t>(spec.seed);  // LCM has no unsigned type: the same 64 bits
  sim::ScenarioToWire(spec.config, &c);
  c.clock_mode = spec.realtime ? sim_control_t::MODE_REALTIME : sim_control_t::MODE_LOCKSTEP;

  // Handshake: RESET + GENOME, repeated until the sim, every module and the monitor answered.
  const auto handshake_start = Clock::now();
  const auto handshake_end =
      handshake_start + (spec.external.empty() ? spec.handshake_timeout : spec.external_timeout);
  auto next_send = Clock::now();
  std::string why;
  auto modules_ok = [&] {
    if (static_cast<int>(ready.size()) == modules) return true;
    return spec.realtime && !ready.empty() &&
           Clock::now() > handshake_start + spec.realtime_join_wait;
  };
  while (!(sim_ready && monitor_ready && modules_ok())) {
    if (!alive(&why)) return finish(EpisodeResult::Failure(why));
    if (!result.error.empty()) return finish(result);
    if (Clock::now() > handshake_end) {
      auto ext = [](bool external) { return external ? " (external)," : ","; };
      std::string missing = sim_ready ? "" : std::string(" the sim") + ext(spec.external.sim);
      if (!monitor_ready)
        missing += std::string(" the fitness monitor") + ext(spec.external.fitness);
      for (int m = 0; m < modules; ++m)
        if (!ready.count(m))
          missing += " module " + std::to_string(m) + ext(spec.external.has_module(m));
      missing.pop_back();
      const auto waited =
          std::chrono::duration_cast<std::chrono::seconds>(Clock::now() - handshake_start);
      return finish(EpisodeResult::Failure("no answer to the episode handshake from" + missing +
                                           " within " + std::to_string(waited.count()) +
                                           " s on arena " + spec.arena));
    }
    if (Clock::now() >= next_send) {
      c.command = sim_control_t::RESET;
      c.utime = bus::NowUtime();
      bus::PublishTyped(bus, ch.SimControl(), c);
      auto g = genome;
      g.utime = bus::NowUtime();
      bus::PublishTyped(bus, ch.Genome(), g);
      next_send = Clock::now() + std::chrono::milliseconds(50);
    }
    pump(std::chrono::milliseconds(5));
  }

  // START, repeated until the sim's clock shows the episode running (a lost START must not
  // leave everyone waiting; the sim ignores repeats).
  c.command = sim_control_t::START;
  const auto episode_end = Clock::now() + spec.episode_timeout;
  auto next_genome = Clock::now() + std::chrono::seconds(1);
  auto next_start = Clock::now();
  progress_at = Clock::now();
  const bool watch_stalls = spec.stall_timeout.count() > 0 && !spec.realtime;
  while (!final_fitness) {
    if (!alive(&why)) return finish(EpisodeResult::Failure(why));
    if (watch_stalls && Clock::now() > progress_at + spec.stall_timeout)
      return finish(EpisodeResult::Failure(
          "the episode stalled: no progress for " + std::to_string(spec.stall_timeout.count()) +
          " s after tick " + std::to_string(std::max<std::int64_t>(progress_tick, 0)) +
          " (exact lockstep waits for every message: one was lost, or a process "
          "stopped)"));
    if (run_state == sim_clock_t::RESET && Clock::now() >= next_start) {
      c.utime = bus::NowUtime();
      bus::PublishTyped(bus, ch.SimControl(), c);
      next_start = Clock::now() + std::chrono::milliseconds(100);
    }
    if (Clock::now() > episode_end)
      return finish(EpisodeResult::Failure("the episode did not end in time"));
    if (spec.realtime && Clock::now() >= next_genome) {  // lets a module that starts late join
      auto g = genome;
      g.utime = bus::NowUtime();
      bus::PublishTyped(bus, ch.Genome(), g);
      next_genome = Clock::now() + std::chrono::seconds(1);
    }
    pump(std::chrono::milliseconds(20));
  }
  if (final_fitness->status != fitness_t::OK) {
    EpisodeResult failed = EpisodeResult::Failure(final_fitness->message);
    failed.episode_failed = true;
    return finish(failed);
  }
  EpisodeResult done;
  done.ok = true;
  done.fitness = final_fitness->fitness;
  done.cost = final_fitness->cost;
  done.descriptor = final_fitness->descriptor;
  done.states_missed = final_fitness->states_missed;
  return finish(done);
}

}  // namespace ahhs::episode
