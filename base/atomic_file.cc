#include "base/atomic_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "base/temp_files.h"

namespace ahhs::base {

namespace fs = std::filesystem;

AtomicTextFile::AtomicTextFile(std::string path)
    : path_(std::move(path)),
      tmp_(base::CreateTempBeside(path_)),
      out_(tmp_, std::ios::binary | std::ios::trunc) {
  if (!out_) throw std::runtime_error("cannot write " + path_ + ": " + std::strerror(errno));
}

AtomicTextFile::~AtomicTextFile() {
  if (done_) return;
  out_.close();
  std::error_code ignored;
  fs::remove(tmp_, ignored);
}

void AtomicTextFile::Commit() {
  out_.flush();
  out_.close();
  if (!out_) {
    const std::string why = std::strerror(errno);
    std::error_code ignored;
    fs::remove(tmp_, ignored);
    done_ = true;
    throw std::runtime_error("cannot write " + path_ + ": " + why);
  }
  std::error_code ec;
  fs::rename(tmp_, path_, ec);
  if (ec) throw std::runtime_error("cannot write " + path_ + ": " + ec.message());
  done_ = true;
}

void WriteFileAtomically(const std::string& path, const std::string& text) {
  AtomicTextFile file(path);
  file.out() << text;
  file.Commit();
}

}  // namespace ahhs::base
