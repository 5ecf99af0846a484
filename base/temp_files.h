// Temporary folders and files that another local user cannot plant, predict or redirect.
// Every tool that writes a temporary file goes through these (docs/viewer.md, "Security").
#pragma once

#include <string>

namespace ahhs::base {

// A new folder of mode 0700 under the system's temporary folder ($TMPDIR, else /tmp), named
// PREFIX followed by six random characters (mkdtemp): it did not exist before, so nothing can
// be planted in it. Throws std::runtime_error saying why it could not be made.
std::string MakeTempDir(const std::string& prefix);

// Creates a new empty file beside `path`, named PATH.tmp-XXXXXX with six random characters
// (O_CREAT | O_EXCL | O_NOFOLLOW: an existing file or symlink of that name is never opened), with
// the permissions a new file gets (0666 less the umask), and returns its name. For writers that
// write under a temporary name and rename into place. Throws std::runtime_error naming `path`.
std::string CreateTempBeside(const std::string& path);

// Removes a folder and everything in it when destroyed (never follows a symlink out of it).
class TempDir {
 public:
  explicit TempDir(const std::string& prefix) : path_(MakeTempDir(prefix)) {}
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace ahhs::base
