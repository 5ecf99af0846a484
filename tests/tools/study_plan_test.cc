// The study plan: what a plan file says becomes exactly the runs and the ahhs-evolve config files
// a study runs, and a bad plan is refused with the line that is wrong.
#include "tools/study/study_plan.h"

#include <toml++/toml.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "base/temp_files.h"

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
  const auto plan = tools::LoadStudyPlan(
      d.Plan("name = \"s\"\n[[config]]\nname = \"a\"\npreset = \"gait.toml\"\nseeds = 2\n"
             "[[config]]\nname = \"b\"\npreset = \"gait.toml\"\nseeds = 3\n"));
  std::vector<std::string> names;
  for (const auto& r : tools::StudyRuns(plan)) names.push_back(r.Name());
  CHECK(names ==
        std::vector<std::string>{"a/seed-1", "b/seed-1", "a/seed-2", "b/seed-2", "b/seed-3"});
}

TEST_CASE("a configuration's file is its preset with the defaults and its own keys on top") {
  PlanDir d;
  const auto plan = tools::LoadStudyPlan(
      d.Plan("name = \"s\"\n[defaults]\ngenerations = 7\ntrials = 3\n"
             "[[config]]\nname = \"robust\"\npreset = \"gait.toml\"\nseeds = 1\n"
             "[config.set]\nrules = 80\nenvelope = \"paper\"\n\"envelope.friction\" = 0.1\n"));
  REQUIRE(plan.configs.size() == 1);
  const toml::table resolved = toml::parse(tools::ResolvedConfigToml(plan.configs[0]));
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
      tools::LoadStudyPlan(d.Plan(text));
    } catch (const tools::StudyPlanError& e) {
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
