// The run store's maintenance: compaction of old run formats (genomes of every 20th generation
// kept, the others bred again when read) and the rebuilding of the digest chain.
#include <sqlite3.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/format.h"
#include "evolver/store/run_layout.h"
#include "evolver/store/run_store.h"
#include "evolver/store/sqlite_db.h"
#include "modules/core/genome_json.h"

namespace ahhs::evolver {

namespace fs = std::filesystem;
using nlohmann::json;
using run_layout::FromSql;
using run_layout::kDatabaseName;
using run_layout::kFormatName;
using run_layout::kLockName;
using run_layout::kTrialsTable;
using run_layout::ToSql;
using run_layout::WriteExport;
using sqlite::Digest;
using sqlite::Statement;

std::uint64_t RunStore::Compact() {
  if (!lock_) throw RunStoreError(dir_ + ": compacting needs the run opened for writing");
  if (format_version_ >= 2) return 0;  // Open(kWrite) has chained a version-2 run already
  const fs::path db_path = fs::path(dir_) / kDatabaseName;
  std::error_code ec;
  const auto before = fs::file_size(db_path, ec);
  GaParams ga;
  try {
    ga = GaParamsFromJson(config_);
  } catch (const std::exception& e) {
    throw RunStoreError(dir_ + ": run config: " + e.what());
  }
  // First check that every generation is what breeding its stored parents gives (so that
  // version 2 can breed it again from a checkpoint); only then drop anything.
  const int last = LastGeneration();
  std::vector<IndividualRecord> parents =
      last >= 0 ? LoadIndividuals(0, -1) : std::vector<IndividualRecord>{};
  for (int g = 1; g <= last; ++g) {
    std::vector<modules::Genome> genomes;
    std::vector<double> fitness;
    for (const auto& r : parents) {
      genomes.push_back(r.genome);
      fitness.push_back(r.evaluation.fitness);
    }
    const std::vector<modules::Genome> bred = Breed(genomes, fitness, ga, BreedingSeed(), g);
    parents = LoadIndividuals(g, -1);
    bool same = bred.size() == parents.size();
    for (std::size_t i = 0; same && i < bred.size(); ++i)
      same = modules::GenomeHash(bred[i]) == modules::GenomeHash(parents[i].genome);
    if (!same)
      throw RunStoreError(dir_ + ": generation " + std::to_string(g) +
                          " is not what breeding generation " + std::to_string(g - 1) +
                          " gives with this build (a run of another build's variation): left "
                          "as it is");
  }
  Exec("BEGIN IMMEDIATE");
  try {
    Statement drop(db_, "UPDATE individuals SET genome = '' WHERE generation % ? != 0");
    drop.Bind(1, static_cast<std::int64_t>(kGenomeCheckpoint)).Run();
    RebuildChain();
    Exec("COMMIT");
  } catch (...) {
    sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    format_version_ = 1;
    throw;
  }
  rederived_generation_ = -1;
  Exec("VACUUM");
  sqlite3_exec(db_, "PRAGMA wal_checkpoint(TRUNCATE)", nullptr, nullptr, nullptr);  // WAL mode
  const auto after = fs::file_size(db_path, ec);
  return before > after ? before - after : 0;
}

bool RunStore::BestFileIsWhole(const fs::path& path, const GenerationRecord& g) const {
  Statement stored(db_, "SELECT genome_hash FROM individuals WHERE generation = ? AND idx = ?");
  stored.Bind(1, static_cast<std::int64_t>(g.generation))
      .Bind(2, static_cast<std::int64_t>(g.stats.best_index));
  if (!stored.Step()) return false;
  try {
    json meta;
    const modules::Genome genome = modules::LoadGenomeFile(path.string(), &meta);
    return stored.Text(0) == modules::GenomeHashText(genome) &&
           meta.at("generation").get<int>() == g.generation &&
           meta.at("individual").get<int>() == g.stats.best_index &&
           meta.at("fitness").get<double>() == g.stats.best;
  } catch (const std::exception&) {
    return false;
  }
}

std::string RunStore::RunTableDigest() const {
  // format_version is left out: a run changes version (Compact, chaining) without changing.
  Digest digest;
  Statement rows(db_, "SELECT key, value FROM run WHERE key != 'format_version' ORDER BY key");
  digest.AddRows(rows);
  return digest.Hex();
}

std::string RunStore::GenerationDigest(int generation, const std::string& previous) const {
  Digest digest;
  digest.AddText(previous);
  Statement row(db_,
                "SELECT generation, best, mean, median, worst, best_index, wall_time, session, "
                "committed_utime FROM generations WHERE generation = ?");
  row.Bind(1, static_cast<std::int64_t>(generation));
  digest.AddRows(row);
  Statement individuals(db_,
                        "SELECT generation, idx, genome, genome_hash, elite, eval_seed, fitness, "
                        "cost, worker, attempt, wall_time, message FROM individuals "
                        "WHERE generation = ? ORDER BY idx");
  individuals.Bind(1, static_cast<std::int64_t>(generation));
  digest.AddRows(individuals);
  if (HasTrials() && config_.value("trials", 1) > 1) {  // with one trial: version 3's digest
    Statement trials(db_,
                     "SELECT generation, idx, trial, seed, fitness, cost, worker, attempt, "
                     "wall_time, message FROM trials WHERE generation = ? ORDER BY idx, trial");
    trials.Bind(1, static_cast<std::int64_t>(generation));
    digest.AddRows(trials);
  }
  return digest.Hex();
}

void RunStore::RebuildChain() {
  Exec(
      "CREATE TABLE IF NOT EXISTS chain(generation INTEGER PRIMARY KEY, digest TEXT NOT NULL);"
      "DELETE FROM chain;");
  Exec(kTrialsTable);
  format_version_ = kFormatVersion;  // the digests below are this version's
  Statement add(db_, "INSERT INTO chain(generation, digest) VALUES(?, ?)");
  std::string previous = RunTableDigest();
  for (const auto& g : LoadGenerationRecords()) {
    previous = GenerationDigest(g.generation, previous);
    add.Bind(1, static_cast<std::int64_t>(g.generation)).Bind(2, previous).Run();
  }
  Statement version(db_, "UPDATE run SET value = ? WHERE key = 'format_version'");
  version.Bind(1, std::to_string(kFormatVersion)).Run();
  format_version_ = kFormatVersion;
  rederived_generation_ = -1;
}

int RunStore::VerifyChain() const {
  const auto intact = [](int g) {
    return g == 0   ? std::string("no generation is intact")
           : g == 1 ? std::string("generation 0 is intact")
                    : "generations 0-" + std::to_string(g - 1) + " are intact";
  };
  const std::string file = dir_ + "/" + kDatabaseName;
  std::vector<int> generations;
  {
    Statement all(db_, "SELECT generation FROM generations ORDER BY generation");
    while (all.Step()) generations.push_back(static_cast<int>(all.Int(0)));
  }
  for (std::size_t k = 0; k < generations.size(); ++k)
    if (generations[k] != static_cast<int>(k))
      throw RunStoreError(file + ": generation " + std::to_string(k) + " is missing (" +
                          intact(static_cast<int>(k)) + "): the store is damaged");
  {
    Statement orphan(db_,
                     "SELECT MIN(generation) FROM individuals WHERE generation NOT IN "
                     "(SELECT generation FROM generations)");
    if (orphan.Step() && !orphan.IsNull(0))
      throw RunStoreError(file + ": individuals of generation " + std::to_string(orphan.Int(0)) +
                          " belong to no stored generation: the store is damaged");
  }
  if (HasTrials()) {
    Statement orphan(db_,
                     "SELECT MIN(generation) FROM trials WHERE generation NOT IN "
                     "(SELECT generation FROM generations)");
    if (orphan.Step() && !orphan.IsNull(0))
      throw RunStoreError(file + ": trials of generation " + std::to_string(orphan.Int(0)) +
                          " belong to no stored generation: the store is damaged");
  }
  if (!Chained()) return 0;
  Statement stored(db_, "SELECT digest FROM chain WHERE generation = ?");
  std::string previous = RunTableDigest();
  for (const int g : generations) {
    previous = GenerationDigest(g, previous);
    stored.Bind(1, static_cast<std::int64_t>(g));
    const bool has = stored.Step();
    const std::string digest = has ? stored.Text(0) : "";
    stored.Reset();
    if (digest != previous)
      throw RunStoreError(file + ": generation " + std::to_string(g) +
                          (g == 0 ? " (or the run's configuration)" : "") +
                          (has ? " does not match its digest" : " has no digest") +
                          ": the store was changed or damaged after it was written (" + intact(g) +
                          "); refusing to use it");
  }
  Statement extra(db_, "SELECT COUNT(*) FROM chain WHERE generation > ?");
  extra.Bind(1, static_cast<std::int64_t>(generations.size()) - 1);
  if (extra.Step() && extra.Int(0) > 0)
    throw RunStoreError(file + ": generation " + std::to_string(generations.size()) +
                        " has a digest but no rows (" +
                        intact(static_cast<int>(generations.size())) + "): the store is damaged");
  return static_cast<int>(generations.size());
}

void RunStore::Export(bool check_existing) const {
  const fs::path root(dir_);
  std::ostringstream csv;
  csv << "generation,best,mean,median,worst,best_index,wall_time_s\n";
  const auto generations = LoadGenerationRecords();
  for (const auto& g : generations)
    csv << g.generation << ',' << base::ExactDouble(g.stats.best) << ','
        << base::ExactDouble(g.stats.mean) << ',' << base::ExactDouble(g.stats.median) << ','
        << base::ExactDouble(g.stats.worst) << ',' << g.stats.best_index << ','
        << base::ExactDouble(g.wall_time) << '\n';
  WriteExport(root / "generations.csv", csv.str());
  std::error_code ec;
  fs::create_directories(root / "best", ec);
  auto meta = [&](const IndividualRecord& r) {
    json m{{"run", run_id_},
           {"generation", r.generation},
           {"individual", r.index},
           {"fitness", r.evaluation.fitness},
           {"cost", r.evaluation.cost},
           {"eval_seed", r.eval_seed},
           {"config", config_}};
    if (!physics_.empty()) m["physics"] = physics_;  // a replay takes the same physics
    if (!r.trials.empty()) {  // `fitness` is their aggregate; `eval_seed` the first trial's
      json trials = json::array();
      for (const auto& t : r.trials)
        trials.push_back({{"seed", t.seed}, {"fitness", t.evaluation.fitness}});
      m["trials"] = trials;
    }
    return m;
  };
  for (const auto& g : generations) {
    char name[32];
    std::snprintf(name, sizeof name, "gen-%04d.json", g.generation);
    const fs::path path = root / "best" / name;
    if (fs::exists(path, ec) && (!check_existing || BestFileIsWhole(path, g))) continue;
    const IndividualRecord r = LoadIndividual(g.generation, g.stats.best_index);
    modules::SaveGenomeFile(path.string(), r.genome, meta(r));
  }
  if (!generations.empty()) {
    const IndividualRecord best = Best();
    json m = meta(best);
    const auto validation = LoadValidation();
    for (const auto& v : validation)
      if (v.generation == best.generation && v.index == best.index) {
        m["validation"] = {{"episodes", v.fitness.size()},
                           {"candidates", validation.size()},
                           {"median", v.Median()}};
        break;
      }
    modules::SaveGenomeFile((root / "best.json").string(), best.genome, m);
  }
}

}  // namespace ahhs::evolver
