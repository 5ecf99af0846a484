// Genome vectors (modules/core/genome_vector.h): the layout, the exact round trip, and what a
// vector out of bounds becomes.
#include "modules/core/genome_vector.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "modules/core/random.h"
#include "modules/core/variation.h"

using namespace ahhs::modules;

namespace {

const Shape kVectorShapes[] = {
    {Variant::kAhhs2, 5, 30, 4, 1},    // gait AHHS2-30
    {Variant::kAhhs1, 5, 80, 4, 1},    // gait AHHS1-80
    {Variant::kAhhs2, 15, 15, 10, 2},  // pendulum AHHS2-15
    {Variant::kAhhs1, 15, 60, 10, 2},  // pendulum AHHS1-60
    {Variant::kAhhs1, 1, 3, 1, 1},     // degenerate sizes: every index range has one entry
};

}  // namespace

TEST_CASE("a genome's vector has 3 values per hormone and 13 per AHHS2 or 7 per AHHS1 rule") {
  const auto a2 = GenomeVectorLayout({Variant::kAhhs2, 5, 30, 4, 1});
  CHECK(a2.size() == 3 * 5 + 13 * 30);
  CHECK(a2.names[15] == "rules[0].weights.idle");
  CHECK(a2.names[15 + 9] == "rules[0].sensor");
  CHECK(a2.upper[15 + 9] == 4);
  CHECK(a2.names[15 + 12] == "rules[0].actuator");
  CHECK(a2.upper[15 + 12] == 1);
  CHECK(a2.names[15 + 13] == "rules[1].weights.idle");
  const auto a1 = GenomeVectorLayout({Variant::kAhhs1, 15, 60, 10, 2});
  CHECK(a1.size() == 3 * 15 + 7 * 60);
  CHECK(a1.names[45] == "rules[0].type");
  CHECK(a1.upper[45] == 4);
  CHECK(a1.names[49] == "rules[0].direction");
  for (std::size_t k = 0; k < a1.size(); ++k) CHECK(a1.lower[k] < a1.upper[k]);
}

TEST_CASE("genome to vector to genome gives the genome back bit for bit") {
  for (const Shape& shape : kVectorShapes)
    for (std::uint64_t seed = 1; seed <= 40; ++seed) {
      Rng rng(seed);
      Genome g = RandomGenome(shape, rng);
      Mutate(&g, MutationParams{}, rng);
      const auto x = GenomeToVector(g);
      const auto layout = GenomeVectorLayout(shape);
      REQUIRE(x.size() == layout.size());
      for (std::size_t k = 0; k < x.size(); ++k) {
        CHECK(x[k] >= layout.lower[k]);
        CHECK(x[k] <= layout.upper[k]);
      }
      const Genome back = GenomeFromVector(shape, x);
      CHECK(CheckGenome(back).empty());
      CHECK(GenomeHash(back) == GenomeHash(g));
      CHECK(GenomeToVector(back) == x);
      // Through the vector file too.
      Shape read;
      CHECK(VectorFromJson(VectorToJson(shape, x), &read) == x);
      CHECK(read == shape);
    }
}

TEST_CASE("any finite vector gives a valid genome: values clipped, weights normalised") {
  const Shape shape{Variant::kAhhs2, 2, 3, 4, 1};
  const auto layout = GenomeVectorLayout(shape);
  Rng rng(5);
  for (int n = 0; n < 200; ++n) {
    std::vector<double> x(layout.size());
    for (auto& v : x) v = rng.Uniform(-10, 10);
    const Genome g = GenomeFromVector(shape, x);
    REQUIRE(CheckGenome(g).empty());
  }
  std::vector<double> x(layout.size(), 0.0);
  x[6] = 2;    // rules[0].weights.idle, clipped to 1
  x[7] = 1;    // rules[0].weights.sensor: the two share the rule
  x[15] = 9;   // rules[0].sensor: just below 4
  x[16] = -3;  // rules[0].input: 0
  const Genome g = GenomeFromVector(shape, x);
  CHECK(g.ahhs2_rules[0].weights[0] == 0.5);
  CHECK(g.ahhs2_rules[0].weights[1] == 0.5);
  CHECK(g.ahhs2_rules[0].sensor == std::nextafter(4.0, 0.0));
  CHECK(g.ahhs2_rules[0].input == 0);
  CHECK(g.ahhs2_rules[1].weights[0] == 1);  // all weights zero: an idle rule
  CHECK(g.ahhs2_rules[0].eta == Ranges::kEtaMin);
}

TEST_CASE("AHHS1 fields are decoded by flooring, input and output as shares of their range") {
  const Shape shape{Variant::kAhhs1, 3, 1, 5, 2};
  //                      alpha mu D (3 hormones)
  std::vector<double> x = {0, 0, 0, 0, 0, 0, 0, 0, 0,
                           // type, input, output, tau, direction, lambda, kappa
                           3.99, 0.7, 0.99, 0.25, 0.2, -1.5, 0.1};
  Genome g = GenomeFromVector(shape, x);
  const Ahhs1Rule& r = g.ahhs1_rules[0];
  CHECK(r.type == Ahhs1Type::kActuator);
  CHECK(r.input == 2);   // floor(0.7 x 3 hormones)
  CHECK(r.output == 1);  // floor(0.99 x 2 actuators)
  CHECK(r.direction == Direction::kBelow);
  CHECK(r.tau == 0.25);
  x[9] = 1.0;   // a sensor rule: input among 5 sensors, output among 3 hormones
  x[13] = 2.0;  // the upper bound of direction: above
  g = GenomeFromVector(shape, x);
  CHECK(g.ahhs1_rules[0].type == Ahhs1Type::kSensor);
  CHECK(g.ahhs1_rules[0].input == 3);
  CHECK(g.ahhs1_rules[0].output == 2);
  CHECK(g.ahhs1_rules[0].direction == Direction::kAbove);
}

TEST_CASE("a vector of the wrong length, a non-finite value or a bad file is refused by name") {
  const Shape shape{Variant::kAhhs2, 1, 1, 2, 1};
  CHECK_THROWS_WITH(GenomeFromVector(shape, std::vector<double>(5)),
                    "a vector of 5 values for a genome of 16");
  std::vector<double> x(16, 0.0);
  x[4] = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(GenomeFromVector(shape, x),
                    "vector[4] (rules[0].weights.sensor) is not finite");
  Shape read;
  const auto good = VectorToJson(shape, std::vector<double>(16, 0.0));
  auto doc = good;
  doc["version"] = 2;
  CHECK_THROWS_WITH(VectorFromJson(doc, &read), Catch::Contains("version 2"));
  doc = good;
  doc["shape"]["hormones"] = 0;
  CHECK_THROWS_WITH(VectorFromJson(doc, &read), Catch::Contains("shape"));
  doc = good;
  doc.erase("x");
  CHECK_THROWS_WITH(VectorFromJson(doc, &read), Catch::Contains("genome vector"));
}
