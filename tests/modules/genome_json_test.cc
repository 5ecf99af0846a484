#include "modules/core/genome_json.h"

#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "modules/core/variation.h"

using namespace ahhs::modules;
using nlohmann::json;

TEST_CASE("genome JSON round trip is bit-exact for both variants", "[genome-file]") {
  Rng rng(21);
  for (Variant v : {Variant::kAhhs1, Variant::kAhhs2}) {
    for (int k = 0; k < 100; ++k) {
      const Genome g = RandomGenome({v, 5, 20, 4, 1}, rng);
      const std::string text = GenomeToJson(g).dump();
      const Genome back = ParseGenome(text, "test");
      REQUIRE(GenomeHash(back) == GenomeHash(g));
      REQUIRE(GenomeToJson(back).dump() == text);
    }
  }
}

TEST_CASE("save is atomic and load reads it back", "[genome-file]") {
  Rng rng(22);
  const Genome g = RandomGenome({Variant::kAhhs2, 3, 4, 2, 2}, rng);
  const std::string path = "genome_json_test_tmp.json";
  SaveGenomeFile(path, g, json{{"note", "test"}});
  CHECK(GenomeHash(LoadGenomeFile(path)) == GenomeHash(g));
  for (const auto& entry : std::filesystem::directory_iterator("."))
    CHECK(entry.path().filename().string().rfind(path + ".tmp", 0) != 0);  // no temporary left
  std::remove(path.c_str());
  CHECK_THROWS_WITH(LoadGenomeFile("/nonexistent/genome.json"), Catch::Contains("cannot open"));
  Genome bad = g;
  bad.hormones[0].mu = 2;
  CHECK_THROWS_WITH(SaveGenomeFile(path, bad), Catch::Contains("hormones[0].mu"));
  std::ifstream none(path);
  CHECK_FALSE(none.good());
}

namespace {
json ValidAhhs2() {
  Rng rng(23);
  return GenomeToJson(RandomGenome({Variant::kAhhs2, 2, 2, 3, 1}, rng));
}
json ValidAhhs1() {
  Rng rng(24);
  return GenomeToJson(RandomGenome({Variant::kAhhs1, 2, 2, 3, 1}, rng));
}
void ExpectRejected(const json& doc, const std::string& field_in_message) {
  INFO(doc.dump());
  CHECK_THROWS_WITH(GenomeFromJson(doc), Catch::Contains(field_in_message));
}
}  // namespace

TEST_CASE("bad genome files of every kind are rejected, naming the field", "[genome-file]") {
  CHECK_THROWS_WITH(ParseGenome("{not json", "f.json"), Catch::Contains("f.json: not valid JSON"));
  CHECK_THROWS_WITH(ParseGenome("", "f.json"), Catch::Contains("not valid JSON"));
  // A number too large for a double is the file's error, naming its field (issue 20's fuzzing
  // found it escaping as nlohmann's out_of_range).
  std::string huge = ValidAhhs2().dump();
  const auto at = huge.find("\"alpha\":") + 8;
  huge.replace(at, huge.find_first_of(",}", at) - at, "1e400");
  CHECK_THROWS_AS(ParseGenome(huge, "f.json"), GenomeFileError);
  CHECK_THROWS_WITH(ParseGenome(huge, "f.json"), Catch::Contains("f.json: alpha: out of range"));
  ExpectRejected(json::array(), "(document)");

  auto j = ValidAhhs2();
  j.erase("hormones");
  ExpectRejected(j, "hormones: missing");
  j = ValidAhhs2();
  j["format"] = "something";
  ExpectRejected(j, "format");
  j = ValidAhhs2();
  j["version"] = 2;
  ExpectRejected(j, "version: unsupported");
  j = ValidAhhs2();
  j["variant"] = "ahhs3";
  ExpectRejected(j, "variant");
  j = ValidAhhs2();
  j["sensors"] = 0;
  ExpectRejected(j, "sensors");
  j = ValidAhhs2();
  j["sensors"] = 2.5;
  ExpectRejected(j, "sensors: must be an integer");
  j = ValidAhhs2();
  j["hormones"] = json::array();
  ExpectRejected(j, "hormones: must hold");
  j = ValidAhhs2();
  j["hormones"][1]["mu"] = "0.5";
  ExpectRejected(j, "hormones[1].mu: must be a number");
  j = ValidAhhs2();
  j["hormones"][1]["mu"] = nullptr;  // how NaN ends up in JSON
  ExpectRejected(j, "hormones[1].mu: must be a number");
  j = ValidAhhs2();
  j["hormones"][0]["alpha"] = 0.2;
  ExpectRejected(j, "hormones[0].alpha: value 0.2 outside [0, 0.1]");
  j = ValidAhhs2();
  j["hormones"][0]["decay"] = 0.2;
  ExpectRejected(j, "hormones[0].decay: unknown field");
  j = ValidAhhs2();
  j["rules"][1]["weights"]["sensor"] = 0.5 + j["rules"][1]["weights"]["sensor"].get<double>();
  ExpectRejected(j, "rules[1].weights: sum");
  j = ValidAhhs2();
  j["rules"][0]["weights"]["idle"] = -0.1;
  ExpectRejected(j, "rules[0].weights.idle");
  j = ValidAhhs2();
  j["rules"][0]["weights"].erase("linear");
  ExpectRejected(j, "rules[0].weights.linear: missing");
  j = ValidAhhs2();
  j["rules"][1]["eta"] = 0.0;
  ExpectRejected(j, "rules[1].eta");
  j = ValidAhhs2();
  j["rules"][1]["sensor"] = 3.0;  // 3 sensors: [0, 3)
  ExpectRejected(j, "rules[1].sensor: index 3 outside [0, 3)");
  j = ValidAhhs2();
  j["rules"][0]["output"] = -0.5;
  ExpectRejected(j, "rules[0].output");
  j = ValidAhhs2();
  j["rules"][0]["lambda"] = 1e300;
  ExpectRejected(j, "rules[0].lambda");
  j = ValidAhhs2();
  j["rules"][0] = 5;
  ExpectRejected(j, "rules[0]: must be an object");
  j = ValidAhhs2();
  j["rules"][0]["type"] = "sensor";  // an AHHS1 field in an AHHS2 rule
  ExpectRejected(j, "rules[0].type: unknown field");
  j = ValidAhhs2();
  j["meta"] = 3;
  ExpectRejected(j, "meta: must be an object");

  j = ValidAhhs1();
  j["rules"][0]["type"] = "motor";
  ExpectRejected(j, "rules[0].type");
  j = ValidAhhs1();
  j["rules"][0]["direction"] = "sideways";
  ExpectRejected(j, "rules[0].direction");
  j = ValidAhhs1();
  j["rules"][0]["type"] = "sensor";
  j["rules"][0]["input"] = 3;
  ExpectRejected(j, "rules[0].input: index 3 outside [0, 3)");
  j = ValidAhhs1();
  j["rules"][1]["type"] = "actuator";
  j["rules"][1]["output"] = 1;
  ExpectRejected(j, "rules[1].output: index 1 outside [0, 1)");
  j = ValidAhhs1();
  j["rules"][1]["tau"] = 1.5;
  ExpectRejected(j, "rules[1].tau");
  j = ValidAhhs1();
  j["rules"][1]["input"] = 0.5;
  ExpectRejected(j, "rules[1].input: must be an integer");
}

TEST_CASE("the genome hash is FNV-1a 64 over little-endian words, as docs/hardware.md says",
          "[genome-file]") {
  // Hand-computed (docs/hardware.md, "Genome hash"): the words 2, 1, 1, 1, 0 (variant, sensors,
  // actuators, hormones, rules) and the doubles 0.5, 0.1, 0.2, each as 8 bytes, least
  // significant first, through FNV-1a 64.
  ahhs::modules::Genome g;
  g.variant = ahhs::modules::Variant::kAhhs2;
  g.num_sensors = 1;
  g.num_actuators = 1;
  g.hormones = {{0.5, 0.1, 0.2}};
  CHECK(ahhs::modules::GenomeHash(g) == 0xc1b7a6fbecf4160bULL);
}
