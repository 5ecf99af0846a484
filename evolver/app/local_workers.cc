#include "evolver/app/local_workers.h"

#include <unistd.h>

#include "base/children.h"

namespace ahhs::evolver {

void StartLocalWorkers(base::ChildProcesses* local, int count, const std::string& url,
                       const std::string& arena, const std::string& run) {
  const std::string worker_bin = base::ExecutableDir() + "/ahhs-worker";
  for (int k = 0; k < count; ++k)
    local->Start(
        "local worker " + std::to_string(k),
        {worker_bin, "--quiet", "--lcm-url", url, "--arena-kind", arena, "--run", run, "--id",
         base::HostName() + ":" + std::to_string(getpid()) + "/w" + std::to_string(k)},
        true);
}

}  // namespace ahhs::evolver
