// An advisory lock on a file (flock), held while its object lives: one writer per run directory,
// one ahhs-study per study directory. The lock goes with the process, so a killed holder never
// leaves a stale lock behind.
#pragma once

#include <optional>
#include <string>

namespace ahhs::base {

class FileLock {
 public:
  // The exclusive lock of `path` (made if missing), without waiting: std::nullopt when another
  // process holds it. Throws std::runtime_error ("cannot write PATH: why") when the file cannot
  // be opened.
  static std::optional<FileLock> TryExclusive(const std::string& path);
  // Whether another process holds the lock of `path` now (false when there is no such file).
  static bool HeldElsewhere(const std::string& path);

  FileLock(FileLock&& other) noexcept;
  FileLock& operator=(FileLock&& other) noexcept;
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  ~FileLock();

 private:
  explicit FileLock(int fd) : fd_(fd) {}
  int fd_ = -1;
};

}  // namespace ahhs::base
