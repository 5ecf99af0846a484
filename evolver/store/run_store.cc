#include "evolver/store/run_store.h"

#include <glib.h>
#include <sqlite3.h>
#include <sys/statvfs.h>
#include <sys/vfs.h>
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
#include "modules/core/genome_json.h"

namespace ahhs::evolver {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* kDatabaseName = "run.sqlite";
constexpr const char* kFormatName = "ahhs-run";
constexpr const char* kLockName = "run.lock";
// Version 4's table: every trial of an individual evaluated several times.
constexpr const char* kTrialsTable =
    "CREATE TABLE IF NOT EXISTS trials(generation INTEGER NOT NULL, idx INTEGER NOT NULL,"
    "  trial INTEGER NOT NULL, seed INTEGER NOT NULL, fitness REAL NOT NULL,"
    "  cost REAL NOT NULL, worker TEXT NOT NULL, attempt INTEGER NOT NULL,"
    "  wall_time REAL NOT NULL, message TEXT NOT NULL, PRIMARY KEY(generation, idx, trial));";

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

// "; the filesystem holding it is full (N kB free)" when the filesystem of `path` has less
// than 1 MiB left: SQLite then reports "disk I/O error" or "database or disk is full".
std::string FullDiskNote(const fs::path& path) {
  struct statvfs st {};
  if (::statvfs(path.c_str(), &st) != 0) return "";
  const unsigned long long free_bytes =
      static_cast<unsigned long long>(st.f_bavail) * static_cast<unsigned long long>(st.f_frsize);
  if (free_bytes >= (1ULL << 20)) return "";
  return "; the filesystem holding it is full (" + std::to_string(free_bytes / 1024) + " kB free)";
}

// "PATH: what SQLite says" for the database's last error.
std::string DatabaseError(sqlite3* db) {
  const char* file = sqlite3_db_filename(db, "main");
  const std::string path = file != nullptr && *file != '\0' ? file : "run database";
  return path + ": " + sqlite3_errmsg(db) + FullDiskNote(fs::path(path).parent_path());
}

// One prepared statement; finalised on scope exit.
class Statement {
 public:
  Statement(sqlite3* db, const char* sql) : db_(db) {
    if (sqlite3_prepare_v2(db, sql, -1, &stmt_, nullptr) != SQLITE_OK)
      throw RunStoreError(DatabaseError(db));
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  Statement& Bind(int i, std::int64_t v) {
    Check(sqlite3_bind_int64(stmt_, i, v));
    return *this;
  }
  Statement& Bind(int i, double v) {
    Check(sqlite3_bind_double(stmt_, i, v));
    return *this;
  }
  Statement& Bind(int i, const std::string& v) {
    Check(sqlite3_bind_text(stmt_, i, v.c_str(), static_cast<int>(v.size()), SQLITE_TRANSIENT));
    return *this;
  }
  // True while there is a row.
  bool Step() {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    throw RunStoreError(DatabaseError(db_));
  }
  void Run() {
    Step();
    Reset();
  }
  void Reset() {
    sqlite3_reset(stmt_);
    sqlite3_clear_bindings(stmt_);
  }
  std::int64_t Int(int col) const { return sqlite3_column_int64(stmt_, col); }
  bool IsNull(int col) const { return sqlite3_column_type(stmt_, col) == SQLITE_NULL; }
  double Real(int col) const { return sqlite3_column_double(stmt_, col); }
  std::string Text(int col) const {
    const unsigned char* t = sqlite3_column_text(stmt_, col);
    return t ? reinterpret_cast<const char*>(t) : "";
  }

 private:
  void Check(int rc) {
    if (rc != SQLITE_OK) throw RunStoreError(DatabaseError(db_));
  }
  friend class Digest;
  sqlite3* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

// SHA-256 (GLib's GChecksum) over rows exactly as SQLite stores them: each value's type and
// its bytes (integers as 8 bytes, reals as their 8 IEEE bytes, text with its length).
class Digest {
 public:
  Digest() : sum_(g_checksum_new(G_CHECKSUM_SHA256)) {}
  ~Digest() { g_checksum_free(sum_); }
  Digest(const Digest&) = delete;
  Digest& operator=(const Digest&) = delete;

  void AddText(const std::string& text) {
    AddInt(static_cast<std::int64_t>(text.size()));
    g_checksum_update(sum_, reinterpret_cast<const guchar*>(text.data()),
                      static_cast<gssize>(text.size()));
  }
  // Every row `statement` gives, all columns.
  void AddRows(Statement& statement) {
    sqlite3_stmt* stmt = statement.stmt_;
    std::int64_t rows = 0;
    while (statement.Step()) {
      ++rows;
      const int columns = sqlite3_column_count(stmt);
      for (int c = 0; c < columns; ++c) {
        const int type = sqlite3_column_type(stmt, c);
        AddByte(static_cast<unsigned char>(type));
        if (type == SQLITE_INTEGER) {
          AddInt(sqlite3_column_int64(stmt, c));
        } else if (type == SQLITE_FLOAT) {
          const double v = sqlite3_column_double(stmt, c);
          std::uint64_t bits;
          std::memcpy(&bits, &v, sizeof bits);
          AddInt(static_cast<std::int64_t>(bits));
        } else if (type != SQLITE_NULL) {
          const auto* bytes = static_cast<const char*>(sqlite3_column_blob(stmt, c));
          AddText(std::string(bytes != nullptr ? bytes : "",
                              static_cast<std::size_t>(sqlite3_column_bytes(stmt, c))));
        }
      }
    }
    AddInt(rows);
  }
  std::string Hex() { return g_checksum_get_string(sum_); }

 private:
  void AddByte(unsigned char b) { g_checksum_update(sum_, &b, 1); }
  void AddInt(std::int64_t v) {
    unsigned char bytes[8];
    for (int k = 0; k < 8; ++k)
      bytes[k] = static_cast<unsigned char>(static_cast<std::uint64_t>(v) >> (8 * k));
    g_checksum_update(sum_, bytes, 8);
  }
  GChecksum* sum_;
};

// Microseconds since the Unix epoch (the store's timestamps, as on the wire).
std::int64_t NowUtime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// SQLite integers are signed 64-bit; seeds are unsigned: store the same bits.
std::int64_t ToSql(std::uint64_t v) { return static_cast<std::int64_t>(v); }
std::uint64_t FromSql(std::int64_t v) { return static_cast<std::uint64_t>(v); }

// The exports, written whole or not at all (atomic_file.h), with the store's error type.
void WriteExport(const fs::path& path, const std::string& text) {
  try {
    base::WriteFileAtomically(path.string(), text);
  } catch (const std::runtime_error& e) {
    throw RunStoreError(e.what());
  }
}

// SQLite's WAL keeps its index in shared memory beside the database, which a network
// filesystem does not share between hosts, and NFS locking is unreliable with it: a run directory
// on one gets a rollback journal instead (docs/evolution.md, "On a Slurm cluster"). The journal
// mode never changes what is stored.
bool OnNetworkFilesystem(const fs::path& dir) {
  struct statfs st {};
  if (::statfs(dir.c_str(), &st) != 0) return false;
  switch (static_cast<unsigned long>(st.f_type)) {
    case 0x6969UL:      // NFS
    case 0xFF534D42UL:  // CIFS
    case 0xFE534D42UL:  // SMB2
    case 0x517BUL:      // SMB
    case 0x0BD00BD0UL:  // Lustre
    case 0x47504653UL:  // GPFS
    case 0x19830326UL:  // BeeGFS
    case 0x00C36400UL:  // CephFS
    case 0x013111A8UL:  // IBRIX
    case 0x65735546UL:  // FUSE (sshfs, s3fs, ...)
      return true;
    default:
      return false;
  }
}

const char* JournalPragma(const fs::path& dir) {
  return OnNetworkFilesystem(dir) ? "PRAGMA journal_mode=DELETE;" : "PRAGMA journal_mode=WAL;";
}

sqlite3* OpenDatabase(const fs::path& path, int flags) {
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(path.c_str(), &db, flags, nullptr) != SQLITE_OK) {
    const std::string why = db ? sqlite3_errmsg(db) : "out of memory";
    sqlite3_close(db);
    throw RunStoreError(path.string() + ": cannot open the run database: " + why +
                        FullDiskNote(path.parent_path()));
  }
  sqlite3_busy_timeout(db, 5000);
  return db;
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
  return format_version_ < 2 || generation % kGenomeCheckpoint == 0;
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

std::uint64_t RunStore::Compact() {
  if (!lock_) throw RunStoreError(dir_ + ": compacting needs the run opened for writing");
  if (format_version_ >= 2) return 0;  // Open(kWrite) has chained a version-2 run already
  const fs::path db_path = fs::path(dir_) / kDatabaseName;
  std::error_code ec;
  const auto before = fs::file_size(db_path, ec);
  GaParams ga;
  try {
    ga = GaParamsFromJson(config_);
  } catch (const std::exception& e) {
    throw RunStoreError(dir_ + ": run config: " + e.what());
  }
  // First check that every generation is what breeding its stored parents gives (so that
  // version 2 can breed it again from a checkpoint); only then drop anything.
  const int last = LastGeneration();
  std::vector<IndividualRecord> parents =
      last >= 0 ? LoadIndividuals(0, -1) : std::vector<IndividualRecord>{};
  for (int g = 1; g <= last; ++g) {
    std::vector<modules::Genome> genomes;
    std::vector<double> fitness;
    for (const auto& r : parents) {
      genomes.push_back(r.genome);
      fitness.push_back(r.evaluation.fitness);
    }
    const std::vector<modules::Genome> bred = Breed(genomes, fitness, ga, BreedingSeed(), g);
    parents = LoadIndividuals(g, -1);
    bool same = bred.size() == parents.size();
    for (std::size_t i = 0; same && i < bred.size(); ++i)
      same = modules::GenomeHash(bred[i]) == modules::GenomeHash(parents[i].genome);
    if (!same)
      throw RunStoreError(dir_ + ": generation " + std::to_string(g) +
                          " is not what breeding generation " + std::to_string(g - 1) +
                          " gives with this build (a run of another build's variation): left "
                          "as it is");
  }
  Exec("BEGIN IMMEDIATE");
  try {
    Statement drop(db_, "UPDATE individuals SET genome = '' WHERE generation % ? != 0");
    drop.Bind(1, static_cast<std::int64_t>(kGenomeCheckpoint)).Run();
    RebuildChain();
    Exec("COMMIT");
  } catch (...) {
    sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    format_version_ = 1;
    throw;
  }
  rederived_generation_ = -1;
  Exec("VACUUM");
  sqlite3_exec(db_, "PRAGMA wal_checkpoint(TRUNCATE)", nullptr, nullptr, nullptr);  // WAL mode
  const auto after = fs::file_size(db_path, ec);
  return before > after ? before - after : 0;
}

bool RunStore::BestFileIsWhole(const fs::path& path, const GenerationRecord& g) const {
  Statement stored(db_, "SELECT genome_hash FROM individuals WHERE generation = ? AND idx = ?");
  stored.Bind(1, static_cast<std::int64_t>(g.generation))
      .Bind(2, static_cast<std::int64_t>(g.stats.best_index));
  if (!stored.Step()) return false;
  try {
    json meta;
    const modules::Genome genome = modules::LoadGenomeFile(path.string(), &meta);
    return stored.Text(0) == modules::GenomeHashText(genome) &&
           meta.at("generation").get<int>() == g.generation &&
           meta.at("individual").get<int>() == g.stats.best_index &&
           meta.at("fitness").get<double>() == g.stats.best;
  } catch (const std::exception&) {
    return false;
  }
}

std::string RunStore::RunTableDigest() const {
  // format_version is left out: a run changes version (Compact, chaining) without changing.
  Digest digest;
  Statement rows(db_, "SELECT key, value FROM run WHERE key != 'format_version' ORDER BY key");
  digest.AddRows(rows);
  return digest.Hex();
}

std::string RunStore::GenerationDigest(int generation, const std::string& previous) const {
  Digest digest;
  digest.AddText(previous);
  Statement row(db_,
                "SELECT generation, best, mean, median, worst, best_index, wall_time, session, "
                "committed_utime FROM generations WHERE generation = ?");
  row.Bind(1, static_cast<std::int64_t>(generation));
  digest.AddRows(row);
  Statement individuals(db_,
                        "SELECT generation, idx, genome, genome_hash, elite, eval_seed, fitness, "
                        "cost, worker, attempt, wall_time, message FROM individuals "
                        "WHERE generation = ? ORDER BY idx");
  individuals.Bind(1, static_cast<std::int64_t>(generation));
  digest.AddRows(individuals);
  if (HasTrials() && config_.value("trials", 1) > 1) {  // with one trial: version 3's digest
    Statement trials(db_,
                     "SELECT generation, idx, trial, seed, fitness, cost, worker, attempt, "
                     "wall_time, message FROM trials WHERE generation = ? ORDER BY idx, trial");
    trials.Bind(1, static_cast<std::int64_t>(generation));
    digest.AddRows(trials);
  }
  return digest.Hex();
}

void RunStore::RebuildChain() {
  Exec(
      "CREATE TABLE IF NOT EXISTS chain(generation INTEGER PRIMARY KEY, digest TEXT NOT NULL);"
      "DELETE FROM chain;");
  Exec(kTrialsTable);
  format_version_ = kFormatVersion;  // the digests below are this version's
  Statement add(db_, "INSERT INTO chain(generation, digest) VALUES(?, ?)");
  std::string previous = RunTableDigest();
  for (const auto& g : LoadGenerationRecords()) {
    previous = GenerationDigest(g.generation, previous);
    add.Bind(1, static_cast<std::int64_t>(g.generation)).Bind(2, previous).Run();
  }
  Statement version(db_, "UPDATE run SET value = ? WHERE key = 'format_version'");
  version.Bind(1, std::to_string(kFormatVersion)).Run();
  format_version_ = kFormatVersion;
  rederived_generation_ = -1;
}

int RunStore::VerifyChain() const {
  const auto intact = [](int g) {
    return g == 0   ? std::string("no generation is intact")
           : g == 1 ? std::string("generation 0 is intact")
                    : "generations 0-" + std::to_string(g - 1) + " are intact";
  };
  const std::string file = dir_ + "/" + kDatabaseName;
  std::vector<int> generations;
  {
    Statement all(db_, "SELECT generation FROM generations ORDER BY generation");
    while (all.Step()) generations.push_back(static_cast<int>(all.Int(0)));
  }
  for (std::size_t k = 0; k < generations.size(); ++k)
    if (generations[k] != static_cast<int>(k))
      throw RunStoreError(file + ": generation " + std::to_string(k) + " is missing (" +
                          intact(static_cast<int>(k)) + "): the store is damaged");
  {
    Statement orphan(db_,
                     "SELECT MIN(generation) FROM individuals WHERE generation NOT IN "
                     "(SELECT generation FROM generations)");
    if (orphan.Step() && !orphan.IsNull(0))
      throw RunStoreError(file + ": individuals of generation " + std::to_string(orphan.Int(0)) +
                          " belong to no stored generation: the store is damaged");
  }
  if (HasTrials()) {
    Statement orphan(db_,
                     "SELECT MIN(generation) FROM trials WHERE generation NOT IN "
                     "(SELECT generation FROM generations)");
    if (orphan.Step() && !orphan.IsNull(0))
      throw RunStoreError(file + ": trials of generation " + std::to_string(orphan.Int(0)) +
                          " belong to no stored generation: the store is damaged");
  }
  if (!Chained()) return 0;
  Statement stored(db_, "SELECT digest FROM chain WHERE generation = ?");
  std::string previous = RunTableDigest();
  for (const int g : generations) {
    previous = GenerationDigest(g, previous);
    stored.Bind(1, static_cast<std::int64_t>(g));
    const bool has = stored.Step();
    const std::string digest = has ? stored.Text(0) : "";
    stored.Reset();
    if (digest != previous)
      throw RunStoreError(file + ": generation " + std::to_string(g) +
                          (g == 0 ? " (or the run's configuration)" : "") +
                          (has ? " does not match its digest" : " has no digest") +
                          ": the store was changed or damaged after it was written (" + intact(g) +
                          "); refusing to use it");
  }
  Statement extra(db_, "SELECT COUNT(*) FROM chain WHERE generation > ?");
  extra.Bind(1, static_cast<std::int64_t>(generations.size()) - 1);
  if (extra.Step() && extra.Int(0) > 0)
    throw RunStoreError(file + ": generation " + std::to_string(generations.size()) +
                        " has a digest but no rows (" +
                        intact(static_cast<int>(generations.size())) + "): the store is damaged");
  return static_cast<int>(generations.size());
}

IndividualRecord RunStore::Best() const {
  Statement best(db_,
                 "SELECT generation, idx FROM individuals ORDER BY fitness DESC, generation, idx "
                 "LIMIT 1");
  if (!best.Step()) throw RunStoreError(dir_ + ": the run has no evaluated individual yet");
  return LoadIndividual(static_cast<int>(best.Int(0)), static_cast<int>(best.Int(1)));
}

void RunStore::Export(bool check_existing) const {
  const fs::path root(dir_);
  std::ostringstream csv;
  csv << "generation,best,mean,median,worst,best_index,wall_time_s\n";
  const auto generations = LoadGenerationRecords();
  for (const auto& g : generations)
    csv << g.generation << ',' << base::ExactDouble(g.stats.best) << ','
        << base::ExactDouble(g.stats.mean) << ',' << base::ExactDouble(g.stats.median) << ','
        << base::ExactDouble(g.stats.worst) << ',' << g.stats.best_index << ','
        << base::ExactDouble(g.wall_time) << '\n';
  WriteExport(root / "generations.csv", csv.str());
  std::error_code ec;
  fs::create_directories(root / "best", ec);
  auto meta = [&](const IndividualRecord& r) {
    json m{{"run", run_id_},
           {"generation", r.generation},
           {"individual", r.index},
           {"fitness", r.evaluation.fitness},
           {"cost", r.evaluation.cost},
           {"eval_seed", r.eval_seed},
           {"config", config_}};
    if (!physics_.empty()) m["physics"] = physics_;  // a replay takes the same physics
    if (!r.trials.empty()) {  // `fitness` is their aggregate; `eval_seed` the first trial's
      json trials = json::array();
      for (const auto& t : r.trials)
        trials.push_back({{"seed", t.seed}, {"fitness", t.evaluation.fitness}});
      m["trials"] = trials;
    }
    return m;
  };
  for (const auto& g : generations) {
    char name[32];
    std::snprintf(name, sizeof name, "gen-%04d.json", g.generation);
    const fs::path path = root / "best" / name;
    if (fs::exists(path, ec) && (!check_existing || BestFileIsWhole(path, g))) continue;
    const IndividualRecord r = LoadIndividual(g.generation, g.stats.best_index);
    modules::SaveGenomeFile(path.string(), r.genome, meta(r));
  }
  if (!generations.empty()) {
    const IndividualRecord best = Best();
    modules::SaveGenomeFile((root / "best.json").string(), best.genome, meta(best));
  }
}

}  // namespace ahhs::evolver
