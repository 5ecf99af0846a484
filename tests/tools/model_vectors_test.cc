// The controller's golden vectors (tools/conformance/data/model-vectors.txt): the file is what
// modules/core computes today, a port's one-bit difference is caught with the case, tick and
// value, and a damaged file gets a clear line.
#include "tools/conformance/model_vectors.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

using namespace ahhs;

namespace {

std::string ShippedVectors() {
  const char* src = std::getenv("AHHS_SOURCE_DIR");
  REQUIRE(src != nullptr);
  std::ifstream in(std::string(src) + "/tools/conformance/data/model-vectors.txt");
  REQUIRE(in);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

TEST_CASE("the shipped golden vectors are exactly what modules/core computes") {
  const std::string shipped = ShippedVectors();
  CHECK(conformance::CheckModelVectors(shipped).empty());
  // Regenerate with `ahhs-conformance vectors --write` only when the model changes on purpose.
  CHECK(conformance::WriteModelVectors() == shipped);
}

TEST_CASE("a golden value one bit off is named with its case, tick and item") {
  std::string text = conformance::WriteModelVectors();
  // The first actuator output of the first case, moved to the next double.
  const auto at = text.find("expect_actuators ") + 17;
  const auto end = text.find_first_of(" \n", at);
  const double value = std::strtod(text.substr(at, end - at).c_str(), nullptr);
  char next[40];
  std::snprintf(next, sizeof next, "%.17g", std::nextafter(value, 2.0));
  text.replace(at, end - at, next);
  CHECK_THAT(conformance::CheckModelVectors(text),
             Catch::StartsWith("case ahhs2-gait tick 0: expect_actuators[0] is ") &&
                 Catch::Contains("modules/core gives"));
}

TEST_CASE("a damaged golden vectors file gets one line naming what is wrong") {
  CHECK_THAT(conformance::CheckModelVectors("hello\n"),
             Catch::Contains("not a model vectors file"));
  CHECK_THAT(conformance::CheckModelVectors("ahhs-model-vectors 9\n"),
             Catch::Contains("version 9"));
  std::string text = conformance::WriteModelVectors();
  text.replace(text.find("alpha "), 6, "alpha x");
  CHECK_THAT(conformance::CheckModelVectors(text), Catch::Contains("line 7: not a number"));
  text = conformance::WriteModelVectors();
  text.resize(text.size() / 2);
  CHECK_FALSE(conformance::CheckModelVectors(text).empty());
}
