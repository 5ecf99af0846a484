// The run directory of one evolution (docs/evolution.md, "Run directory"):
//   run.sqlite            SQLite in WAL mode: run config and seeds, every individual of every
//                         generation (genome, fitness, evaluation seed, worker, timings), every
//                         trial of an individual evaluated several times (seed, fitness, worker,
//                         timings), the statistics of every generation, the sessions.
//                         The validation that chose the run's best among its leaders (when the
//                         config asks for one): every candidate's validation episodes.
//                         One transaction per generation: a killed run loses at most the
//                         generation in progress and resumes from the last committed one.
//                         Each generation carries a SHA-256 digest of its rows chained to the
//                         previous generation's (and, for generation 0, to the run table), so
//                         a store that was changed after the fact is caught (VerifyChain).
//   generations.csv       generation, best, mean, median, worst, wall time (s)
//   best/gen-NNNN.json    the best genome of every generation (docs/genome.md)
//   best.json             the best genome of the run so far (after a validation: the chosen one)
// The CSV and JSON files are exports of the database, rewritten atomically after each commit
// (and on resume), so they never disagree with it for long and are never half-written.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/file_lock.h"
#include "evolver/ga/ga.h"
#include "modules/core/genome.h"

struct sqlite3;

namespace ahhs::evolver {

// Thrown for every problem with a run directory; what() is a message for the user.
class RunStoreError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One episode of an individual evaluated on several trials (robust evolution).
struct TrialRecord {
  int trial = 0;
  std::uint64_t seed = 0;
  Evaluation evaluation;
};

struct IndividualRecord {
  int generation = 0;
  int index = 0;
  modules::Genome genome;
  bool elite = false;               // copied unchanged from the previous generation
  std::uint64_t eval_seed = 0;      // the first trial's
  Evaluation evaluation;            // with several trials: their aggregate (ga.h, StepGeneration)
  std::vector<TrialRecord> trials;  // every trial when there are several; empty with one
};

// One candidate of the validation that chooses a run's best (docs/evolution.md, "Validation"):
// an individual of the run evaluated again on the run's validation episodes.
struct ValidationRecord {
  int candidate = 0;  // its place among the candidates, 0 first (ties go to the lower)
  int generation = 0;
  int index = 0;
  std::vector<std::uint64_t> seeds;  // one per validation episode, the same for every candidate
  std::vector<double> fitness;       // one per validation episode
  // The median of `fitness` (what chooses the best).
  double Median() const;
};

struct GenerationRecord {
  int generation = 0;
  GenerationStats stats;
  double wall_time = 0;  // seconds from the first job issued to the last result
  int session = 0;
};

// A run directory is written by one process at a time: Create and Open(kWrite) hold an exclusive
// lock on `run.lock` in it for the store's lifetime (released by the kernel when the process dies,
// so kill -9 leaves no stale lock). Readers (kRead) take no lock.
enum class StoreAccess { kRead, kWrite };

class RunStore {
 public:
  // Version 2 stores a generation's genomes in full only every kGenomeCheckpoint generations
  // (0, 20, 40, ...); the others keep each genome's hash, and reading one re-derives its
  // generation by breeding from the full generation before it (the GA is a pure function of a
  // generation's genomes and fitness and the run seed: evolver/ga/ga.h), checked against the
  // hashes. Version 3 is version 2 with the digest chain. Version 4 adds the trials table (one
  // row per trial of an individual evaluated several times), chained with its generation.
  // Version 1 (every genome in full, no chain) is read and resumed as it is; version 3 is read
  // and resumed as it is (a version-3 run has one trial); Open(kWrite) brings version 2 to 4,
  // Compact 1 to 4.
  static constexpr int kFormatVersion = 4;
  static constexpr int kGenomeCheckpoint = 20;
  static std::string FormatVersionLine() {  // for --version
    return "run store format " + std::to_string(kFormatVersion);
  }

  // Makes a new run directory. Refuses an existing non-empty directory unless `overwrite`, in
  // which case the old run's files are removed first. `config` and `physics` (the version of
  // the physics its fitnesses are measured with, sim::PhysicsVersion) are stored verbatim.
  // Refuses a directory that another process is writing.
  static std::unique_ptr<RunStore> Create(const std::string& dir, const std::string& run_id,
                                          std::uint64_t run_seed, const nlohmann::json& config,
                                          const std::string& physics, bool overwrite);
  // Opens an existing run (kWrite to resume it, kRead to read it). Checks that it is a run
  // directory of this format and that its database is intact; kWrite also verifies the digest
  // chain (VerifyChain), and refuses a directory that another process is writing.
  static std::unique_ptr<RunStore> Open(const std::string& dir,
                                        StoreAccess access = StoreAccess::kWrite);
  // True when a process holds the write lock of `dir` (a run in progress).
  static bool InUse(const std::string& dir);
  ~RunStore();
  RunStore(const RunStore&) = delete;
  RunStore& operator=(const RunStore&) = delete;

  const std::string& dir() const { return dir_; }
  const std::string& run_id() const { return run_id_; }
  std::uint64_t run_seed() const { return run_seed_; }
  const nlohmann::json& config() const { return config_; }
  // The physics version stored by Create; "" for runs made before it was stored (2026-12-01).
  const std::string& physics() const { return physics_; }

  // Records a new session (the first start or a resume) and returns its number (1, 2, ...).
  int BeginSession(const std::string& command_line);

  // The highest committed generation, -1 when none.
  int LastGeneration() const;
  std::vector<IndividualRecord> LoadGeneration(int generation) const;
  // One individual; throws RunStoreError when it is not stored.
  IndividualRecord LoadIndividual(int generation, int index) const;
  std::vector<GenerationRecord> LoadGenerationRecords() const;

  // Stores a whole generation in one transaction, then rewrites the exports.
  void CommitGeneration(const GenerationRecord& record,
                        const std::vector<IndividualRecord>& individuals);

  // Brings a version-1 run to version 3 (store opened kWrite): after checking that every
  // generation is exactly what breeding the one before gives (a run of another build's
  // variation is refused and left as it was), the genomes of the generations that are not
  // checkpoints are dropped, the generations chained and the database vacuumed. Returns the bytes
  // saved.
  std::uint64_t Compact();
  int format_version() const { return format_version_; }

  // Checks that the generations are 0 to LastGeneration() and that each one's rows match its
  // digest. Throws RunStoreError naming the first generation that does not ("... generation 57
  // does not match its digest ... generations 0-56 are intact"). A version-1 run has no chain:
  // only the numbering is checked. Returns the number of generations checked against digests.
  int VerifyChain() const;

  // Rewrites generations.csv and best.json from the database, and writes best/gen-NNNN.json for
  // generations that have none. `check_existing` (a resume) also rewrites a best file that is
  // not the whole, right genome file (short, damaged, another individual).
  void Export(bool check_existing = false) const;

  // The run's best: after a validation the candidate with the highest validation median (the
  // lowest candidate number on ties), otherwise TrainingBest().
  IndividualRecord Best() const;
  // The individual with the highest fitness (earliest on ties).
  IndividualRecord TrainingBest() const;
  // The `count` best distinct genomes of the run, by fitness (each where it scored highest,
  // earliest on ties), best first.
  std::vector<IndividualRecord> BestDistinct(int count) const;

  // Stores a validation (replacing any earlier one) in one transaction, then rewrites the
  // exports: best.json is the chosen candidate from then on. Every candidate must be a stored
  // individual with as many fitnesses as seeds, all finite.
  void CommitValidation(const std::vector<ValidationRecord>& candidates);
  // The stored validation, by candidate; empty when the run has none.
  std::vector<ValidationRecord> LoadValidation() const;

 private:
  RunStore(std::string dir, sqlite3* db, std::optional<base::FileLock> lock);
  void Exec(const char* sql) const;
  void LoadRunTable();
  std::vector<IndividualRecord> LoadIndividuals(int generation, int index) const;  // -1: all
  // Every genome of a generation stored by hash only, bred again from the newest full one.
  const std::vector<modules::Genome>& Rederive(int generation) const;
  bool StoresInFull(int generation) const;
  bool Chained() const { return format_version_ >= 3; }
  bool HasTrials() const { return format_version_ >= 4; }
  bool HasTable(const char* name) const;
  // The digest of `generation`'s rows after `previous` (the run table's digest for generation 0).
  std::string GenerationDigest(int generation, const std::string& previous) const;
  std::string RunTableDigest() const;
  bool BestFileIsWhole(const std::filesystem::path& path, const GenerationRecord& g) const;
  // Digests every generation again (after Compact, or to chain a version-2 run) and sets
  // version 3; inside the caller's transaction.
  void RebuildChain();
  std::uint64_t BreedingSeed() const;

  std::string dir_;
  sqlite3* db_ = nullptr;
  std::optional<base::FileLock> lock_;  // the write lock; none for a reader
  std::string run_id_;
  std::uint64_t run_seed_ = 0;
  nlohmann::json config_;
  std::string physics_;
  int format_version_ = kFormatVersion;
  mutable int rederived_generation_ = -1;  // cache of Rederive
  mutable std::vector<modules::Genome> rederived_;
};

}  // namespace ahhs::evolver
