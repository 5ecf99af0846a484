// The study plan: what a plan file says becomes exactly the runs and the ahhs-evolve config files
// a study runs, and a bad plan is refused with the line that is wrong. Also --finish-by's time.
#include "tools/study/study_plan.h"

#include <toml++/toml.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "base/temp_files.h"
#include "tools/study/study_runs.h"

using namespace ahhs;
namespace fs = std::filesystem;

namespace {

// A plan folder with one preset file.
struct PlanDir {
  PlanDir() : dir("ahhs-plan-") {
    std::ofstream(fs::path(dir.path()) / "gait.toml") << "scenario = \"gait\"\nrules = 30\n";
  }
  std::string Plan(const std::string& text) const {
    const std::string path = (fs::path(dir.path()) / "plan.toml").string();
    std::ofstream(path) << text;
    return path;
  }
  base::TempDir dir;
};

}  // namespace

TEST_CASE("a study runs seed 1 of every configuration first, then seed 2, ...") {
  PlanDir d;
  const auto plan = study::LoadStudyPlan(
      d.Plan("name = \"s\"\n[[config]]\nname = \"a\"\npreset = \"gait.toml\"\nseeds = 2\n"
             "[[config]]\nname = \"b\"\npreset = \"gait.toml\"\nseeds = 3\n"));
  std::vector<std::string> names;
  for (const auto& r : study::StudyRuns(plan)) names.push_back(r.Name());
  CHECK(names ==
        std::vector<std::string>{"a/seed-1", "b/seed-1", "a/seed-2", "b/seed-2", "b/seed-3"});
}

TEST_CASE("a configuration's file is its preset with the defaults and its own keys on top") {
  PlanDir d;
  const auto plan = study::LoadStudyPlan(
      d.Plan("name = \"s\"\n[defaults]\ngenerations = 7\ntrials = 3\n"
             "[[config]]\nname = \"robust\"\npreset = \"gait.toml\"\nseeds = 1\n"
             "[config.set]\nrules = 80\nenvelope = \"paper\"\n\"envelope.friction\" = 0.1\n"));
  REQUIRE(plan.configs.size() == 1);
  const toml::table resolved = toml::parse(study::ResolvedConfigToml(plan.configs[0]));
  CHECK(resolved["scenario"].value<std::string>() == "gait");
  CHECK(resolved["rules"].value<int>() == 80);
  CHECK(resolved["generations"].value<int>() == 7);
  CHECK(resolved["trials"].value<int>() == 3);
  CHECK(resolved["envelope"].value<std::string>() == "paper");
  // A single envelope key stays one flat key (quoted), not a table.
  CHECK(resolved["envelope.friction"].value<double>() == 0.1);
}

TEST_CASE("a bad plan is refused with the line that is wrong") {
  PlanDir d;
  const auto refused = [&](const std::string& text) {
    try {
      study::LoadStudyPlan(d.Plan(text));
    } catch (const study::StudyPlanError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string head = "name = \"s\"\n[[config]]\nname = \"a\"\npreset = \"gait.toml\"\n";
  CHECK_THAT(refused(head + "seeds = 1\n[config.set]\npopulaton = 3\n"),
             Catch::Contains("plan.toml:7:") && Catch::Contains("'populaton' is not"));
  CHECK_THAT(refused(head + "seeds = 1\n[config.set]\nseed = 3\n"),
             Catch::Contains("a study sets the seeds itself"));
  CHECK_THAT(refused("name = \"s\"\n[[config]]\nname = \"a\"\npreset = \"none.toml\"\nseeds = 1\n"),
             Catch::Contains("none.toml"));
  CHECK(refused(head + "seeds = 1\n") == "accepted");
}

TEST_CASE("the committed study plans load, and their configurations resolve to flat TOML") {
  const char* src = std::getenv("AHHS_SOURCE_DIR");
  REQUIRE(src != nullptr);
  for (const char* name : {"paper-2010.toml", "paper-2010-robust.toml"}) {
    INFO(name);
    const auto plan = study::LoadStudyPlan(std::string(src) + "/studies/" + name);
    CHECK_FALSE(plan.configs.empty());
    for (const auto& config : plan.configs) {
      const toml::table resolved = toml::parse(study::ResolvedConfigToml(config));
      CHECK(resolved["generations"].value<int>() == 200);
    }
  }
  const auto robust = study::LoadStudyPlan(std::string(src) + "/studies/paper-2010-robust.toml");
  for (const auto& config : robust.configs) {
    const toml::table resolved = toml::parse(study::ResolvedConfigToml(config));
    CHECK(resolved["envelope"].value<std::string>() == "paper");
    CHECK(resolved["post-eval"].value<int>() == 50);
    const bool damped = config.name.find("damped") != std::string::npos;
    CHECK(resolved["trials"].value<int>() == (damped ? 3 : 5));
  }
}

TEST_CASE(
    "a study finishes by a time of day or after a duration from now, anything else is a usage "
    "error") {
  std::tm noon{};
  noon.tm_year = 126;
  noon.tm_mon = 11;
  noon.tm_mday = 6;
  noon.tm_hour = 12;
  noon.tm_isdst = -1;
  const std::time_t now = std::mktime(&noon);
  CHECK(study::ParseFinishBy("90m", now) == now + 5400);
  CHECK(study::ParseFinishBy("2.5h", now) == now + 9000);
  CHECK(study::ParseFinishBy("600s", now) == now + 600);
  CHECK(study::ParseFinishBy("17:30", now) == now + 5 * 3600 + 1800);  // later today
  const std::time_t tomorrow = study::ParseFinishBy("11:15", now);     // passed: tomorrow
  std::tm t = *std::localtime(&tomorrow);
  CHECK((t.tm_mday == 7 && t.tm_hour == 11 && t.tm_min == 15 && t.tm_sec == 0));
  CHECK(study::ParseFinishBy("12:00", now) > now);  // now is passed too
  for (const char* bad : {"", "90", "90x", "-5m", "0h", "25:00", "12:60", "7:30", "12:30:00",
                          "soon", "1e9h", "5m later"})
    CHECK_THROWS_AS(study::ParseFinishBy(bad, now), base::UsageError);
}
