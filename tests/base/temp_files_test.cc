#include "base/temp_files.h"

#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>

#include "base/atomic_file.h"
#include "modules/core/genome.h"
#include "modules/core/genome_json.h"
#include "modules/core/variation.h"

namespace fs = std::filesystem;
using ahhs::base::CreateTempBeside;
using ahhs::base::MakeTempDir;
using ahhs::base::TempDir;

namespace {

std::string Read(const fs::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// What is in `dir` besides `keep`.
int Others(const fs::path& dir, const std::set<std::string>& keep) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir))
    if (!keep.count(e.path().filename().string())) ++n;
  return n;
}

}  // namespace

TEST_CASE("a temporary folder is new, private and removed with its owner", "[temp-files]") {
  std::string path;
  {
    const TempDir a("ahhs-test-"), b("ahhs-test-");
    path = a.path();
    CHECK(a.path() != b.path());
    CHECK(fs::path(a.path()).filename().string().size() == std::string("ahhs-test-").size() + 6);
    struct stat st {};
    REQUIRE(::lstat(a.path().c_str(), &st) == 0);
    CHECK(S_ISDIR(st.st_mode));
    CHECK((st.st_mode & 0777) == 0700);
    std::ofstream(fs::path(a.path()) / "inside") << "x";
  }
  CHECK_FALSE(fs::exists(path));
}

TEST_CASE("a temporary folder follows TMPDIR and fails loudly where it cannot be made",
          "[temp-files]") {
  const TempDir outer("ahhs-test-");
  const char* old = std::getenv("TMPDIR");
  const std::string saved = old ? old : "";
  ::setenv("TMPDIR", outer.path().c_str(), 1);
  const std::string inner = MakeTempDir("x-");
  CHECK(fs::path(inner).parent_path() == fs::path(outer.path()));
  ::setenv("TMPDIR", (outer.path() + "/missing").c_str(), 1);
  CHECK_THROWS_WITH(MakeTempDir("x-"), Catch::Contains("temporary folder"));
  if (old)
    ::setenv("TMPDIR", saved.c_str(), 1);
  else
    ::unsetenv("TMPDIR");
}

TEST_CASE("a temporary file beside a path is new each time and never a planted symlink",
          "[temp-files]") {
  const TempDir dir("ahhs-test-");
  const fs::path target = fs::path(dir.path()) / "out.txt";
  const fs::path victim = fs::path(dir.path()) / "victim.txt";
  std::ofstream(victim) << "precious";
  // The names the writers used before: an attacker's symlinks to the victim.
  fs::create_symlink(victim, target.string() + ".tmp");
  const std::string a = CreateTempBeside(target.string());
  const std::string b = CreateTempBeside(target.string());
  CHECK(a != b);
  CHECK(a.rfind(target.string() + ".tmp-", 0) == 0);
  struct stat st {};
  REQUIRE(::lstat(a.c_str(), &st) == 0);
  CHECK(S_ISREG(st.st_mode));
  CHECK(st.st_size == 0);
  const mode_t mask = ::umask(0);
  ::umask(mask);
  CHECK((st.st_mode & 0777) == (0666 & ~mask));
  CHECK_THROWS_WITH(CreateTempBeside((fs::path(dir.path()) / "no" / "x").string()),
                    Catch::Contains("cannot write"));

  SECTION("the atomic writers leave the victim alone and no temporary behind") {
    fs::remove(a);
    fs::remove(b);
    ahhs::base::WriteFileAtomically(target.string(), "new text");
    CHECK(Read(target) == "new text");
    const fs::path genome = fs::path(dir.path()) / "g.json";
    fs::create_symlink(victim, genome.string() + ".tmp");
    ahhs::modules::Rng rng(3);
    const auto g = ahhs::modules::RandomGenome({ahhs::modules::Variant::kAhhs2, 2, 2, 2, 1}, rng);
    ahhs::modules::SaveGenomeFile(genome.string(), g);
    CHECK(ahhs::modules::GenomeHash(ahhs::modules::LoadGenomeFile(genome.string())) ==
          ahhs::modules::GenomeHash(g));
    CHECK(Read(victim) == "precious");
    CHECK(Others(dir.path(), {"out.txt", "out.txt.tmp", "victim.txt", "g.json", "g.json.tmp"}) ==
          0);
  }
}
