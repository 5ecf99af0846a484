// The evaluation farm's messages as plain structs (docs/protocol.md, "Evaluation farm"), with
// no LCM: EVAL/REQUEST (evolver -> one worker), EVAL/GENOME (evolver -> all: a genome's pieces,
// see genome_pieces.h), EVAL/WANT (worker -> evolver: missing pieces), EVAL/RESULT (worker ->
// evolver), WORKER/STATUS (worker -> all, about 1 Hz and on every change).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "modules/core/genome.h"
#include "sim/core/scenario.h"

namespace ahhs::evolver {

// Bumped whenever a message of the farm changes meaning. Workers refuse requests of another
// version; evolvers ignore workers of another version (both say so).
// 3: the envelope of noise in EVAL/REQUEST; 4: the behaviour descriptor in EVAL/RESULT, the
// pendulum's choices in EVAL/REQUEST; 5: envelope_command_delay; 6: envelope_start_hinge; 7: the
// physics version by name (a worker refuses one its build does not simulate).
inline constexpr int kFarmProtocolVersion = 7;
inline std::string FarmVersionLine() {  // for --version
  return "farm protocol " + std::to_string(kFarmProtocolVersion);
}

// A run on the wire is "RUN_ID/sSESSION" (ahhs-evolve). A worker that serves one run only names
// its RUN_ID in every status; a status's run matches a wire run when it is the same or its id.
inline bool SameRun(const std::string& status_run, const std::string& wire_run) {
  return status_run == wire_run ||
         (!status_run.empty() && wire_run.rfind(status_run + "/", 0) == 0);
}

struct FarmJob {
  int protocol_version = kFarmProtocolVersion;
  std::string run;  // run id on the wire (unique per evolver session)
  std::int64_t job = 0;
  int attempt = 0;
  std::string worker;  // the worker the job is addressed to
  sim::ScenarioConfig config;
  std::uint64_t seed = 0;
  std::int64_t deadline_utime = 0;  // microseconds since the epoch
  // The genome by reference, as on the wire; `genome` is filled once its pieces are assembled.
  std::uint64_t genome_hash = 0;
  int genome_bytes = 0;
  int genome_chunks = 0;
  modules::Genome genome;
};

// A worker's request for the pieces of a genome it misses (EVAL/WANT).
struct GenomeWant {
  int protocol_version = kFarmProtocolVersion;
  std::string run;
  std::string worker;
  std::uint64_t genome_hash = 0;
  std::vector<int> missing;  // piece indexes
};

struct FarmResult {
  enum class Status { kOk, kError, kRefused };
  int protocol_version = kFarmProtocolVersion;
  std::string run;
  std::int64_t job = 0;
  int attempt = 0;
  std::string worker;
  Status status = Status::kOk;
  double fitness = 0;
  double cost = 0;
  double wall_time = 0;   // seconds
  int states_missed = 0;  // ticks whose state the fitness monitor missed (process arenas)
  std::string message;
  std::vector<double> descriptor;  // the episode's behaviour descriptor (EpisodeResult)
};

struct WorkerStatus {
  int protocol_version = kFarmProtocolVersion;
  std::string worker;
  std::string host;
  int slots = 1;
  int free_slots = 1;
  std::int64_t evaluations_done = 0;
  std::vector<std::int64_t> jobs;  // jobs queued or being evaluated, all of run `run`
  std::string run;                 // "" when idle
};

}  // namespace ahhs::evolver
