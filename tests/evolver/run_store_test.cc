// The run store: what is committed comes back bit for bit; a run directory is never
// overwritten unless asked; damaged or foreign directories give clear errors; the exports
// match the database. And RunEvolution resumed after a stop equals an uninterrupted run.
#include "evolver/store/run_store.h"

#include <sqlite3.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "episode/arena/post_eval.h"
#include "evolver/evolve/evolution.h"
#include "modules/core/genome_json.h"

using namespace ahhs;
namespace fs = std::filesystem;
using evolver::RunStore;
using evolver::RunStoreError;

namespace {

struct TempDir {
  TempDir() {
    char tmpl[] = "/tmp/ahhs-store-XXXXXX";
    path = mkdtemp(tmpl);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string path;
};

std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A cheap deterministic fitness of (genome, seed): the controller is not run, but every
// field and the seed matter, so any difference in genomes or seeds shows.
class HashFitness : public evolver::FitnessEvaluator {
 public:
  std::vector<evolver::Evaluation> Evaluate(
      const std::vector<evolver::EvaluationJob>& jobs) override {
    std::vector<evolver::Evaluation> out;
    for (const auto& j : jobs) {
      double s = 0;
      for (const auto& h : j.genome->hormones) s += h.alpha - 0.3 * h.mu + 0.1 * h.diffusion;
      evolver::Evaluation e;
      e.fitness = s + static_cast<double>(j.seed % 97) * 1e-4;
      e.cost = -s;
      e.worker = "test";
      out.push_back(e);
    }
    ++batches;
    return out;
  }
  int batches = 0;
};

evolver::EvolveConfig SmallConfig() {
  evolver::EvolveConfig c;
  c.scenario.kind = sim::ScenarioKind::kPendulum;
  c.scenario.num_modules = 2;
  c.hormones = 3;
  c.rules = 4;
  c.ga.population = 8;
  c.ga.generations = 6;
  c.seed = 123;
  return c;
}

std::string DumpRun(const RunStore& store) {
  std::ostringstream s;
  for (int g = 0; g <= store.LastGeneration(); ++g)
    for (const auto& r : store.LoadGeneration(g)) {
      s << g << ' ' << r.index << ' ' << modules::GenomeHash(r.genome) << ' ' << r.eval_seed << ' '
        << std::hexfloat << r.evaluation.fitness << ' ' << r.elite << '\n';
      for (const auto& t : r.trials)
        s << "  trial " << t.trial << ' ' << t.seed << ' ' << t.evaluation.fitness << ' '
          << t.evaluation.cost << '\n';
    }
  return s.str();
}

// Starts a run in `dir` and stops it after `generations` committed generations, as Ctrl-C would.
void StopAfter(const std::string& dir, const std::string& run_id,
               const evolver::EvolveConfig& config, evolver::FitnessEvaluator& f, int generations) {
  auto store =
      RunStore::Create(dir, run_id, 123, evolver::ConfigToJson(config), "test-physics", false);
  evolver::EvolutionHooks hooks;
  int committed = 0;
  hooks.on_generation = [&](const evolver::GenerationRecord&) { ++committed; };
  hooks.stop = [&] { return committed >= generations; };
  REQUIRE_FALSE(evolver::RunEvolution(*store, config, f, 1, hooks));
}

}  // namespace

TEST_CASE("a committed generation comes back bit for bit, with its exports") {
  TempDir tmp;
  const std::string dir = tmp.path + "/run";
  const auto config = SmallConfig();
  auto store =
      RunStore::Create(dir, "run-1", 123, evolver::ConfigToJson(config), "test-physics", false);
  CHECK(store->LastGeneration() == -1);
  CHECK(store->BeginSession("test") == 1);
  HashFitness f;
  REQUIRE(evolver::RunEvolution(*store, config, f, 1));
  CHECK(f.batches == 6);
  CHECK(store->LastGeneration() == 5);
  const auto gen3 = store->LoadGeneration(3);
  REQUIRE(gen3.size() == 8);
  CHECK(gen3[0].elite);
  CHECK_FALSE(gen3[1].elite);
  CHECK(gen3[2].eval_seed == evolver::EvaluationSeed(123, 3, 2));
  CHECK(gen3[2].evaluation.worker == "test");

  // Reopen: config and seed survive; the records are identical.
  const std::string before = DumpRun(*store);
  store.reset();
  auto reopened = RunStore::Open(dir);
  CHECK(reopened->physics() == "test-physics");
  CHECK(reopened->run_id() == "run-1");
  CHECK(reopened->run_seed() == 123);
  CHECK(evolver::ConfigToJson(evolver::ConfigFromJson(reopened->config())) ==
        evolver::ConfigToJson(config));
  CHECK(DumpRun(*reopened) == before);

  // Exports: one CSV row per generation, a best genome per generation, best.json = run best.
  const std::string csv = ReadFile(dir + "/generations.csv");
  CHECK(std::count(csv.begin(), csv.end(), '\n') == 7);
  CHECK(csv.rfind("generation,best,mean,median,worst,best_index,wall_time_s\n", 0) == 0);
  for (int g = 0; g < 6; ++g) {
    char name[64];
    std::snprintf(name, sizeof name, "%s/best/gen-%04d.json", dir.c_str(), g);
    REQUIRE(fs::exists(name));
    const auto records = reopened->LoadGenerationRecords();
    const auto best = modules::LoadGenomeFile(name);
    CHECK(modules::GenomeHash(best) ==
          modules::GenomeHash(
              reopened->LoadGeneration(g)[static_cast<std::size_t>(records[g].stats.best_index)]
                  .genome));
  }
  const auto best = reopened->Best();
  CHECK(modules::GenomeHash(modules::LoadGenomeFile(dir + "/best.json")) ==
        modules::GenomeHash(best.genome));
  for (const auto& g : reopened->LoadGenerationRecords())
    CHECK(g.stats.best <= best.evaluation.fitness);
}

TEST_CASE("a run stopped after any generation and resumed equals the uninterrupted run") {
  TempDir tmp;
  const auto config = SmallConfig();
  HashFitness f;
  auto whole = RunStore::Create(tmp.path + "/whole", "w", 123, evolver::ConfigToJson(config),
                                "test-physics", false);
  evolver::RunEvolution(*whole, config, f, 1);
  const std::string expected = DumpRun(*whole);

  for (int stop_after : {0, 2, 4}) {
    const std::string dir = tmp.path + "/part" + std::to_string(stop_after);
    {
      auto part =
          RunStore::Create(dir, "p", 123, evolver::ConfigToJson(config), "test-physics", false);
      CHECK(part->BeginSession("start") == 1);
      evolver::EvolutionHooks hooks;
      int committed = 0;
      hooks.on_generation = [&](const evolver::GenerationRecord&) { ++committed; };
      hooks.stop = [&] { return committed > stop_after; };
      CHECK_FALSE(evolver::RunEvolution(*part, config, f, 1, hooks));
      CHECK(part->LastGeneration() == stop_after);
    }
    auto resumed = RunStore::Open(dir);
    CHECK(resumed->BeginSession("resume") == 2);
    CHECK(evolver::RunEvolution(*resumed, evolver::ConfigFromJson(resumed->config()), f, 2));
    CHECK(DumpRun(*resumed) == expected);
  }
}

// Raw SQL on a run database (the store's own API never writes a format-1 run any more).
void Sql(const std::string& dir, const std::string& sql) {
  sqlite3* db = nullptr;
  REQUIRE(sqlite3_open((dir + "/run.sqlite").c_str(), &db) == SQLITE_OK);
  REQUIRE(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr) == SQLITE_OK);
  sqlite3_close(db);
}

TEST_CASE("format 4 keeps every 20th generation's genomes and breeds the others again exactly") {
  TempDir tmp;
  auto config = SmallConfig();
  config.ga.generations = 50;
  HashFitness f;
  auto whole = RunStore::Create(tmp.path + "/whole", "w", 123, evolver::ConfigToJson(config),
                                "test-physics", false);
  REQUIRE(evolver::RunEvolution(*whole, config, f, 1));
  CHECK(whole->format_version() == 4);
  const std::string expected = DumpRun(*whole);  // every genome read back, checked by its hash
  whole.reset();
  // Only generations 0, 20 and 40 hold genomes.
  sqlite3* db = nullptr;
  REQUIRE(sqlite3_open((tmp.path + "/whole/run.sqlite").c_str(), &db) == SQLITE_OK);
  sqlite3_stmt* st = nullptr;
  sqlite3_prepare_v2(db,
                     "SELECT group_concat(DISTINCT generation) FROM individuals WHERE genome != ''",
                     -1, &st, nullptr);
  REQUIRE(sqlite3_step(st) == SQLITE_ROW);
  CHECK(std::string(reinterpret_cast<const char*>(sqlite3_column_text(st, 0))) == "0,20,40");
  sqlite3_finalize(st);
  sqlite3_close(db);

  // Stopped anywhere (before, at and after a checkpoint) and resumed: the same run.
  for (int stop_after : {19, 20, 33}) {
    const std::string dir = tmp.path + "/part" + std::to_string(stop_after);
    {
      auto part =
          RunStore::Create(dir, "p", 123, evolver::ConfigToJson(config), "test-physics", false);
      evolver::EvolutionHooks hooks;
      int committed = 0;
      hooks.on_generation = [&](const evolver::GenerationRecord&) { ++committed; };
      hooks.stop = [&] { return committed > stop_after; };
      CHECK_FALSE(evolver::RunEvolution(*part, config, f, 1, hooks));
    }
    auto resumed = RunStore::Open(dir);
    CHECK(evolver::RunEvolution(*resumed, config, f, 2));
    CHECK(DumpRun(*resumed) == expected);
  }

  // A genome stored by hash only that breeding does not give back is an error, not a wrong
  // genome: change a fitness the breeding of generation 21 depends on.
  Sql(tmp.path + "/whole",
      "UPDATE individuals SET fitness = fitness + 10 WHERE generation = 20 AND idx = 3");
  auto damaged = RunStore::Open(tmp.path + "/whole", evolver::StoreAccess::kRead);
  CHECK_THROWS_WITH(damaged->LoadGeneration(21), Catch::Contains("does not match its hash"));
  // And the digest chain names the generation that was changed.
  CHECK_THROWS_WITH(damaged->VerifyChain(),
                    Catch::Contains("generation 20 does not match its digest") &&
                        Catch::Contains("generations 0-19 are intact"));
}

TEST_CASE("a format-1 run is compacted to format 4 only when breeding gives it back exactly") {
  TempDir tmp;
  auto config = SmallConfig();
  config.ga.generations = 45;
  HashFitness f;
  const std::string dir = tmp.path + "/run";
  {  // a format-1 run: every genome in full (as runs stored before 2026-12-02)
    auto store =
        RunStore::Create(dir, "r", 123, evolver::ConfigToJson(config), "test-physics", false);
    store.reset();
    Sql(dir, "UPDATE run SET value = '1' WHERE key = 'format_version'");
    auto v1 = RunStore::Open(dir);
    REQUIRE(v1->format_version() == 1);
    REQUIRE(evolver::RunEvolution(*v1, config, f, 1));
  }
  const std::string copy = tmp.path + "/copy";
  fs::copy(dir, copy, fs::copy_options::recursive);
  const std::string expected = DumpRun(*RunStore::Open(dir, evolver::StoreAccess::kRead));
  const auto size_before = fs::file_size(dir + "/run.sqlite");
  {
    auto store = RunStore::Open(dir);
    CHECK(store->Compact() > 0);
    CHECK(store->format_version() == 4);
    CHECK(store->VerifyChain() == 45);  // chained as it was compacted
    CHECK(store->Compact() == 0);       // nothing left to do
  }
  CHECK(fs::file_size(dir + "/run.sqlite") < size_before);
  CHECK(DumpRun(*RunStore::Open(dir, evolver::StoreAccess::kRead)) == expected);

  // A run whose generations are not what this build breeds (here: a genome of generation 30
  // replaced, with its hash) is refused and left whole.
  auto other = RunStore::Open(copy, evolver::StoreAccess::kRead);
  const auto g29 = other->LoadGeneration(29);
  other.reset();
  std::string text = modules::GenomeToJson(g29[3].genome).dump();
  const std::string hash = modules::GenomeHashText(g29[3].genome);
  std::string quoted;
  for (char c : text) quoted += c == '\'' ? std::string("''") : std::string(1, c);
  Sql(copy, "UPDATE individuals SET genome = '" + quoted + "', genome_hash = '" + hash +
                "' WHERE generation = 30 AND idx = 5");
  const std::string damaged = DumpRun(*RunStore::Open(copy, evolver::StoreAccess::kRead));
  {
    auto store = RunStore::Open(copy);
    CHECK_THROWS_WITH(store->Compact(), Catch::Contains("generation 30 is not what breeding"));
    CHECK(store->format_version() == 1);
  }
  CHECK(DumpRun(*RunStore::Open(copy, evolver::StoreAccess::kRead)) == damaged);
}

TEST_CASE("every generation's digest is chained: a store changed afterwards is refused") {
  TempDir tmp;
  auto config = SmallConfig();
  config.ga.generations = 8;
  HashFitness f;
  const std::string dir = tmp.path + "/run";
  {
    auto store =
        RunStore::Create(dir, "r", 123, evolver::ConfigToJson(config), "test-physics", false);
    REQUIRE(evolver::RunEvolution(*store, config, f, 1));
    CHECK(store->VerifyChain() == 8);
  }
  const auto refused = [&](const std::string& sql) {
    const std::string copy = tmp.path + "/copy";
    fs::remove_all(copy);
    fs::copy(dir, copy, fs::copy_options::recursive);
    Sql(copy, sql);
    try {
      RunStore::Open(copy);  // a resume
    } catch (const RunStoreError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  // One bit of one double; a value SQLite's own checks cannot see as wrong.
  CHECK_THAT(refused("UPDATE individuals SET fitness = fitness * (1 + 2.3e-16) WHERE "
                     "generation = 5 AND idx = 2"),
             Catch::Contains("run.sqlite: generation 5 does not match its digest") &&
                 Catch::Contains("generations 0-4 are intact"));
  CHECK_THAT(refused("UPDATE individuals SET worker = 'x' WHERE generation = 0 AND idx = 0"),
             Catch::Contains("generation 0 (or the run's configuration) does not match") &&
                 Catch::Contains("no generation is intact"));
  CHECK_THAT(refused("UPDATE run SET value = '124' WHERE key = 'seed'"),
             Catch::Contains("generation 0 (or the run's configuration) does not match"));
  CHECK_THAT(refused("UPDATE generations SET best = 9 WHERE generation = 7"),
             Catch::Contains("generation 7 does not match"));
  CHECK_THAT(refused("DELETE FROM individuals WHERE generation = 6 AND idx = 7"),
             Catch::Contains("generation 6 does not match"));
  CHECK_THAT(refused("UPDATE chain SET digest = upper(digest) WHERE generation = 3"),
             Catch::Contains("generation 3 does not match"));
  CHECK_THAT(refused("DELETE FROM chain WHERE generation = 2"),
             Catch::Contains("generation 2 has no digest"));
  CHECK_THAT(refused("DELETE FROM generations WHERE generation = 1"),
             Catch::Contains("generation 1 is missing (generation 0 is intact)"));
  CHECK_THAT(refused("DELETE FROM generations WHERE generation = 7"),
             Catch::Contains("individuals of generation 7 belong to no stored generation"));
  CHECK_THAT(refused("DROP TABLE chain"), Catch::Contains("run.sqlite: no such table: chain"));
  CHECK_THAT(refused("DROP TABLE sessions; UPDATE run SET value = '2' WHERE key = "
                     "'format_version'"),
             Catch::Contains("accepted"));  // version 2 is chained as it is found
  CHECK(refused("UPDATE generations SET wall_time = wall_time") == "accepted");  // same values
}

TEST_CASE("a version-2 run is chained when it is opened for writing, and resumes the same") {
  TempDir tmp;
  auto config = SmallConfig();
  config.ga.generations = 8;
  HashFitness f;
  const std::string whole = tmp.path + "/whole", part = tmp.path + "/part";
  {
    auto store =
        RunStore::Create(whole, "r", 123, evolver::ConfigToJson(config), "test-physics", false);
    REQUIRE(evolver::RunEvolution(*store, config, f, 1));
  }
  StopAfter(part, "r", config, f, 4);
  // As a build before the chain left it.
  Sql(part, "DROP TABLE chain; UPDATE run SET value = '2' WHERE key = 'format_version'");
  REQUIRE(RunStore::Open(part, evolver::StoreAccess::kRead)->format_version() == 2);
  auto resumed = RunStore::Open(part);
  CHECK(resumed->format_version() == 4);
  CHECK(resumed->VerifyChain() == 4);
  REQUIRE(evolver::RunEvolution(*resumed, config, f, 2));
  CHECK(resumed->VerifyChain() == 8);
  CHECK(DumpRun(*resumed) == DumpRun(*RunStore::Open(whole, evolver::StoreAccess::kRead)));
}

TEST_CASE("a resume rebuilds from the database the exports that are missing, short or wrong") {
  TempDir tmp;
  auto config = SmallConfig();
  HashFitness f;
  const std::string dir = tmp.path + "/run";
  {
    auto store =
        RunStore::Create(dir, "r", 123, evolver::ConfigToJson(config), "test-physics", false);
    REQUIRE(evolver::RunEvolution(*store, config, f, 1));
  }
  const std::string csv = ReadFile(dir + "/generations.csv"), best = ReadFile(dir + "/best.json"),
                    gen2 = ReadFile(dir + "/best/gen-0002.json"),
                    gen3 = ReadFile(dir + "/best/gen-0003.json"),
                    gen5 = ReadFile(dir + "/best/gen-0005.json");
  std::ofstream(dir + "/generations.csv") << csv.substr(0, csv.size() / 2);
  fs::remove(dir + "/best.json");
  std::ofstream(dir + "/best/gen-0002.json") << gen2.substr(0, gen2.size() - 10);
  fs::remove(dir + "/best/gen-0003.json");
  std::ofstream(dir + "/best/gen-0005.json") << gen2;  // whole, but another generation's
  RunStore::Open(dir)->Export(true);
  CHECK(ReadFile(dir + "/generations.csv") == csv);
  CHECK(ReadFile(dir + "/best.json") == best);
  CHECK(ReadFile(dir + "/best/gen-0002.json") == gen2);
  CHECK(ReadFile(dir + "/best/gen-0003.json") == gen3);
  CHECK(ReadFile(dir + "/best/gen-0005.json") == gen5);
}

TEST_CASE("an existing run directory is never overwritten unless asked") {
  TempDir tmp;
  const std::string dir = tmp.path + "/run";
  const auto json = evolver::ConfigToJson(SmallConfig());
  RunStore::Create(dir, "a", 1, json, "test-physics", false);
  try {
    RunStore::Create(dir, "b", 1, json, "test-physics", false);
    FAIL("no error");
  } catch (const RunStoreError& e) {
    CHECK_THAT(e.what(), Catch::Contains("--resume") && Catch::Contains("--overwrite"));
  }
  CHECK(RunStore::Open(dir)->run_id() == "a");
  CHECK(RunStore::Create(dir, "b", 1, json, "test-physics", true)->run_id() == "b");
  // A file where the directory should be.
  std::ofstream(tmp.path + "/file") << "x";
  CHECK_THROWS_AS(RunStore::Create(tmp.path + "/file", "c", 1, json, "test-physics", false),
                  RunStoreError);
}

TEST_CASE("a run directory has one writer at a time, and readers need no lock") {
  TempDir tmp;
  const std::string dir = tmp.path + "/run";
  const auto json = evolver::ConfigToJson(SmallConfig());
  {
    auto writer = RunStore::Create(dir, "a", 1, json, "test-physics", false);
    CHECK(RunStore::InUse(dir));
    try {
      RunStore::Open(dir);
      FAIL("a second writer was let in");
    } catch (const RunStoreError& e) {
      CHECK_THAT(e.what(), Catch::Contains("is in use"));
    }
    CHECK_THROWS_WITH(RunStore::Create(dir, "b", 1, json, "test-physics", true),
                      Catch::Contains("is in use"));
    CHECK(RunStore::Open(dir, evolver::StoreAccess::kRead)->run_id() == "a");
  }
  CHECK_FALSE(RunStore::InUse(dir));
  CHECK(RunStore::Open(dir)->run_id() == "a");
}

TEST_CASE("opening something that is not an intact run gives a clear error") {
  TempDir tmp;
  auto message = [](const std::string& dir) {
    try {
      RunStore::Open(dir);
    } catch (const RunStoreError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(message(tmp.path + "/missing"), Catch::Contains("not a directory"));
  fs::create_directories(tmp.path + "/empty");
  CHECK_THAT(message(tmp.path + "/empty"), Catch::Contains("not a run directory"));
  fs::create_directories(tmp.path + "/garbage");
  std::ofstream(tmp.path + "/garbage/run.sqlite") << std::string(5000, 'x');
  CHECK_THAT(message(tmp.path + "/garbage"), Catch::Contains("not a readable run database"));
  // A real run whose database is then damaged in the middle.
  const std::string dir = tmp.path + "/damaged";
  {
    auto store =
        RunStore::Create(dir, "d", 1, evolver::ConfigToJson(SmallConfig()), "test-physics", false);
    HashFitness f;
    evolver::RunEvolution(*store, SmallConfig(), f, 1);
  }
  {
    std::fstream db(dir + "/run.sqlite", std::ios::in | std::ios::out | std::ios::binary);
    db.seekp(0, std::ios::end);
    const auto size = static_cast<long>(db.tellp());
    REQUIRE(size > 12000);
    db.seekp(0);
    db << std::string(200, '\0');  // the header
  }
  CHECK_THAT(message(dir), Catch::Contains("not a readable run database"));
}

TEST_CASE("run configs round-trip through JSON and bad ones are refused") {
  auto c = SmallConfig();
  c.variant = modules::Variant::kAhhs1;
  c.scenario.duration = 12.5;
  c.ga.crossover_rate = 0.25;
  const auto json = evolver::ConfigToJson(c);
  CHECK(evolver::ConfigToJson(evolver::ConfigFromJson(json)) == json);
  auto bad = json;
  bad["population"] = 1;
  CHECK_THROWS_WITH(evolver::ConfigFromJson(bad), Catch::Contains("population"));
  bad = json;
  bad.erase("rules");
  CHECK_THROWS_WITH(evolver::ConfigFromJson(bad), Catch::Contains("rules"));
  bad = json;
  bad["variant"] = "ahhs3";
  CHECK_THROWS_WITH(evolver::ConfigFromJson(bad), Catch::Contains("variant"));
}

TEST_CASE(
    "a run with k trials stores every trial's seed and fitness, chained, and resumes the same") {
  TempDir tmp;
  auto config = SmallConfig();
  config.ga.trials = 3;
  config.ga.aggregate = evolver::Aggregate::kMedian;
  HashFitness f;
  const std::string whole = tmp.path + "/whole", part = tmp.path + "/part";
  {
    auto store =
        RunStore::Create(whole, "w", 123, evolver::ConfigToJson(config), "test-physics", false);
    REQUIRE(evolver::RunEvolution(*store, config, f, 1));
  }
  auto done = RunStore::Open(whole, evolver::StoreAccess::kRead);
  const auto gen2 = done->LoadGeneration(2);
  for (const auto& r : gen2) {
    REQUIRE(r.trials.size() == 3);
    std::vector<double> scores;
    for (int t = 0; t < 3; ++t) {
      const auto& trial = r.trials[static_cast<std::size_t>(t)];
      CHECK(trial.trial == t);
      CHECK(trial.seed == evolver::TrialSeed(123, 2, r.index, t));
      CHECK(trial.evaluation.worker == "test");
      scores.push_back(trial.evaluation.fitness);
    }
    CHECK(r.eval_seed == r.trials[0].seed);
    CHECK(r.evaluation.fitness == evolver::AggregateFitness(evolver::Aggregate::kMedian, scores));
  }
  // The elite is evaluated again with fresh seeds: its fitness is not the one it was bred with.
  const auto gen1 = done->LoadGeneration(1);
  const auto best1 = done->LoadGenerationRecords()[1].stats.best_index;
  const auto& parent = gen1[static_cast<std::size_t>(best1)];
  REQUIRE(gen2[0].elite);
  REQUIRE(modules::GenomeHash(gen2[0].genome) == modules::GenomeHash(parent.genome));
  CHECK(gen2[0].evaluation.fitness != parent.evaluation.fitness);
  CHECK(gen2[0].trials[0].seed != parent.trials[0].seed);
  CHECK(done->LoadIndividual(2, 3).trials.size() == 3);
  // Stopped after generation 1 and resumed: the same rows, trials included.
  StopAfter(part, "w", config, f, 2);
  auto resumed = RunStore::Open(part);
  REQUIRE(evolver::RunEvolution(*resumed, evolver::ConfigFromJson(resumed->config()), f, 2));
  CHECK(DumpRun(*resumed) == DumpRun(*done));
  // A trial changed afterwards breaks the chain.
  resumed.reset();
  Sql(part,
      "UPDATE trials SET fitness = fitness + 1e-9 WHERE generation = 3 AND idx = 1 AND "
      "trial = 2");
  CHECK_THROWS_WITH(RunStore::Open(part), Catch::Contains("generation 3 does not match"));
}

TEST_CASE("a format-3 run (one trial, no trials table) is read and resumed as it is") {
  TempDir tmp;
  auto config = SmallConfig();
  HashFitness f;
  const std::string whole = tmp.path + "/whole", part = tmp.path + "/part";
  {
    auto store =
        RunStore::Create(whole, "r", 123, evolver::ConfigToJson(config), "test-physics", false);
    REQUIRE(evolver::RunEvolution(*store, config, f, 1));
  }
  StopAfter(part, "r", config, f, 3);
  // As the build before trials left it: no trials table, version 3, the same digests.
  Sql(part, "DROP TABLE trials; UPDATE run SET value = '3' WHERE key = 'format_version'");
  auto resumed = RunStore::Open(part);
  CHECK(resumed->format_version() == 3);
  CHECK(resumed->VerifyChain() == 3);
  REQUIRE(evolver::RunEvolution(*resumed, config, f, 2));
  CHECK(resumed->VerifyChain() == 6);
  CHECK(DumpRun(*resumed) == DumpRun(*RunStore::Open(whole, evolver::StoreAccess::kRead)));
}

TEST_CASE("a run config keeps trials and the envelope, and a paper config has neither key") {
  auto c = SmallConfig();
  const auto paper = evolver::ConfigToJson(c);
  CHECK_FALSE(paper.contains("trials"));
  CHECK_FALSE(paper.contains("aggregate"));
  CHECK_FALSE(paper.contains("envelope"));
  c.ga.trials = 4;
  c.ga.aggregate = evolver::Aggregate::kMin;
  c.scenario.envelope = sim::EnvelopePreset("paper");
  c.scenario.envelope.friction = 0.125;
  const auto robust = evolver::ConfigToJson(c);
  CHECK(robust.at("trials") == 4);
  CHECK(robust.at("aggregate") == "min");
  CHECK(robust.at("envelope").at("friction") == 0.125);
  const auto back = evolver::ConfigFromJson(robust);
  CHECK(back.scenario.envelope == c.scenario.envelope);
  CHECK(back.ga.trials == 4);
  CHECK(back.ga.aggregate == evolver::Aggregate::kMin);
  CHECK(evolver::ConfigToJson(back) == robust);
  auto bad = robust;
  bad["envelope"]["frition"] = 0.1;
  CHECK_THROWS_WITH(evolver::ConfigFromJson(bad),
                    Catch::Contains("unknown envelope key 'frition'"));
  bad = robust;
  bad["envelope"]["mass"] = 2.0;
  CHECK_THROWS_WITH(evolver::ConfigFromJson(bad), Catch::Contains("envelope"));
  bad = robust;
  bad["trials"] = 0;
  CHECK_THROWS_WITH(evolver::ConfigFromJson(bad), Catch::Contains("trials"));
}

namespace {

// Fitness = the genome's quality (as HashFitness) plus episode noise far larger than the
// differences in quality: the highest training score is luck, a median over common seeds is not.
class NoisyFitness : public evolver::FitnessEvaluator {
 public:
  static double Quality(const modules::Genome& g) {
    double s = 0;
    for (const auto& h : g.hormones) s += h.alpha - 0.3 * h.mu + 0.1 * h.diffusion;
    return s;
  }
  std::vector<evolver::Evaluation> Evaluate(
      const std::vector<evolver::EvaluationJob>& jobs) override {
    if (fail) throw std::runtime_error("evaluator lost");
    std::vector<evolver::Evaluation> out;
    for (const auto& j : jobs) {
      evolver::Evaluation e;
      e.fitness = Quality(*j.genome) + static_cast<double>(j.seed % 1000) * 1e-2;
      out.push_back(e);
      seeds.push_back(j.seed);
    }
    return out;
  }
  bool fail = false;
  std::vector<std::uint64_t> seeds;
};

}  // namespace

TEST_CASE("validation chooses the best by its median on seeds no training episode had") {
  TempDir tmp;
  auto config = SmallConfig();
  config.ga.trials = 2;
  config.validation = 9;
  config.validation_candidates = 4;
  const std::string dir = tmp.path + "/run";
  auto store =
      RunStore::Create(dir, "v", 123, evolver::ConfigToJson(config), "test-physics", false);
  NoisyFitness f;
  REQUIRE(evolver::RunEvolution(*store, config, f, 1));
  const std::set<std::uint64_t> training(f.seeds.begin(), f.seeds.end());
  CHECK(store->LoadValidation().empty());
  CHECK(store->Best().generation == store->TrainingBest().generation);

  // Killed (the evaluator lost) during the validation: nothing is stored, and it runs again.
  f.fail = true;
  CHECK_THROWS(evolver::ValidateRun(*store, config, f));
  CHECK(store->LoadValidation().empty());
  f.fail = false;
  f.seeds.clear();
  REQUIRE(evolver::ValidateRun(*store, config, f));
  CHECK_FALSE(evolver::ValidateRun(*store, config, f));  // done once, kept

  const auto candidates = evolver::ValidationCandidates(*store, 4);
  const auto validation = store->LoadValidation();
  REQUIRE(validation.size() == candidates.size());
  REQUIRE(validation.size() > 4);  // the run's best and the last generation's
  std::set<std::string> distinct;
  const evolver::ValidationRecord* chosen = nullptr;
  double best_quality = -1e300;
  for (std::size_t c = 0; c < validation.size(); ++c) {
    const auto& v = validation[c];
    CHECK(v.candidate == static_cast<int>(c));
    CHECK(v.generation == candidates[c].generation);
    CHECK(v.index == candidates[c].index);
    distinct.insert(modules::GenomeHashText(candidates[c].genome));
    REQUIRE(v.seeds.size() == 9);
    for (int k = 0; k < 9; ++k) {
      const std::uint64_t seed = v.seeds[static_cast<std::size_t>(k)];
      CHECK(seed == evolver::ValidationSeed(123, k));
      CHECK(training.count(seed) == 0);
      CHECK(seed != episode::HeldOutSeed(static_cast<std::uint64_t>(k)));
    }
    const double q = NoisyFitness::Quality(candidates[c].genome);
    if (q > best_quality) best_quality = q, chosen = &v;
  }
  CHECK(distinct.size() == validation.size());
  // Common seeds: every candidate's median is its quality plus the same noise median, so the
  // validation chooses the candidate of highest quality, whatever its training luck.
  const auto best = store->Best();
  CHECK(best.generation == chosen->generation);
  CHECK(best.index == chosen->index);
  const auto file = nlohmann::json::parse(ReadFile(dir + "/best.json"));
  CHECK(file.at("meta").at("generation") == best.generation);
  CHECK(file.at("meta").at("individual") == best.index);
  CHECK(file.at("meta").at("validation").at("episodes") == 9);
  CHECK(file.at("meta").at("validation").at("median") == chosen->Median());

  // The config keeps the validation, and a config without one has no key.
  const auto doc = evolver::ConfigToJson(config);
  CHECK(doc.at("validation").at("episodes") == 9);
  CHECK(doc.at("validation").at("candidates") == 4);
  CHECK(evolver::ConfigToJson(evolver::ConfigFromJson(doc)) == doc);
  CHECK_FALSE(evolver::ConfigToJson(SmallConfig()).contains("validation"));
  auto bad = doc;
  bad["validation"]["episodes"] = -1;
  CHECK_THROWS_WITH(evolver::ConfigFromJson(bad), Catch::Contains("validation"));
}

TEST_CASE(
    "a config stored before the command delay existed is written back unchanged, and a "
    "delay is stored and read back") {
  const char* src = std::getenv("AHHS_SOURCE_DIR");
  REQUIRE(src != nullptr);
  // The robust study's export: resume and --from-export compare these configs as JSON.
  const auto summary = nlohmann::json::parse(ReadFile(
      std::string(src) + "/studies/paper-2010-robust/gait-fixed-ahhs2-50/seed-1/summary.json"));
  const nlohmann::json stored = summary.at("evolve_config");
  CHECK(evolver::ConfigToJson(evolver::ConfigFromJson(stored)) == stored);
  CHECK_FALSE(stored.at("envelope").contains("command-delay"));

  evolver::EvolveConfig config = evolver::ConfigFromJson(stored);
  config.scenario.envelope.command_delay = 0.25;
  const nlohmann::json written = evolver::ConfigToJson(config);
  CHECK(written.at("envelope").at("command-delay") == 0.25);
  CHECK(evolver::ConfigFromJson(written).scenario.envelope.command_delay == 0.25);
  CHECK_FALSE(written.at("post_eval").at("envelope").contains("command-delay"));
}
