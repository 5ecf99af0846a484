// Files that appear whole or not at all: written under a new temporary name (PATH.tmp-XXXXXX,
// base/temp_files.h: never an existing file or a planted symlink) and renamed
// into place, so a reader sees the old file or the new one and a killed writer leaves no
// half-written file (run exports, study files, replay outputs).
#pragma once

#include <fstream>
#include <string>

namespace ahhs::base {

// A text file being written. Commit() moves it into place; destroyed without Commit(), it
// removes its temporary file. Throws std::runtime_error naming the path.
class AtomicTextFile {
 public:
  explicit AtomicTextFile(std::string path);
  ~AtomicTextFile();
  AtomicTextFile(const AtomicTextFile&) = delete;
  AtomicTextFile& operator=(const AtomicTextFile&) = delete;

  std::ofstream& out() { return out_; }
  void Commit();

 private:
  std::string path_, tmp_;
  std::ofstream out_;
  bool done_ = false;
};

// The whole text at once. Throws std::runtime_error naming the path.
void WriteFileAtomically(const std::string& path, const std::string& text);

}  // namespace ahhs::base
