// The run's best: by fitness, or chosen by a stored validation (run_store.h).
#include <cmath>
#include <set>
#include <string>

#include "evolver/store/run_layout.h"
#include "evolver/store/run_store.h"
#include "evolver/store/sqlite_db.h"

namespace ahhs::evolver {

using run_layout::FromSql;
using run_layout::kValidationTable;
using run_layout::ToSql;
using sqlite::Statement;

double ValidationRecord::Median() const { return AggregateFitness(Aggregate::kMedian, fitness); }

bool RunStore::HasTable(const char* name) const {
  Statement table(db_, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = ?");
  table.Bind(1, std::string(name));
  return table.Step();
}

IndividualRecord RunStore::TrainingBest() const {
  Statement best(db_,
                 "SELECT generation, idx FROM individuals ORDER BY fitness DESC, generation, idx "
                 "LIMIT 1");
  if (!best.Step()) throw RunStoreError(dir_ + ": the run has no evaluated individual yet");
  return LoadIndividual(static_cast<int>(best.Int(0)), static_cast<int>(best.Int(1)));
}

IndividualRecord RunStore::Best() const {
  const std::vector<ValidationRecord> validation = LoadValidation();
  if (validation.empty()) return TrainingBest();
  const ValidationRecord* chosen = &validation.front();
  for (const auto& v : validation)
    if (v.Median() > chosen->Median()) chosen = &v;  // the lower candidate number on ties
  return LoadIndividual(chosen->generation, chosen->index);
}

std::vector<IndividualRecord> RunStore::BestDistinct(int count) const {
  std::vector<IndividualRecord> out;
  std::set<std::string> seen;
  Statement rows(db_,
                 "SELECT generation, idx, genome_hash FROM individuals "
                 "ORDER BY fitness DESC, generation, idx");
  while (static_cast<int>(out.size()) < count && rows.Step())
    if (seen.insert(rows.Text(2)).second)
      out.push_back(LoadIndividual(static_cast<int>(rows.Int(0)), static_cast<int>(rows.Int(1))));
  return out;
}

void RunStore::CommitValidation(const std::vector<ValidationRecord>& candidates) {
  for (const auto& v : candidates) {
    LoadIndividual(v.generation, v.index);  // throws for an individual the run does not have
    if (v.fitness.size() != v.seeds.size() || v.fitness.empty())
      throw RunStoreError(dir_ + ": validation candidate " + std::to_string(v.candidate) + " has " +
                          std::to_string(v.fitness.size()) + " fitnesses for " +
                          std::to_string(v.seeds.size()) + " episodes");
    for (double f : v.fitness)
      if (!std::isfinite(f))
        throw RunStoreError(dir_ + ": validation candidate " + std::to_string(v.candidate) +
                            " has a non-finite fitness");
  }
  Exec("BEGIN IMMEDIATE");
  try {
    Exec(kValidationTable);
    Exec("DELETE FROM validation");
    Statement add(db_,
                  "INSERT INTO validation(candidate, generation, idx, episode, seed, fitness) "
                  "VALUES(?, ?, ?, ?, ?, ?)");
    for (const auto& v : candidates)
      for (std::size_t k = 0; k < v.seeds.size(); ++k)
        add.Bind(1, static_cast<std::int64_t>(v.candidate))
            .Bind(2, static_cast<std::int64_t>(v.generation))
            .Bind(3, static_cast<std::int64_t>(v.index))
            .Bind(4, static_cast<std::int64_t>(k))
            .Bind(5, ToSql(v.seeds[k]))
            .Bind(6, v.fitness[k])
            .Run();
    Exec("COMMIT");
  } catch (...) {
    sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
  Export();
}

std::vector<ValidationRecord> RunStore::LoadValidation() const {
  std::vector<ValidationRecord> out;
  if (!HasTable("validation")) return out;
  Statement rows(db_,
                 "SELECT candidate, generation, idx, seed, fitness FROM validation "
                 "ORDER BY candidate, episode");
  while (rows.Step()) {
    const int candidate = static_cast<int>(rows.Int(0));
    if (out.empty() || out.back().candidate != candidate) {
      out.emplace_back();
      out.back().candidate = candidate;
      out.back().generation = static_cast<int>(rows.Int(1));
      out.back().index = static_cast<int>(rows.Int(2));
    }
    out.back().seeds.push_back(FromSql(rows.Int(3)));
    out.back().fitness.push_back(rows.Real(4));
  }
  return out;
}

}  // namespace ahhs::evolver
