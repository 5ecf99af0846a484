#include "base/temp_files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <vector>

namespace ahhs::base {

namespace fs = std::filesystem;

namespace {

std::vector<char> Template(const std::string& head) {
  const std::string t = head + "XXXXXX";
  return std::vector<char>(t.c_str(), t.c_str() + t.size() + 1);
}

// Six characters from [a-zA-Z0-9], from the kernel's random source (names, not seeds).
std::string RandomSuffix() {
  static const char kChars[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  std::random_device device;
  std::string s(6, 'x');
  for (char& c : s) c = kChars[device() % (sizeof kChars - 1)];
  return s;
}

}  // namespace

std::string MakeTempDir(const std::string& prefix) {
  std::error_code ec;
  const fs::path root = fs::temp_directory_path(ec);
  if (ec) throw std::runtime_error("no temporary folder ($TMPDIR, /tmp): " + ec.message());
  std::vector<char> name = Template((root / prefix).string());
  if (::mkdtemp(name.data()) == nullptr)
    throw std::runtime_error("cannot make a temporary folder in " + root.string() + ": " +
                             std::strerror(errno));
  return name.data();
}

std::string CreateTempBeside(const std::string& path) {
  // Like mkstemp, but with mode 0666 less the umask, as any new file of this process gets.
  for (int attempt = 0; attempt < 100; ++attempt) {
    const std::string name = path + ".tmp-" + RandomSuffix();
    const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd >= 0) {
      ::close(fd);
      return name;
    }
    if (errno != EEXIST) break;
  }
  throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
}

TempDir::~TempDir() {
  std::error_code ignored;
  fs::remove_all(path_, ignored);  // removes symlinks themselves, never what they point at
}

}  // namespace ahhs::base
