#include "base/file_lock.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <stdexcept>

#include "base/temp_files.h"

using ahhs::base::FileLock;

TEST_CASE("a file lock has one holder at a time and is free again when its holder goes") {
  const ahhs::base::TempDir dir("ahhs-lock-test");
  const std::string path = dir.path() + "/x.lock";
  CHECK_FALSE(FileLock::HeldElsewhere(path));  // no such file yet
  {
    std::optional<FileLock> first = FileLock::TryExclusive(path);
    REQUIRE(first.has_value());
    CHECK(std::filesystem::exists(path));
    CHECK(FileLock::HeldElsewhere(path));
    CHECK_FALSE(FileLock::TryExclusive(path).has_value());  // another open file, refused
    FileLock moved = std::move(*first);                     // the lock moves with the object
    first.reset();
    CHECK(FileLock::HeldElsewhere(path));
  }
  CHECK_FALSE(FileLock::HeldElsewhere(path));
  CHECK(FileLock::TryExclusive(path).has_value());
}

TEST_CASE("a file lock that cannot be made says which file and why") {
  try {
    FileLock::TryExclusive("/nonexistent-ahhs-dir/x.lock");
    FAIL("no error");
  } catch (const std::runtime_error& e) {
    CHECK_THAT(e.what(),
               Catch::Contains("cannot write /nonexistent-ahhs-dir/x.lock: No such file"));
  }
}
