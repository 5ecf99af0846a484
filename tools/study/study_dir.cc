#include "tools/study/study_dir.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/atomic_file.h"
#include "evolver/store/run_store.h"
#include "sim/core/scenario.h"

namespace ahhs::study {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* kPlanFile = "study.toml";
constexpr const char* kSummaryFile = "summary.json";

// The physics version a run of this resolved ahhs-evolve configuration is measured with.
// The physics a run of this config is measured in: the one it keeps (ahhs-evolve --physics, a
// plan's `physics`), else this build's.
std::string PhysicsOf(const json& evolve_config) {
  return evolve_config.value("physics",
                             std::string(sim::PhysicsVersion(
                                 sim::ParseScenarioKind(evolve_config.value("scenario", "gait")),
                                 sim::ParseDocking(evolve_config.value("joints", "damped")))));
}
// A config without the physics it keeps: whether a run kept it by name or was made when it was
// the build's own, its settings are the same.
json WithoutPhysics(json evolve_config) {
  evolve_config.erase("physics");
  return evolve_config;
}
constexpr const char* kSummaryFormat = "ahhs-study-run";
// What an export keeps of a complete run.
const char* const kExportedFiles[] = {"best.json", "generations.csv", kSummaryFile};

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw StudyPlanError("cannot read " + path.string());
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Whole or not at all (evolver/store/atomic_file.h), in a folder made as needed.
void WriteFile(const fs::path& path, const std::string& text) {
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  try {
    base::WriteFileAtomically(path.string(), text);
  } catch (const std::runtime_error& e) {
    throw StudyPlanError(e.what());
  }
}

void CopyFile(const fs::path& from, const fs::path& to) { WriteFile(to, ReadFile(from)); }

// A study directory whose creation was killed: only configs/ (the plan, written last, is missing).
bool Unfinished(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec) || fs::exists(fs::path(dir) / kPlanFile, ec)) return false;
  bool any = false;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (entry.path().filename() != "configs") return false;
    any = true;
  }
  return any;
}

std::optional<json> ReadSummary(const fs::path& run_dir) {
  std::error_code ec;
  const fs::path path = run_dir / kSummaryFile;
  if (!fs::is_regular_file(path, ec)) return std::nullopt;
  try {
    json summary = json::parse(ReadFile(path));
    if (summary.value("format", "") != kSummaryFormat) return std::nullopt;
    return summary;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// Committed generations, best fitness and wall time from a run's generations.csv.
void ReadGenerationsCsv(const fs::path& path, RunState* state) {
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line)) return;  // header
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    if (cells.size() < 7) continue;
    try {
      const double best = std::stod(cells[1]);
      state->best = state->best ? std::max(*state->best, best) : best;
      state->wall_time += std::stod(cells[6]);
      ++state->generations_done;
    } catch (const std::exception&) {
      continue;
    }
  }
}

}  // namespace

const char* RunStateName(RunStateKind kind) {
  switch (kind) {
    case RunStateKind::kPending:
      return "pending";
    case RunStateKind::kStopped:
      return "stopped";
    case RunStateKind::kRunning:
      return "running";
    case RunStateKind::kFailed:
      return "failed";
    case RunStateKind::kComplete:
      return "complete";
  }
  return "?";
}

StudyDir::StudyDir(std::string dir, StudyPlan plan, std::string plan_text)
    : dir_(std::move(dir)), plan_(std::move(plan)), plan_text_(std::move(plan_text)) {}

StudyDir StudyDir::Create(const std::string& dir, const std::string& plan_path,
                          const StudyPlan& plan, const Resolver& resolve) {
  std::error_code ec;
  if (Unfinished(dir)) fs::remove_all(dir, ec);  // a creation killed before its plan was written
  if (fs::exists(dir, ec) && !(fs::is_directory(dir, ec) && fs::is_empty(dir, ec)))
    throw StudyPlanError(dir +
                         " already holds files; continue that study with ahhs-study run "
                         "--resume " +
                         dir);
  fs::create_directories(fs::path(dir) / "configs", ec);
  if (ec) throw StudyPlanError("cannot create " + dir + ": " + ec.message());
  const std::string text = ReadFile(plan_path);
  try {
    for (const StudyConfig& config : plan.configs) {
      const fs::path file = fs::path(dir) / "configs" / (config.name + ".toml");
      WriteFile(file, ResolvedConfigToml(config));
      json resolved;
      try {
        resolved = resolve(file.string());
      } catch (const StudyPlanError& e) {
        throw StudyPlanError(plan_path + ": configuration " + config.name + ": " + e.what());
      }
      WriteFile(fs::path(dir) / "configs" / (config.name + ".json"), resolved.dump(2) + "\n");
    }
  } catch (...) {
    fs::remove_all(dir, ec);  // nothing half-made stays behind
    throw;
  }
  WriteFile(fs::path(dir) / kPlanFile, text);  // last: its presence marks a study
  return StudyDir(dir, plan, text);
}

StudyDir StudyDir::Open(const std::string& dir) {
  std::error_code ec;
  const fs::path plan_path = fs::path(dir) / kPlanFile;
  if (Unfinished(dir))
    throw StudyPlanError(dir +
                         " is a study whose creation was interrupted (no runs yet); start it "
                         "again: ahhs-study run PLAN --out " +
                         dir);
  if (!fs::is_regular_file(plan_path, ec))
    throw StudyPlanError(dir + " is not a study directory (no " + kPlanFile + ")");
  const std::string text = ReadFile(plan_path);
  StudyPlan plan = ParseStudyPlan(text, plan_path.string(), false);
  for (const auto& config : plan.configs)
    for (const char* ext : {".toml", ".json"})
      if (!fs::is_regular_file(fs::path(dir) / "configs" / (config.name + ext), ec))
        throw StudyPlanError(dir + ": configs/" + config.name + ext + " is missing");
  return StudyDir(dir, std::move(plan), text);
}

std::string StudyDir::RunDir(const StudyRun& run) const {
  return (fs::path(dir_) / run.config / ("seed-" + std::to_string(run.seed))).string();
}
std::string StudyDir::LogFile(const StudyRun& run) const { return RunDir(run) + ".log"; }
std::string StudyDir::FailedFile(const StudyRun& run) const { return RunDir(run) + ".failed"; }
std::string StudyDir::ConfigFile(const std::string& config) const {
  return (fs::path(dir_) / "configs" / (config + ".toml")).string();
}

json StudyDir::EvolveConfig(const StudyRun& run) const {
  json config = json::parse(ReadFile(fs::path(dir_) / "configs" / (run.config + ".json")));
  config["seed"] = run.seed;
  return config;
}

RunState StudyDir::State(const StudyRun& run) const {
  RunState state;
  const fs::path run_dir = RunDir(run);
  try {
    state.generations = EvolveConfig(run).value("generations", 0);
  } catch (const std::exception&) {
  }
  std::error_code ec;
  ReadGenerationsCsv(run_dir / "generations.csv", &state);
  const bool has_database = fs::exists(run_dir / "run.sqlite", ec);
  if (const auto summary = ReadSummary(run_dir)) {
    state.kind = RunStateKind::kComplete;
    state.exported_only = !has_database;
    return state;
  }
  if (evolver::RunStore::InUse(run_dir.string())) {
    state.kind = RunStateKind::kRunning;
  } else if (fs::is_regular_file(FailedFile(run), ec)) {
    state.kind = RunStateKind::kFailed;
    std::istringstream text(ReadFile(FailedFile(run)));
    std::getline(text, state.note);
  } else if (has_database) {
    state.kind = RunStateKind::kStopped;
  }
  return state;
}

void StudyDir::WriteSummary(const StudyRun& run) const {
  const std::string run_dir = RunDir(run);
  try {
    auto store = evolver::RunStore::Open(run_dir, evolver::StoreAccess::kRead);
    const auto records = store->LoadGenerationRecords();
    const int generations = store->config().value("generations", 0);
    if (static_cast<int>(records.size()) != generations)
      throw StudyPlanError(run.Name() + " is not complete (" + std::to_string(records.size()) +
                           " of " + std::to_string(generations) + " generations)");
    double wall_time = 0;
    for (const auto& r : records) wall_time += r.wall_time;
    const evolver::IndividualRecord best = store->Best();
    json summary{
        {"format", kSummaryFormat},
        {"format_version", 1},
        {"study", plan_.name},
        {"config", run.config},
        {"seed", run.seed},
        {"run_id", store->run_id()},
        {"evolve_config", store->config()},
        {"generations", generations},
        {"best_fitness", best.evaluation.fitness},
        {"best_generation", best.generation},
        {"best_index", best.index},
        {"best_eval_seed", best.eval_seed},
        {"final_best", records.back().stats.best},
        {"wall_time_s", wall_time},
        {"physics", store->physics().empty() ? PhysicsOf(store->config()) : store->physics()}};
    // How the best was chosen, when a validation chose it (ahhs-evolve --validation).
    const std::vector<evolver::ValidationRecord> validation = store->LoadValidation();
    for (const auto& v : validation)
      if (v.generation == best.generation && v.index == best.index)
        summary["validation"] = {
            {"episodes", v.fitness.size()},
            {"candidates", validation.size()},
            {"median", v.Median()},
            {"training_best_fitness", store->TrainingBest().evaluation.fitness}};
    // The run's held-out post-evaluation (ahhs-evolve --post-eval), when it has one.
    const fs::path post_eval = fs::path(run_dir) / "post-eval.json";
    std::error_code exists_ec;
    if (fs::is_regular_file(post_eval, exists_ec)) {
      try {
        summary["post_eval"] = json::parse(ReadFile(post_eval));
      } catch (const json::exception& e) {
        throw StudyPlanError(post_eval.string() + ": " + e.what());
      }
    }
    store->Export();  // the database is the truth: its exports are whole before they are copied
    WriteFile(fs::path(run_dir) / kSummaryFile, summary.dump(2) + "\n");
  } catch (const evolver::RunStoreError& e) {
    throw StudyPlanError(e.what());
  }
}

int StudyDir::Export(const std::string& dest) const {
  std::error_code ec;
  const fs::path out(dest);
  if (fs::exists(out, ec) && !fs::is_empty(out, ec)) {
    if (!fs::is_regular_file(out / kPlanFile, ec))
      throw StudyPlanError(dest +
                           " holds files and is not a study export; give an empty or new "
                           "directory");
    const StudyPlan other =
        ParseStudyPlan(ReadFile(out / kPlanFile), (out / kPlanFile).string(), false);
    if (other.name != plan_.name)
      throw StudyPlanError(dest + " holds an export of the study " + other.name + ", not " +
                           plan_.name);
  }
  for (const auto& config : plan_.configs)
    for (const char* ext : {".toml", ".json"})
      CopyFile(fs::path(dir_) / "configs" / (config.name + ext),
               out / "configs" / (config.name + ext));
  int exported = 0;
  for (const StudyRun& run : Runs()) {
    const fs::path from = RunDir(run);
    if (!ReadSummary(from)) continue;
    const fs::path to = out / run.config / ("seed-" + std::to_string(run.seed));
    for (const char* file : kExportedFiles) CopyFile(from / file, to / file);
    ++exported;
  }
  WriteFile(out / kPlanFile, plan_text_);
  return exported;
}

std::vector<std::string> StudyDir::Import(const std::string& src,
                                          std::vector<std::string>* skipped) const {
  std::error_code ec;
  if (!fs::is_regular_file(fs::path(src) / kPlanFile, ec))
    throw StudyPlanError(src + " is not a study export (no " + kPlanFile + ")");
  std::vector<std::string> taken;
  for (const StudyRun& run : Runs()) {
    const fs::path from = fs::path(src) / run.config / ("seed-" + std::to_string(run.seed));
    const auto summary = ReadSummary(from);
    if (!summary) continue;
    if (ReadSummary(RunDir(run))) continue;  // complete here already
    const json config = EvolveConfig(run);
    if (WithoutPhysics(summary->value("evolve_config", json())) != WithoutPhysics(config) ||
        summary->value("physics", "") != PhysicsOf(config)) {
      if (skipped) skipped->push_back(run.Name());
      continue;
    }
    const fs::path to = RunDir(run);
    if (evolver::RunStore::InUse(to.string()))
      throw StudyPlanError(run.Name() + " is running; stop the study before importing");
    fs::remove_all(to, ec);
    fs::remove(FailedFile(run), ec);
    for (const char* file : kExportedFiles) CopyFile(from / file, to / file);
    taken.push_back(run.Name());
  }
  return taken;
}

}  // namespace ahhs::study
