// What the harnesses share: a broken contract stops the fuzzer with a message (libFuzzer saves
// the input that did it). A crash, a sanitizer report or an exception the code under test does
// not document (libFuzzer reports an uncaught one as a crash) stops it too.
#pragma once

#include <cstdio>
#include <cstdlib>

#define FUZZ_CONTRACT(condition, what)                                                 \
  do {                                                                                 \
    if (!(condition)) {                                                                \
      std::fprintf(stderr, "contract broken: %s (%s:%d)\n", what, __FILE__, __LINE__); \
      std::abort();                                                                    \
    }                                                                                  \
  } while (0)
