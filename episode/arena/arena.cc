#include "episode/arena/arena.h"

#include <stdexcept>

#include "episode/arena/direct_arena.h"
#include "episode/arena/fused_arena.h"
#include "episode/arena/process_arena.h"

namespace ahhs::episode {

ArenaKind ParseArenaKind(const std::string& name) {
  if (name == "direct") return ArenaKind::kDirect;
  if (name == "fused") return ArenaKind::kFused;
  if (name == "processes") return ArenaKind::kProcesses;
  throw std::invalid_argument("unknown arena '" + name + "' (direct, fused or processes)");
}

const char* ArenaKindName(ArenaKind kind) {
  switch (kind) {
    case ArenaKind::kDirect:
      return "direct";
    case ArenaKind::kFused:
      return "fused";
    case ArenaKind::kProcesses:
      return "processes";
  }
  return "?";
}

namespace {

class DirectArena : public Arena {
 public:
  EpisodeResult Run(const EpisodeSpec& spec) override { return RunDirectEpisode(spec); }
};

class FusedArena : public Arena {
 public:
  EpisodeResult Run(const EpisodeSpec& spec) override { return RunFused(spec); }
};

class ProcessesArena : public Arena {
 public:
  ProcessesArena(ProcessArenaOptions options, bool realtime)
      : processes_(std::move(options)), realtime_(realtime) {}
  EpisodeResult Run(const EpisodeSpec& spec) override {
    EpisodeSpec s = spec;
    s.realtime = s.realtime || realtime_;
    return processes_.Run(s, [](std::string*) { return true; });
  }
  bool healthy() const override { return processes_.healthy(); }

 private:
  ProcessArena processes_;
  bool realtime_;
};

}  // namespace

std::unique_ptr<Arena> MakeArena(const ArenaOptions& options, const sim::ScenarioConfig& config) {
  switch (options.kind) {
    case ArenaKind::kDirect:
      if (!options.external.empty() || options.realtime)
        throw std::invalid_argument("external roles and real time need the process arena");
      return std::make_unique<DirectArena>();
    case ArenaKind::kFused:
      if (!options.external.empty() || options.realtime)
        throw std::invalid_argument("external roles and real time need the process arena");
      return std::make_unique<FusedArena>();
    case ArenaKind::kProcesses: {
      ProcessArenaOptions o;
      o.url = options.url;
      o.arena = options.name;
      o.num_modules = sim::ShapeOf(config).compartments;
      if (!options.external.empty())
        o.external = ParseExternalRoles(options.external, o.num_modules);
      o.external_timeout = options.external_timeout;
      return std::make_unique<ProcessesArena>(o, options.realtime);
    }
  }
  throw std::invalid_argument("unknown arena kind");
}

}  // namespace ahhs::episode
