// Records a direct episode tick by tick (ahhs-replay, docs/analysis.md): an LCM log with what a
// live arena would carry (per tick every module's SENSORS and HINGE, its TRACE, SIM/SCENE at the
// sim's cadence, SIM/STATE after the tick and the running FITNESS, the final FITNESS), a per-tick
// CSV, and how often each rule fired. Files are written to temporary names and moved into place by
// Commit(): an interrupted replay leaves nothing half-written.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "episode/arena/direct_arena.h"

namespace ahhs::episode {

class EpisodeRecorder {
 public:
  // Empty paths are not written. `body_csv`: the organism per tick (pendulum: cart position and
  // pole angle; gait: the centroid), `tick,time,...`.
  EpisodeRecorder(const EpisodeSpec& spec, const std::string& log_file, const std::string& csv_file,
                  const std::string& rules_csv, const std::string& body_csv = "");
  ~EpisodeRecorder();
  EpisodeRecorder(const EpisodeRecorder&) = delete;
  EpisodeRecorder& operator=(const EpisodeRecorder&) = delete;

  // Call after every tick (RunDirectEpisode's observer).
  void Observe(const DirectTick& tick);
  // Writes the final FITNESS and moves every file into place.
  void Commit(const EpisodeResult& result);

 private:
  class Files;
  const EpisodeSpec spec_;
  std::unique_ptr<Files> files_;
  std::vector<std::vector<std::uint64_t>> last_activity_;  // per module
  std::vector<std::vector<std::uint64_t>> final_activity_, final_parts_;
  std::int64_t ticks_done_ = 0;
  double period_ = 0;
  std::int64_t last_utime_ = 0;
};

}  // namespace ahhs::episode
