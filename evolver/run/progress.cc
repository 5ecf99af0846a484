#include "evolver/run/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace ahhs::evolver {

std::string FormatDuration(double s) {
  if (!(s >= 0) || !std::isfinite(s)) return "?";
  char buf[32];
  const long t = std::lround(s);
  if (t >= 3600)
    std::snprintf(buf, sizeof buf, "%ldh%02ldm", t / 3600, (t / 60) % 60);
  else if (t >= 60)
    std::snprintf(buf, sizeof buf, "%ldm%02lds", t / 60, t % 60);
  else
    std::snprintf(buf, sizeof buf, "%lds", t);
  return buf;
}

Progress::Progress(int first_generation, int generations)
    : tty_(isatty(STDOUT_FILENO) != 0),
      generations_(generations),
      first_(first_generation),
      start_(Clock::now()) {}

void Progress::Evaluated(int generation, std::size_t done, std::size_t total) {
  if (!tty_) return;
  const auto now = Clock::now();
  if (done != total && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  const double gens_done =
      (generation - first_) + static_cast<double>(done) / static_cast<double>(total);
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double eta =
      gens_done > 0 ? elapsed / gens_done * (generations_ - first_ - gens_done) : NAN;
  const int width = 30;
  const int filled =
      static_cast<int>(width * static_cast<double>(done) / static_cast<double>(total));
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.resize(width, '.');
  if (generation >= generations_)  // the finished run's validation
    std::printf("\r\033[K validation [%s] %zu/%zu%s", bar.c_str(), done, total, last_.c_str());
  else
    std::printf("\r\033[K generation %d/%d [%s] %zu/%zu  ETA %s%s", generation, generations_ - 1,
                bar.c_str(), done, total, FormatDuration(eta).c_str(), last_.c_str());
  std::fflush(stdout);
  drawn_ = true;
}

void Progress::Generation(const GenerationRecord& r) {
  char line[240];
  const int done = r.generation + 1 - first_;
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  const int left = generations_ - 1 - r.generation;
  std::snprintf(line, sizeof line,
                "generation %d/%d: best %.6f  mean %.6f  median %.6f  worst %.6f  (%.1f s%s%s)",
                r.generation, generations_ - 1, r.stats.best, r.stats.mean, r.stats.median,
                r.stats.worst, r.wall_time, left > 0 && done > 0 ? ", ETA " : "",
                left > 0 && done > 0 ? FormatDuration(elapsed / done * left).c_str() : "");
  Clear();
  std::printf("%s\n", line);
  std::fflush(stdout);
  char summary[80];
  std::snprintf(summary, sizeof summary, "  | last: best %.4f mean %.4f", r.stats.best,
                r.stats.mean);
  last_ = summary;
}

void Progress::Say(const std::string& text) {
  Clear();
  std::fprintf(stderr, "ahhs-evolve: %s\n", text.c_str());
}

void Progress::Clear() {
  if (tty_ && drawn_) {
    std::printf("\r\033[K");
    std::fflush(stdout);
    drawn_ = false;
  }
}

}  // namespace ahhs::evolver
