#include "evolver/serve/service_run.h"

#include <stdexcept>

#include "sim/core/scenario.h"

namespace ahhs::evolver {

std::unique_ptr<RunStore> OpenServiceRun(const std::string& dir, bool resume, bool overwrite,
                                         const std::string& run_id, EvolveConfig* config) {
  if (!resume) {
    if (config->optimizer.empty()) throw std::invalid_argument("--optimizer must not be empty");
    const std::string error = CheckEvolveConfig(*config);
    if (!error.empty()) throw std::invalid_argument(error);
    return RunStore::Create(dir, run_id, config->seed, ConfigToJson(*config),
                            sim::PhysicsOf(config->scenario), overwrite);
  }
  auto store = RunStore::Open(dir, StoreAccess::kWrite);
  *config = ConfigFromJson(store->config());
  if (config->optimizer.empty())
    throw std::invalid_argument(dir + " is a run of the GA: resume it with ahhs-evolve --resume");
  const std::string own = sim::PhysicsVersion(config->scenario.kind, config->scenario.docking);
  if (!sim::CheckPhysics(config->scenario.kind, config->scenario.docking, store->physics())
           .empty() ||
      store->physics().empty())
    throw std::invalid_argument(
        dir + " was made with the " + std::string(sim::ScenarioName(config->scenario.kind)) +
        " physics of " + store->physics() + ", this build has " + own +
        " and does not simulate that one: resume it with the release that does, or start a new "
        "run");
  sim::KeepPhysics(store->physics(), &config->scenario);
  store->Export(true);
  return store;
}

}  // namespace ahhs::evolver
