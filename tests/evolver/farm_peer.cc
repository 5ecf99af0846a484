// Test peer for the evaluation farm over a real bus:
//   farm_peer --role foreign-worker --lcm-url URL --seconds S
//       announces a worker of protocol version 99 on WORKER/STATUS every 200 ms
//   farm_peer --role foreign-evolver --lcm-url URL --worker ID
//       sends that worker a request of protocol version 99 and prints its answer; exit 0 when
//       the worker refused it with a message
#include <chrono>
#include <iostream>
#include <optional>
#include <thread>

#include "base/cli.h"
#include "bus/channels.h"
#include "bus/lcm_bus.h"
#include "bus/typed.h"
#include "evolver/farm/farm_codec.h"

namespace cli = ahhs::base::cli;

using namespace ahhs;

int main(int argc, char** argv) {
  cli::App app{"evaluation-farm test peer"};
  std::string role, url, worker;
  double seconds = 5;
  app.add_option("--role", role)
      ->required()
      ->check(cli::IsMember({"foreign-worker", "foreign-evolver"}));
  app.add_option("--lcm-url", url)->required();
  app.add_option("--seconds", seconds);
  app.add_option("--worker", worker);
  if (const int code = ahhs::base::Parse(app, argc, argv); code >= 0) return code;
  bus::LcmBus bus(url);
  const auto end = std::chrono::steady_clock::now() +
                   std::chrono::milliseconds(static_cast<long>(seconds * 1000));
  if (role == "foreign-worker") {
    evolver::WorkerStatus s;
    s.protocol_version = 99;
    s.worker = "future-worker";
    s.host = "future-host";
    long sent = 0;
    while (std::chrono::steady_clock::now() < end) {
      bus::PublishTyped(bus, bus::kWorkerStatusChannel, evolver::StatusMessage(s));
      ++sent;
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    std::cout << "foreign worker: " << sent << " statuses\n";
    return 0;
  }
  std::optional<eval_result_t> answer;
  auto subscription_50 = bus::SubscribeTyped<eval_result_t>(
      bus, bus::kEvalResultChannel, [&](const std::string&, const eval_result_t& r) {
        if (r.run == "foreign-run") answer = r;
      });
  evolver::FarmJob job;
  job.protocol_version = 99;
  job.run = "foreign-run";
  job.job = 1;
  job.worker = worker;
  job.config.kind = sim::ScenarioKind::kPendulum;
  job.config.num_modules = 2;
  job.genome_hash = 1;  // refused before its genome is looked for
  job.genome_chunks = 1;
  while (!answer && std::chrono::steady_clock::now() < end) {
    bus::PublishTyped(bus, bus::kEvalRequestChannel, evolver::RequestMessage(job));
    bus.Handle(std::chrono::milliseconds(200));
  }
  if (!answer) {
    std::cout << "no answer from " << worker << '\n';
    return 1;
  }
  std::cout << "status " << static_cast<int>(answer->status) << ": " << answer->message << '\n';
  return answer->status == eval_result_t::REFUSED && !answer->message.empty() ? 0 : 1;
}
