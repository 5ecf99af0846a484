#include "base/format.h"

#include <catch2/catch.hpp>
#include <cstdlib>
#include <string>

using ahhs::base::ShellWord;

TEST_CASE("a safe word is printed as it is, any other in single quotes the shell reads back",
          "[format]") {
  CHECK(ShellWord("/work/runs/gait-1") == "/work/runs/gait-1");
  CHECK(ShellWord("udpm://239.255.76.67:7667?ttl=1") == "'udpm://239.255.76.67:7667?ttl=1'");
  CHECK(ShellWord("a b") == "'a b'");
  CHECK(ShellWord("") == "''");
  CHECK(ShellWord("it's") == "'it'\\''s'");
  // sh reads each back to the word itself (given to it unquoted in the environment).
  for (const std::string word : {"it's", "a&b;c", "$HOME `x` \"q\"", "x\\y", "-n"}) {
    ::setenv("AHHS_WORD", word.c_str(), 1);
    const std::string cmd = "test \"$AHHS_WORD\" = " + ShellWord(word);
    CHECK(std::system(cmd.c_str()) == 0);
  }
}
