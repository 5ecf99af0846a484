#include "base/children.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <thread>

using ahhs::base::ChildProcesses;
using ahhs::base::DescendantSamples;
using ahhs::base::ParentPidFromStat;

TEST_CASE("the parent pid of a /proc stat line, whatever the command name holds") {
  CHECK(ParentPidFromStat("4242 (ahhs-worker) S 4100 4242 4100 0 -1") == 4100);
  CHECK(ParentPidFromStat("7 (a) b (c) R 1 7 7 0") == 1);  // spaces and parentheses in the name
  CHECK(ParentPidFromStat("8 (x)) S 3 8") == 3);
  CHECK(ParentPidFromStat("") == -1);
  CHECK(ParentPidFromStat("9 (no close S 3") == -1);
  CHECK(ParentPidFromStat("9 (x) S") == -1);
  CHECK(ParentPidFromStat("9 (x) S -5") == -1);
}

TEST_CASE("descendants are sampled with their state: a sleeping child is asleep, not starved") {
  ChildProcesses children;
  const std::size_t k = children.Start("sleeper", {"/bin/sleep", "30"}, true);
  const pid_t pid = children.pid(k);
  std::vector<ahhs::base::ProcessSample> samples;
  for (int i = 0; i < 200; ++i) {  // until the child has exec'd and sleeps
    samples = DescendantSamples();
    const auto it =
        std::find_if(samples.begin(), samples.end(), [&](const auto& s) { return s.pid == pid; });
    if (it != samples.end() && it->state == 'S') break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  const auto it =
      std::find_if(samples.begin(), samples.end(), [&](const auto& s) { return s.pid == pid; });
  REQUIRE(it != samples.end());
  CHECK(it->state == 'S');
  CHECK(it->cpu_ns >= 0);
  ahhs::base::CpuStarvation starvation(std::chrono::milliseconds(50));
  CHECK_FALSE(starvation.Starved());  // the first answer
  std::this_thread::sleep_for(std::chrono::milliseconds(60));
  CHECK_FALSE(starvation.Starved());  // asleep is not starved
  children.StopAll(std::chrono::milliseconds(500));
}
