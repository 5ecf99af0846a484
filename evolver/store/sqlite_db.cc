#include "evolver/store/sqlite_db.h"

#include <sys/statvfs.h>
#include <sys/vfs.h>

namespace ahhs::evolver::sqlite {

namespace fs = std::filesystem;

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

}  // namespace ahhs::evolver::sqlite
