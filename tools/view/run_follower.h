// "Watch an evolution" (ahhs-view --run): follows a run directory that ahhs-evolve may still be
// writing, reading its store without a lock. When the newest generation's best individual is a
// genome other than the one shown, it replays it with its stored evaluation seed in this process
// (the workers' direct arena, so the fitness is the stored one to the bit) and hands out the
// recording. The evolution is not slowed beyond the one core this replay takes for about a
// second per new best.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "tools/view/view_events.h"

namespace ahhs::evolver {
class RunStore;
}

namespace ahhs::view {

class RunFollower {
 public:
  // `scratch_dir`: where the replay's log is written and read back (removed after).
  RunFollower(std::string run_dir, std::string scratch_dir);
  ~RunFollower();
  // A new recording when the newest generation's best changed, else nothing (also while the run
  // directory or its first generation does not exist yet). Throws when the directory is not a
  // readable run.
  std::optional<Json> Poll();
  std::string waiting_for() const;  // what the page says before the first recording

 private:
  std::string run_dir_, scratch_dir_;
  std::unique_ptr<evolver::RunStore> store_;
  int open_failures_ = 0;
  int shown_generation_ = -1;
  std::string shown_hash_;
};

}  // namespace ahhs::view
