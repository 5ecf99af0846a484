// The run directory's files and tables as the run store keeps them (evolver/store/ only): one
// home for these facts, shared by the store's files.
#pragma once

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "base/atomic_file.h"
#include "evolver/store/run_store.h"

namespace ahhs::evolver::run_layout {

inline constexpr const char* kDatabaseName = "run.sqlite";
inline constexpr const char* kFormatName = "ahhs-run";
inline constexpr const char* kLockName = "run.lock";
// Version 4's table: every trial of an individual evaluated several times.
inline constexpr const char* kTrialsTable =
    "CREATE TABLE IF NOT EXISTS trials(generation INTEGER NOT NULL, idx INTEGER NOT NULL,"
    "  trial INTEGER NOT NULL, seed INTEGER NOT NULL, fitness REAL NOT NULL,"
    "  cost REAL NOT NULL, worker TEXT NOT NULL, attempt INTEGER NOT NULL,"
    "  wall_time REAL NOT NULL, message TEXT NOT NULL, PRIMARY KEY(generation, idx, trial));";
// The validation that chose the run's best (any version; a run without one has no such table).
inline constexpr const char* kValidationTable =
    "CREATE TABLE IF NOT EXISTS validation(candidate INTEGER NOT NULL, generation INTEGER NOT NULL,"
    "  idx INTEGER NOT NULL, episode INTEGER NOT NULL, seed INTEGER NOT NULL,"
    "  fitness REAL NOT NULL, PRIMARY KEY(candidate, episode));";

// SQLite integers are signed 64-bit; seeds are unsigned: store the same bits.
inline std::int64_t ToSql(std::uint64_t v) { return static_cast<std::int64_t>(v); }
inline std::uint64_t FromSql(std::int64_t v) { return static_cast<std::uint64_t>(v); }

// The exports, written whole or not at all (atomic_file.h), with the store's error type.
inline void WriteExport(const std::filesystem::path& path, const std::string& text) {
  try {
    base::WriteFileAtomically(path.string(), text);
  } catch (const std::runtime_error& e) {
    throw RunStoreError(e.what());
  }
}

}  // namespace ahhs::evolver::run_layout
