// The run store's SQLite access (evolver/store/run_store.h uses it; nothing else should):
// opening a database with a clear error, prepared statements, the digest of stored rows, and the
// journal mode a run directory's filesystem allows. Errors are RunStoreError.
#pragma once

#include <glib.h>
#include <sqlite3.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>

#include "evolver/store/run_store.h"

namespace ahhs::evolver::sqlite {

// "; the filesystem holding it is full (N kB free)" when the filesystem of `path` has less
// than 1 MiB left: SQLite then reports "disk I/O error" or "database or disk is full".
std::string FullDiskNote(const std::filesystem::path& path);

// "PATH: what SQLite says" for the database's last error.
std::string DatabaseError(sqlite3* db);

// Opens the database at `path` (flags of sqlite3_open_v2) with a 5 s busy timeout.
sqlite3* OpenDatabase(const std::filesystem::path& path, int flags);

// Whether `dir` is on a network filesystem (NFS, CIFS, Lustre, ...), and the journal pragma for
// a database there: WAL locally, a rollback journal on a network filesystem, whose hosts do not
// share WAL's memory-mapped index. The journal mode never changes what is stored.
bool OnNetworkFilesystem(const std::filesystem::path& dir);
const char* JournalPragma(const std::filesystem::path& dir);

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

}  // namespace ahhs::evolver::sqlite
