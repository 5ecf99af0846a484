#include "evolver/store/run_store.h"

#include <sqlite3.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/atomic_file.h"
#include "base/format.h"
#include "evolver/store/run_layout.h"
#include "evolver/store/sqlite_db.h"
#include "modules/core/genome_json.h"

namespace ahhs::evolver {

namespace fs = std::filesystem;
using nlohmann::json;
using run_layout::FromSql;
using run_layout::kDatabaseName;
using run_layout::kFormatName;
using run_layout::kLockName;
using run_layout::kTrialsTable;
using run_layout::ToSql;
using run_layout::WriteExport;
using sqlite::DatabaseError;
using sqlite::Digest;
using sqlite::FullDiskNote;
using sqlite::JournalPragma;
using sqlite::OpenDatabase;
using sqlite::Statement;

namespace {

// The write lock of a run directory. Throws when another process holds it or the lock file
// cannot be made.
base::FileLock LockOrThrow(const fs::path& root) {
  std::optional<base::FileLock> lock;
  try {
    lock = base::FileLock::TryExclusive((root / kLockName).string());
  } catch (const std::runtime_error& e) {
    throw RunStoreError(std::string(e.what()) +
                        " (a run directory must be writable to be written or resumed)");
  }
  if (!lock)
    throw RunStoreError(root.string() +
                        " is in use: another process (ahhs-evolve) is writing this run");
  return std::move(*lock);
}

// Microseconds since the Unix epoch (the store's timestamps, as on the wire).
std::int64_t NowUtime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace

RunStore::RunStore(std::string dir, sqlite3* db, std::optional<base::FileLock> lock)
    : dir_(std::move(dir)), db_(db), lock_(std::move(lock)) {}

RunStore::~RunStore() { sqlite3_close(db_); }

bool RunStore::InUse(const std::string& dir) {
  return base::FileLock::HeldElsewhere((fs::path(dir) / kLockName).string());
}

void RunStore::Exec(const char* sql) const {
  char* error = nullptr;
  if (sqlite3_exec(db_, sql, nullptr, nullptr, &error) != SQLITE_OK) {
    const std::string why = error ? error : "unknown error";
    sqlite3_free(error);
    throw RunStoreError(dir_ + "/" + kDatabaseName + ": " + why + FullDiskNote(dir_));
  }
}

std::unique_ptr<RunStore> RunStore::Create(const std::string& dir, const std::string& run_id,
                                           std::uint64_t run_seed, const json& config,
                                           const std::string& physics, bool overwrite) {
  const fs::path root(dir);
  std::error_code ec;
  if (fs::exists(root, ec)) {
    if (!fs::is_directory(root, ec)) throw RunStoreError(dir + " exists and is not a directory");
    if (!fs::is_empty(root, ec)) {
      if (!overwrite)
        throw RunStoreError(dir + " already holds files; continue that run with --resume " + dir +
                            ", or pass --overwrite to replace it");
    }
  }
  fs::create_directories(root, ec);
  if (ec) throw RunStoreError("cannot create " + dir + ": " + ec.message());
  base::FileLock lock = LockOrThrow(root);
  for (const auto& entry : fs::directory_iterator(root))
    if (entry.path().filename() != kLockName) fs::remove_all(entry.path(), ec);
  fs::create_directories(root / "best", ec);
  if (ec) throw RunStoreError("cannot create " + dir + ": " + ec.message());
  sqlite3* db = OpenDatabase(root / kDatabaseName, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE);
  std::unique_ptr<RunStore> store(new RunStore(dir, db, std::move(lock)));
  store->Exec(JournalPragma(root));
  store->Exec(
      "PRAGMA synchronous=NORMAL;"
      "CREATE TABLE run(key TEXT PRIMARY KEY, value TEXT NOT NULL);"
      "CREATE TABLE sessions(session INTEGER PRIMARY KEY, started_utime INTEGER NOT NULL,"
      "  command TEXT NOT NULL);"
      "CREATE TABLE generations(generation INTEGER PRIMARY KEY, best REAL NOT NULL,"
      "  mean REAL NOT NULL, median REAL NOT NULL, worst REAL NOT NULL,"
      "  best_index INTEGER NOT NULL, wall_time REAL NOT NULL, session INTEGER NOT NULL,"
      "  committed_utime INTEGER NOT NULL);"
      "CREATE TABLE individuals(generation INTEGER NOT NULL, idx INTEGER NOT NULL,"
      "  genome TEXT NOT NULL, genome_hash TEXT NOT NULL, elite INTEGER NOT NULL,"
      "  eval_seed INTEGER NOT NULL, fitness REAL NOT NULL, cost REAL NOT NULL,"
      "  worker TEXT NOT NULL, attempt INTEGER NOT NULL, wall_time REAL NOT NULL,"
      "  message TEXT NOT NULL, PRIMARY KEY(generation, idx));"
      "CREATE TABLE chain(generation INTEGER PRIMARY KEY, digest TEXT NOT NULL);");
  store->Exec(kTrialsTable);
  {
    store->Exec("BEGIN");
    Statement put(db, "INSERT INTO run(key, value) VALUES(?, ?)");
    put.Bind(1, std::string("format")).Bind(2, std::string(kFormatName)).Run();
    put.Bind(1, std::string("format_version")).Bind(2, std::to_string(kFormatVersion)).Run();
    put.Bind(1, std::string("run_id")).Bind(2, run_id).Run();
    put.Bind(1, std::string("seed")).Bind(2, std::to_string(run_seed)).Run();
    put.Bind(1, std::string("config")).Bind(2, config.dump()).Run();
    put.Bind(1, std::string("physics")).Bind(2, physics).Run();
    put.Bind(1, std::string("created_utime")).Bind(2, std::to_string(NowUtime())).Run();
    store->Exec("COMMIT");
  }
  store->LoadRunTable();
  store->Export();
  return store;
}

std::unique_ptr<RunStore> RunStore::Open(const std::string& dir, StoreAccess access) {
  const fs::path root(dir);
  std::error_code ec;
  if (!fs::is_directory(root, ec)) throw RunStoreError(dir + " is not a directory");
  if (!fs::exists(root / kDatabaseName, ec))
    throw RunStoreError(dir + " is not a run directory (no " + kDatabaseName + ")");
  std::optional<base::FileLock> lock;
  if (access == StoreAccess::kWrite) lock = LockOrThrow(root);
  sqlite3* db = OpenDatabase(root / kDatabaseName, SQLITE_OPEN_READWRITE);
  std::unique_ptr<RunStore> store(new RunStore(dir, db, std::move(lock)));
  try {
    Statement check(db, "PRAGMA quick_check");
    if (!check.Step() || check.Text(0) != "ok")
      throw RunStoreError("integrity check failed: " + check.Text(0));
    store->LoadRunTable();
  } catch (const RunStoreError& e) {
    const std::string full = FullDiskNote(root);
    if (!full.empty()) throw RunStoreError(e.what());  // the disk, not the database
    throw RunStoreError(dir + ": not a readable run database (" + e.what() + ")");
  }
  if (access == StoreAccess::kWrite) {
    fs::create_directories(root / "best", ec);
    store->Exec(JournalPragma(root));   // a run may move between filesystems between sessions
    if (store->format_version_ == 2) {  // chain it: from now on, changes are caught
      store->Exec("BEGIN IMMEDIATE");
      try {
        store->RebuildChain();
        store->Exec("COMMIT");
      } catch (...) {
        sqlite3_exec(db, "ROLLBACK", nullptr, nullptr, nullptr);
        store->format_version_ = 2;
        throw;
      }
    }
    store->VerifyChain();
  }
  return store;
}

void RunStore::LoadRunTable() {
  json values = json::object();
  Statement get(db_, "SELECT key, value FROM run");
  while (get.Step()) values[get.Text(0)] = get.Text(1);
  if (values.value("format", "") != kFormatName)
    throw RunStoreError("the database is not an ahhs run");
  const std::string version = values.value("format_version", "");
  if (version != "1" && version != "2" && version != "3" &&
      version != std::to_string(kFormatVersion))
    throw RunStoreError("run format version " + (version.empty() ? "?" : version) +
                        " is not supported (this build reads versions 1 to " +
                        std::to_string(kFormatVersion) + ")");
  format_version_ = std::stoi(version);
  run_id_ = values.value("run_id", "");
  physics_ = values.value("physics", "");
  try {
    run_seed_ = std::stoull(values.value("seed", ""));
    config_ = json::parse(values.value("config", ""));
  } catch (const std::exception& e) {
    throw RunStoreError(std::string("run table: ") + e.what());
  }
}

int RunStore::BeginSession(const std::string& command_line) {
  Statement add(db_, "INSERT INTO sessions(started_utime, command) VALUES(?, ?)");
  add.Bind(1, NowUtime()).Bind(2, command_line).Run();
  return static_cast<int>(sqlite3_last_insert_rowid(db_));
}

int RunStore::LastGeneration() const {
  Statement last(db_, "SELECT COALESCE(MAX(generation), -1) FROM generations");
  last.Step();
  return static_cast<int>(last.Int(0));
}

std::vector<IndividualRecord> RunStore::LoadGeneration(int generation) const {
  return LoadIndividuals(generation, -1);
}

IndividualRecord RunStore::LoadIndividual(int generation, int index) const {
  auto found = LoadIndividuals(generation, index);
  if (found.empty())
    throw RunStoreError(dir_ + ": generation " + std::to_string(generation) + " individual " +
                        std::to_string(index) + " is not stored");
  return found.front();
}

std::uint64_t RunStore::BreedingSeed() const {
  // The seed the evolution bred with: its config's (RunEvolution takes the config's seed).
  try {
    return config_.at("seed").get<std::uint64_t>();
  } catch (const std::exception& e) {
    throw RunStoreError(dir_ + ": run config: " + e.what());
  }
}

bool RunStore::StoresInFull(int generation) const {
  // A run of another optimizer (ahhs-evaluate --out) cannot be bred again: every genome in full.
  return format_version_ < 2 || generation % kGenomeCheckpoint == 0 ||
         config_.contains("optimizer");
}

const std::vector<modules::Genome>& RunStore::Rederive(int generation) const {
  if (rederived_generation_ == generation) return rederived_;
  // The newest generation at or before `generation` whose genomes are all stored.
  Statement full(db_,
                 "SELECT MAX(generation) FROM generations WHERE generation <= ? AND generation "
                 "NOT IN (SELECT generation FROM individuals WHERE genome = '')");
  full.Bind(1, static_cast<std::int64_t>(generation));
  if (!full.Step() || full.IsNull(0))
    throw RunStoreError(dir_ + ": no generation stored in full before generation " +
                        std::to_string(generation));
  const int start = static_cast<int>(full.Int(0));
  GaParams ga;
  try {
    ga = GaParamsFromJson(config_);
  } catch (const std::exception& e) {
    throw RunStoreError(dir_ + ": run config: " + e.what());
  }
  std::vector<modules::Genome> population;
  std::vector<double> fitness;
  for (const auto& r : LoadIndividuals(start, -1)) {
    population.push_back(r.genome);
    fitness.push_back(r.evaluation.fitness);
  }
  for (int g = start + 1; g <= generation; ++g) {
    population = Breed(population, fitness, ga, BreedingSeed(), g);
    if (g == generation) break;
    fitness.clear();
    Statement get(db_, "SELECT fitness FROM individuals WHERE generation = ? ORDER BY idx");
    get.Bind(1, static_cast<std::int64_t>(g));
    while (get.Step()) fitness.push_back(get.Real(0));
  }
  rederived_ = std::move(population);
  rederived_generation_ = generation;
  return rederived_;
}

std::vector<IndividualRecord> RunStore::LoadIndividuals(int generation, int index) const {
  std::vector<IndividualRecord> out;
  Statement get(db_,
                "SELECT idx, genome, genome_hash, elite, eval_seed, fitness, cost, worker, "
                "attempt, wall_time, message FROM individuals WHERE generation = ? "
                "AND (? < 0 OR idx = ?) ORDER BY idx");
  get.Bind(1, static_cast<std::int64_t>(generation))
      .Bind(2, static_cast<std::int64_t>(index))
      .Bind(3, static_cast<std::int64_t>(index));
  while (get.Step()) {
    IndividualRecord r;
    r.generation = generation;
    r.index = static_cast<int>(get.Int(0));
    const std::string text = get.Text(1);
    try {
      if (text.empty()) {
        const auto& bred = Rederive(generation);
        if (static_cast<std::size_t>(r.index) >= bred.size())
          throw std::runtime_error("generation " + std::to_string(generation) +
                                   " was bred with fewer individuals than are stored");
        r.genome = bred[static_cast<std::size_t>(r.index)];
      } else {
        r.genome = modules::ParseGenome(text, "generation " + std::to_string(generation) +
                                                  " individual " + std::to_string(r.index));
      }
    } catch (const RunStoreError&) {
      throw;
    } catch (const std::exception& e) {
      throw RunStoreError(dir_ + ": " + e.what());
    }
    if (get.Text(2) != modules::GenomeHashText(r.genome))
      throw RunStoreError(dir_ + ": generation " + std::to_string(generation) + " individual " +
                          std::to_string(r.index) +
                          (text.empty() ? ": the genome bred again does not match its hash (this "
                                          "build's variation differs from the run's)"
                                        : ": the genome does not match its hash"));
    r.elite = get.Int(3) != 0;
    r.eval_seed = FromSql(get.Int(4));
    r.evaluation.fitness = get.Real(5);
    r.evaluation.cost = get.Real(6);
    r.evaluation.worker = get.Text(7);
    r.evaluation.attempt = static_cast<int>(get.Int(8));
    r.evaluation.wall_time = get.Real(9);
    r.evaluation.message = get.Text(10);
    out.push_back(std::move(r));
  }
  if (HasTrials() && !out.empty()) {
    Statement trials(db_,
                     "SELECT idx, trial, seed, fitness, cost, worker, attempt, wall_time, message "
                     "FROM trials WHERE generation = ? AND (? < 0 OR idx = ?) ORDER BY idx, trial");
    trials.Bind(1, static_cast<std::int64_t>(generation))
        .Bind(2, static_cast<std::int64_t>(index))
        .Bind(3, static_cast<std::int64_t>(index));
    std::size_t k = 0;
    while (trials.Step()) {
      const int idx = static_cast<int>(trials.Int(0));
      while (k < out.size() && out[k].index < idx) ++k;
      if (k == out.size() || out[k].index != idx)
        throw RunStoreError(dir_ + ": generation " + std::to_string(generation) +
                            " has a trial of individual " + std::to_string(idx) +
                            ", which is not stored: the store is damaged");
      TrialRecord t;
      t.trial = static_cast<int>(trials.Int(1));
      t.seed = FromSql(trials.Int(2));
      t.evaluation.fitness = trials.Real(3);
      t.evaluation.cost = trials.Real(4);
      t.evaluation.worker = trials.Text(5);
      t.evaluation.attempt = static_cast<int>(trials.Int(6));
      t.evaluation.wall_time = trials.Real(7);
      t.evaluation.message = trials.Text(8);
      out[k].trials.push_back(std::move(t));
    }
  }
  return out;
}

std::vector<GenerationRecord> RunStore::LoadGenerationRecords() const {
  std::vector<GenerationRecord> out;
  Statement get(db_,
                "SELECT generation, best, mean, median, worst, best_index, wall_time, session "
                "FROM generations ORDER BY generation");
  while (get.Step()) {
    GenerationRecord r;
    r.generation = static_cast<int>(get.Int(0));
    r.stats.best = get.Real(1);
    r.stats.mean = get.Real(2);
    r.stats.median = get.Real(3);
    r.stats.worst = get.Real(4);
    r.stats.best_index = static_cast<int>(get.Int(5));
    r.wall_time = get.Real(6);
    r.session = static_cast<int>(get.Int(7));
    out.push_back(r);
  }
  return out;
}

void RunStore::CommitGeneration(const GenerationRecord& record,
                                const std::vector<IndividualRecord>& individuals) {
  Exec("BEGIN IMMEDIATE");
  try {
    Statement gen(db_,
                  "INSERT INTO generations(generation, best, mean, median, worst, best_index, "
                  "wall_time, session, committed_utime) VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?)");
    gen.Bind(1, static_cast<std::int64_t>(record.generation))
        .Bind(2, record.stats.best)
        .Bind(3, record.stats.mean)
        .Bind(4, record.stats.median)
        .Bind(5, record.stats.worst)
        .Bind(6, static_cast<std::int64_t>(record.stats.best_index))
        .Bind(7, record.wall_time)
        .Bind(8, static_cast<std::int64_t>(record.session))
        .Bind(9, NowUtime())
        .Run();
    Statement add(db_,
                  "INSERT INTO individuals(generation, idx, genome, genome_hash, elite, "
                  "eval_seed, fitness, cost, worker, attempt, wall_time, message) "
                  "VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
    for (const auto& r : individuals) {
      const std::string hash = modules::GenomeHashText(r.genome);
      add.Bind(1, static_cast<std::int64_t>(record.generation))
          .Bind(2, static_cast<std::int64_t>(r.index))
          .Bind(3, StoresInFull(record.generation) ? modules::GenomeToJson(r.genome).dump()
                                                   : std::string())
          .Bind(4, std::string(hash))
          .Bind(5, static_cast<std::int64_t>(r.elite ? 1 : 0))
          .Bind(6, ToSql(r.eval_seed))
          .Bind(7, r.evaluation.fitness)
          .Bind(8, r.evaluation.cost)
          .Bind(9, r.evaluation.worker)
          .Bind(10, static_cast<std::int64_t>(r.evaluation.attempt))
          .Bind(11, r.evaluation.wall_time)
          .Bind(12, r.evaluation.message)
          .Run();
    }
    bool any_trials = false;
    for (const auto& r : individuals) any_trials = any_trials || !r.trials.empty();
    if (any_trials && !HasTrials())
      throw RunStoreError(dir_ + ": a run of store format " + std::to_string(format_version_) +
                          " cannot hold trials: start a new run");
    if (any_trials) {
      Statement trial(db_,
                      "INSERT INTO trials(generation, idx, trial, seed, fitness, cost, worker, "
                      "attempt, wall_time, message) VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
      for (const auto& r : individuals)
        for (const auto& t : r.trials)
          trial.Bind(1, static_cast<std::int64_t>(record.generation))
              .Bind(2, static_cast<std::int64_t>(r.index))
              .Bind(3, static_cast<std::int64_t>(t.trial))
              .Bind(4, ToSql(t.seed))
              .Bind(5, t.evaluation.fitness)
              .Bind(6, t.evaluation.cost)
              .Bind(7, t.evaluation.worker)
              .Bind(8, static_cast<std::int64_t>(t.evaluation.attempt))
              .Bind(9, t.evaluation.wall_time)
              .Bind(10, t.evaluation.message)
              .Run();
    }
    if (Chained()) {
      std::string previous;
      if (record.generation == 0) {
        previous = RunTableDigest();
      } else {
        Statement last(db_, "SELECT digest FROM chain WHERE generation = ?");
        last.Bind(1, static_cast<std::int64_t>(record.generation - 1));
        if (!last.Step())
          throw RunStoreError(dir_ + ": generation " + std::to_string(record.generation - 1) +
                              " has no digest: the store is damaged");
        previous = last.Text(0);
      }
      Statement chain(db_, "INSERT INTO chain(generation, digest) VALUES(?, ?)");
      chain.Bind(1, static_cast<std::int64_t>(record.generation))
          .Bind(2, GenerationDigest(record.generation, previous))
          .Run();
    }
    Exec("COMMIT");
  } catch (...) {
    sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
  Export();
}

}  // namespace ahhs::evolver
