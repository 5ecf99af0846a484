// What ahhs-evolve shows while a run goes on: a progress bar with ETA on a terminal, a line per
// generation (with ETA) always.
#pragma once

#include <chrono>
#include <string>

#include "evolver/store/run_store.h"

namespace ahhs::evolver {

// "1h02m", "3m05s", "42s"; "?" for a negative or unknown time.
std::string FormatDuration(double seconds);

// The terminal display: a progress bar with ETA on a terminal, plain lines otherwise.
class Progress {
 public:
  Progress(int first_generation, int generations);
  // `done` of `total` evaluations of `generation` are back (redraws the bar at most 10 times a s);
  // a generation past the run's last is its validation.
  void Evaluated(int generation, std::size_t done, std::size_t total);
  // A generation is stored: its line, with the time it took and the ETA of the run.
  void Generation(const GenerationRecord& r);
  // A message on stderr ("ahhs-evolve: TEXT"), the bar cleared first.
  void Say(const std::string& text);
  void Clear();

 private:
  using Clock = std::chrono::steady_clock;
  bool tty_;
  int generations_, first_;
  Clock::time_point start_, last_draw_{};
  std::string last_;
  bool drawn_ = false;
};

}  // namespace ahhs::evolver
