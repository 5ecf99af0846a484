// The evaluation farm in one process over memq://: FarmEvaluator and WorkerNodes on one bus
// (the workers are polled from the evaluator's loop). Results must not depend on how many
// workers served, which failed, or what else was on the bus.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <random>

#include "bus/channels.h"
#include "bus/lcm_bus.h"
#include "evolver/farm/farm_codec.h"
#include "evolver/farm/farm_evaluator.h"
#include "evolver/farm/worker_node.h"
#include "evolver/ga/ga.h"
#include "sim/core/constants.h"

using namespace ahhs;
using namespace ahhs::evolver;

namespace {

// A deterministic stand-in for an episode: depends on every gene and the seed.
double FakeFitness(const modules::Genome& g, std::uint64_t seed) {
  return static_cast<double>(modules::GenomeHash(g) % 100003) * 1e-5 +
         static_cast<double>(seed % 1009) * 1e-9;
}

FarmResult Good(const FarmJob& job) {
  FarmResult o;
  o.fitness = FakeFitness(job.genome, job.seed);
  o.cost = 1;
  return o;
}

struct Batch {
  std::vector<modules::Genome> genomes;
  std::vector<EvaluationJob> jobs;
  explicit Batch(int n) {
    GaParams p;
    p.population = n;
    genomes = InitialPopulation({modules::Variant::kAhhs2, 3, 5, 10, 2}, p, 77);
    for (int i = 0; i < n; ++i)
      jobs.push_back({2, i, 0, &genomes[static_cast<std::size_t>(i)], EvaluationSeed(77, 2, i)});
  }
  void CheckResults(const std::vector<Evaluation>& results) const {
    REQUIRE(results.size() == jobs.size());
    for (std::size_t k = 0; k < jobs.size(); ++k)
      CHECK(results[k].fitness == FakeFitness(*jobs[k].genome, jobs[k].seed));
  }
};

FarmOptions FastFarm() {
  FarmOptions o;
  o.run = "test-run/s1";
  o.config.kind = sim::ScenarioKind::kPendulum;
  o.config.num_modules = 2;
  o.population = 100;
  o.lease.job_deadline = std::chrono::milliseconds(2000);
  o.lease.worker_silence = std::chrono::milliseconds(300);
  o.lease.status_grace = std::chrono::milliseconds(200);
  o.no_worker_timeout = std::chrono::milliseconds(1500);
  return o;
}

}  // namespace

TEST_CASE("one or three workers give the same results as evaluating in place") {
  for (int n_workers : {1, 3}) {
    bus::LcmBus bus("memq://");
    std::vector<std::unique_ptr<WorkerNode>> workers;
    for (int w = 0; w < n_workers; ++w)
      workers.push_back(std::make_unique<WorkerNode>(&bus, "w" + std::to_string(w), "host", Good,
                                                     std::chrono::milliseconds(50)));
    FarmEvaluator::Hooks hooks;
    std::size_t last_progress = 0;
    hooks.interrupted = [&] {
      for (auto& w : workers) w->Poll(std::chrono::microseconds(0));
      return false;
    };
    hooks.progress = [&](std::size_t done, std::size_t total) {
      CHECK(done > last_progress);
      CHECK(total == 30);
      last_progress = done;
    };
    FarmEvaluator farm(&bus, FastFarm(), hooks);
    Batch batch(30);
    const auto results = farm.Evaluate(batch.jobs);
    batch.CheckResults(results);
    CHECK(last_progress == 30);
    CHECK(farm.counters().reissued == 0);
    std::int64_t total = 0;
    for (auto& w : workers) total += w->counters().evaluations;
    CHECK(total == 30);
    if (n_workers == 3)
      for (auto& w : workers) CHECK(w->counters().evaluations > 0);  // the load was spread
  }
}

TEST_CASE(
    "waiting for workers counts those ready to serve this run, not one dedicated to another") {
  bus::LcmBus bus("memq://");
  WorkerNode any(&bus, "any", "host", Good, std::chrono::milliseconds(50));
  WorkerNode ours(&bus, "ours", "host", Good, std::chrono::milliseconds(50));
  WorkerNode theirs(&bus, "theirs", "host", Good, std::chrono::milliseconds(50));
  ours.ServeOnlyRun("test-run");  // the evolver's session test-run/s1 is of this run
  theirs.ServeOnlyRun("other-run");
  bool stop = false;
  FarmEvaluator::Hooks hooks;
  hooks.poll = [&] {
    for (WorkerNode* w : {&any, &ours, &theirs}) w->Poll(std::chrono::microseconds(0));
  };
  hooks.interrupted = [&] { return stop; };
  FarmEvaluator farm(&bus, FastFarm(), hooks);
  CHECK(farm.WaitForWorkers(2, std::chrono::milliseconds(5000)) == 2);
  // A third never comes: the wait ends at its timeout with the two, all three heard.
  CHECK(farm.WaitForWorkers(3, std::chrono::milliseconds(400)) == 2);
  CHECK(farm.workers().size() == 3);
  // They serve: the batch's results are as in place, none from the dedicated worker.
  Batch batch(6);
  batch.CheckResults(farm.Evaluate(batch.jobs));
  CHECK(theirs.counters().evaluations == 0);
  stop = true;
  CHECK_THROWS_AS(farm.WaitForWorkers(3, std::chrono::milliseconds(5000)), FarmInterrupted);
}

TEST_CASE("a worker that returns NaN gets its jobs re-issued elsewhere, and it is reported") {
  bus::LcmBus bus("memq://");
  auto nan_fitness = [](const FarmJob& job) {
    FarmResult o = Good(job);
    o.fitness = std::numeric_limits<double>::quiet_NaN();
    return o;
  };
  WorkerNode bad(&bus, "bad", "host", nan_fitness, std::chrono::milliseconds(50));
  WorkerNode good(&bus, "good", "host", Good, std::chrono::milliseconds(50));
  std::vector<std::string> reports;
  FarmEvaluator::Hooks hooks;
  hooks.interrupted = [&] {
    bad.Poll(std::chrono::microseconds(0));
    good.Poll(std::chrono::microseconds(0));
    return false;
  };
  hooks.report = [&](const std::string& s) { reports.push_back(s); };
  FarmEvaluator farm(&bus, FastFarm(), hooks);
  Batch batch(12);
  const auto results = farm.Evaluate(batch.jobs);
  batch.CheckResults(results);
  for (const auto& r : results) CHECK(r.worker == "good");
  CHECK(bad.counters().evaluations > 0);
  CHECK(farm.counters().invalid_results >= 1);
  CHECK(farm.counters().invalid_results <= 3);  // then it is quarantined
  REQUIRE_FALSE(reports.empty());
  CHECK_THAT(reports.front(), Catch::Contains("non-finite") && Catch::Contains("bad"));
  if (farm.counters().invalid_results == 3)
    CHECK(std::any_of(reports.begin(), reports.end(), [](const std::string& r) {
      return r.find("worker bad returned 3 invalid results") != std::string::npos;
    }));
}

TEST_CASE("a worker that dies mid-batch: its jobs are re-issued, results unchanged") {
  bus::LcmBus bus("memq://");
  WorkerNode dying(&bus, "dying", "host", Good, std::chrono::milliseconds(50));
  WorkerNode steady(&bus, "steady", "host", Good, std::chrono::milliseconds(50));
  FarmEvaluator::Hooks hooks;
  hooks.interrupted = [&] {
    // "dying" evaluates two jobs, then never answers again (its queue is lost with it).
    if (dying.counters().evaluations < 2) dying.Poll(std::chrono::microseconds(0));
    steady.Poll(std::chrono::microseconds(0));
    return false;
  };
  FarmEvaluator farm(&bus, FastFarm(), hooks);
  Batch batch(20);
  batch.CheckResults(farm.Evaluate(batch.jobs));
  CHECK(dying.counters().evaluations == 2);
  CHECK(farm.counters().reissued >= 1);
}

TEST_CASE("foreign protocol versions, garbage and other runs' results are ignored") {
  bus::LcmBus bus("memq://");
  WorkerNode good(&bus, "good", "host", Good, std::chrono::milliseconds(50));
  std::vector<std::string> reports;
  FarmEvaluator::Hooks hooks;
  int loops = 0;
  hooks.interrupted = [&] {
    if (++loops % 3 == 0) {
      // A worker of a future protocol version announces itself.
      WorkerStatus foreign;
      foreign.protocol_version = 99;
      foreign.worker = "future";
      foreign.host = "elsewhere";
      bus::PublishTyped(bus, bus::kWorkerStatusChannel, StatusMessage(foreign));
      // Garbage on every farm channel.
      const std::uint8_t junk[] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
      for (const char* ch :
           {bus::kEvalRequestChannel, bus::kEvalResultChannel, bus::kWorkerStatusChannel})
        bus.Publish(ch, junk, sizeof junk);
      // A result of another run for a job id of ours.
      FarmResult stray;
      stray.run = "other/s1";
      stray.job = 200;
      stray.fitness = -5;
      stray.worker = "good";
      bus::PublishTyped(bus, bus::kEvalResultChannel, ResultMessage(stray));
    }
    good.Poll(std::chrono::microseconds(0));
    return false;
  };
  hooks.report = [&](const std::string& s) { reports.push_back(s); };
  FarmEvaluator farm(&bus, FastFarm(), hooks);
  Batch batch(10);
  batch.CheckResults(farm.Evaluate(batch.jobs));
  CHECK(farm.counters().results.dropped > 0);
  CHECK(farm.counters().statuses.dropped > 0);
  CHECK(good.counters().requests.dropped > 0);
  REQUIRE(reports.size() == 1);  // said once, not per status
  CHECK_THAT(reports[0], Catch::Contains("refused worker future") && Catch::Contains("99"));
  CHECK(farm.workers().count("future") == 0);
}

TEST_CASE("a worker refuses a request of another protocol version and says why") {
  bus::LcmBus bus("memq://");
  WorkerNode worker(&bus, "w", "host", Good);
  std::vector<eval_result_t> results;
  auto subscription_195 = bus::SubscribeTyped<eval_result_t>(
      bus, bus::kEvalResultChannel,
      [&](const std::string&, const eval_result_t& r) { results.push_back(r); });
  Batch batch(1);
  FarmJob job;
  job.protocol_version = kFarmProtocolVersion + 1;
  job.run = "r";
  job.job = 5;
  job.worker = "w";
  job.config.kind = sim::ScenarioKind::kPendulum;
  job.config.num_modules = 2;
  job.genome = batch.genomes[0];
  bus::PublishTyped(bus, bus::kEvalRequestChannel, RequestMessage(job));
  worker.Poll(std::chrono::milliseconds(10));
  bus.Handle(std::chrono::milliseconds(0));
  REQUIRE(results.size() == 1);
  CHECK(results[0].status == eval_result_t::REFUSED);
  CHECK_THAT(results[0].message, Catch::Contains("version"));
  CHECK(worker.counters().refused == 1);
  CHECK(worker.counters().evaluations == 0);
}

TEST_CASE(
    "a worker refuses a job in a physics its build does not simulate, and takes an earlier one it "
    "does") {
  bus::LcmBus bus("memq://");
  std::vector<std::string> evaluated_in;
  WorkerNode worker(&bus, "w", "host", [&](const FarmJob& j) {
    evaluated_in.push_back(sim::PhysicsOf(j.config));
    return Good(j);
  });
  std::vector<eval_result_t> results;
  auto subscription = bus::SubscribeTyped<eval_result_t>(
      bus, bus::kEvalResultChannel,
      [&](const std::string&, const eval_result_t& r) { results.push_back(r); });
  Batch batch(1);
  const EncodedGenome encoded = EncodeGenome(batch.genomes[0]);
  const auto pieces = SplitGenome(encoded.hash, encoded.bytes);
  for (const auto& piece : pieces)
    bus::PublishTyped(bus, bus::kEvalGenomeChannel, PieceMessage(piece));
  FarmJob job;
  job.run = "r";
  job.worker = "w";
  job.config = sim::MakeScenarioConfig(sim::ScenarioKind::kGait, sim::DockingKind::kFixed, 5, 1);
  job.genome_hash = encoded.hash;
  job.genome_bytes = static_cast<int>(encoded.bytes.size());
  job.genome_chunks = static_cast<int>(pieces.size());
  job.deadline_utime = bus::NowUtime() + 60000000;
  eval_request_t future = RequestMessage(job);
  CHECK(future.physics == sim::kGaitFixedPhysicsVersion);  // by name, never ""
  future.physics = "2999-01-01";
  future.job = 1;
  bus::PublishTyped(bus, bus::kEvalRequestChannel, future);
  job.job = 2;
  job.config.physics = sim::kGaitChainColdPhysicsVersion;
  bus::PublishTyped(bus, bus::kEvalRequestChannel, RequestMessage(job));
  for (int i = 0; i < 20 && results.size() < 2; ++i) {
    worker.Poll(std::chrono::milliseconds(10));
    bus.Handle(std::chrono::milliseconds(0));
  }
  REQUIRE(results.size() == 2);
  CHECK(results[0].job == 1);
  CHECK(results[0].status == eval_result_t::REFUSED);
  CHECK_THAT(results[0].message, Catch::Contains("this build simulates the gait physics of") &&
                                     Catch::Contains("not 2999-01-01"));
  CHECK(results[1].job == 2);
  CHECK(results[1].status == eval_result_t::OK);
  CHECK(evaluated_in == std::vector<std::string>{std::string(sim::kGaitChainColdPhysicsVersion)});
  CHECK(worker.counters().refused == 1);
}

TEST_CASE("without any worker the farm gives up with a clear error, Ctrl-C interrupts", "[wall]") {
  bus::LcmBus bus("memq://");
  {
    FarmEvaluator farm(&bus, FastFarm(), {});
    Batch batch(3);
    CHECK_THROWS_WITH(farm.Evaluate(batch.jobs), Catch::Contains("no evaluation worker"));
  }
  {
    FarmEvaluator::Hooks hooks;
    int loops = 0;
    hooks.interrupted = [&] { return ++loops > 5; };
    FarmEvaluator farm(&bus, FastFarm(), hooks);
    Batch batch(3);
    CHECK_THROWS_AS(farm.Evaluate(batch.jobs), FarmInterrupted);
  }
}

namespace {
// A bus that refuses the first `refusals` sends on one channel, as a transport may.
class RefusingBus final : public bus::Bus {
 public:
  RefusingBus(std::string channel, int refusals) : channel_(std::move(channel)), left_(refusals) {}
  bool Publish(const std::string& channel, const void* data, std::size_t size) override {
    if (channel == channel_ && left_ > 0) {
      --left_;
      return false;
    }
    return inner_.Publish(channel, data, size);
  }
  int Subscribe(const std::string& regex, bus::RawHandler handler, int capacity) override {
    return inner_.Subscribe(regex, std::move(handler), capacity);
  }
  void Unsubscribe(int id) override { inner_.Unsubscribe(id); }
  int Handle(std::chrono::microseconds timeout) override { return inner_.Handle(timeout); }
  void CountUnencodable(const std::string& channel) override { inner_.CountUnencodable(channel); }
  const bus::BusStats& stats() const override { return inner_.stats(); }

 private:
  bus::LcmBus inner_{"memq://"};
  std::string channel_;
  int left_;
};

FarmJob OneJob(const std::string& worker) {
  Batch batch(1);
  FarmJob job;
  job.protocol_version = kFarmProtocolVersion;
  job.run = "r";
  job.job = 5;
  job.attempt = 1;
  job.worker = worker;
  job.config.kind = sim::ScenarioKind::kPendulum;
  job.config.num_modules = 2;
  job.genome = batch.genomes[0];
  job.deadline_utime = bus::NowUtime() + 10'000'000;
  return job;
}

// Publishes the job's genome pieces (unless `pieces` is false), then its request.
void SendJob(bus::Bus& bus, FarmJob job, bool pieces = true) {
  const EncodedGenome encoded = EncodeGenome(job.genome);
  const auto split = SplitGenome(encoded.hash, encoded.bytes);
  job.genome_hash = encoded.hash;
  job.genome_bytes = static_cast<int>(encoded.bytes.size());
  job.genome_chunks = static_cast<int>(split.size());
  if (pieces)
    for (const auto& p : split) bus::PublishTyped(bus, bus::kEvalGenomeChannel, PieceMessage(p));
  bus::PublishTyped(bus, bus::kEvalRequestChannel, RequestMessage(job));
}
}  // namespace

TEST_CASE("a request whose strings are not text is dropped at decode and counted") {
  bus::LcmBus bus("memq://");
  WorkerNode worker(&bus, "w", "host", Good);
  eval_request_t request = RequestMessage(OneJob("w"));
  request.run = "r\x01n";  // made "r\0n" below: lcm-gen's encoder cannot write a NUL itself
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(request.getEncodedSize()));
  REQUIRE(request.encode(bytes.data(), 0, static_cast<int>(bytes.size())) ==
          static_cast<int>(bytes.size()));
  const auto at = std::search(bytes.begin(), bytes.end(), request.run.begin(), request.run.end());
  REQUIRE(at != bytes.end());
  at[1] = 0;
  bus.Publish(bus::kEvalRequestChannel, bytes.data(), bytes.size());
  worker.Poll(std::chrono::milliseconds(10));
  worker.Poll(std::chrono::milliseconds(0));
  CHECK(worker.counters().requests.dropped == 1);
  CHECK(worker.counters().requests.decoded == 0);
  CHECK(worker.counters().evaluations == 0);
}

TEST_CASE("a result the bus does not send is counted and answered by an error result") {
  RefusingBus bus(bus::kEvalResultChannel, 1);
  WorkerNode worker(&bus, "w", "host", Good);
  std::vector<eval_result_t> results;
  auto subscription = bus::SubscribeTyped<eval_result_t>(
      bus, bus::kEvalResultChannel,
      [&](const std::string&, const eval_result_t& r) { results.push_back(r); });
  SendJob(bus, OneJob("w"));
  worker.Poll(std::chrono::milliseconds(10));  // takes the request
  worker.Poll(std::chrono::milliseconds(0));   // evaluates; the result is refused
  bus.Handle(std::chrono::milliseconds(0));
  CHECK(worker.counters().evaluations == 1);
  CHECK(worker.counters().unsent_results == 1);
  REQUIRE(results.size() == 1);
  CHECK(results[0].status == eval_result_t::ERROR);
  CHECK(results[0].job == 5);
  CHECK_THAT(results[0].message, Catch::Contains("could not send the result of job 5"));
}

namespace {
// One node's view of a shared bus that loses a seeded fraction of the messages it receives on
// one channel (as a host behind a lossy link would).
class LossyView final : public bus::Bus {
 public:
  LossyView(bus::Bus* inner, std::string channel, double drop, std::uint64_t seed)
      : inner_(inner), channel_(std::move(channel)), drop_(drop), rng_(seed) {}
  bool Publish(const std::string& channel, const void* data, std::size_t size) override {
    return inner_->Publish(channel, data, size);
  }
  int Subscribe(const std::string& regex, bus::RawHandler handler, int capacity) override {
    return inner_->Subscribe(
        regex,
        [this, handler = std::move(handler)](const std::string& channel, const std::uint8_t* data,
                                             std::size_t size) {
          if (channel == channel_ && std::uniform_real_distribution<>(0, 1)(rng_) < drop_) {
            ++dropped_;
            return;
          }
          handler(channel, data, size);
        },
        capacity);
  }
  void Unsubscribe(int id) override { inner_->Unsubscribe(id); }
  int Handle(std::chrono::microseconds timeout) override { return inner_->Handle(timeout); }
  void CountUnencodable(const std::string& channel) override { inner_->CountUnencodable(channel); }
  const bus::BusStats& stats() const override { return inner_->stats(); }
  int dropped() const { return dropped_; }

 private:
  bus::Bus* inner_;
  std::string channel_;
  double drop_;
  std::mt19937_64 rng_;
  int dropped_ = 0;
};

// A population of AHHS1-300 genomes (about 17 kB each on the wire, as in the LAN test).
struct BigBatch {
  std::vector<modules::Genome> genomes;
  std::vector<EvaluationJob> jobs;
  explicit BigBatch(int n) {
    GaParams p;
    p.population = n;
    genomes = InitialPopulation({modules::Variant::kAhhs1, 5, 300, 4, 2}, p, 78);
    for (int i = 0; i < n; ++i)
      jobs.push_back({0, i, 0, &genomes[static_cast<std::size_t>(i)], EvaluationSeed(78, 0, i)});
  }
};
}  // namespace

TEST_CASE("every farm message fits one datagram and each genome goes out once per generation") {
  bus::LcmBus bus("memq://");
  std::vector<std::unique_ptr<WorkerNode>> workers;
  for (int w = 0; w < 2; ++w)
    workers.push_back(std::make_unique<WorkerNode>(&bus, "w" + std::to_string(w), "host", Good,
                                                   std::chrono::milliseconds(50)));
  std::size_t largest = 0;
  std::map<std::string, int> count;
  auto spy = bus::Subscription(
      &bus, bus.Subscribe(
                "EVAL/.*|WORKER/STATUS",
                [&](const std::string& channel, const std::uint8_t*, std::size_t size) {
                  // An LCM datagram: 8-byte header, the channel and its NUL, the message.
                  largest = std::max(largest, 8 + channel.size() + 1 + size);
                  ++count[channel];
                },
                bus::kDefaultQueueCapacity));
  FarmEvaluator::Hooks hooks;
  hooks.interrupted = [&] {
    for (auto& w : workers) w->Poll(std::chrono::microseconds(0));
    return false;
  };
  FarmEvaluator farm(&bus, FastFarm(), hooks);
  BigBatch batch(6);
  batch.genomes[5] = batch.genomes[4];  // an elite twice: its genome still goes out once
  const auto results = farm.Evaluate(batch.jobs);
  for (std::size_t k = 0; k < batch.jobs.size(); ++k)
    CHECK(results[k].fitness == FakeFitness(*batch.jobs[k].genome, batch.jobs[k].seed));
  const std::size_t genome_bytes = EncodeGenome(batch.genomes[0]).bytes.size();
  CHECK(genome_bytes > 15000);
  const int pieces = static_cast<int>((genome_bytes + kGenomePieceBytes - 1) / kGenomePieceBytes);
  CHECK(largest <= 1472);  // an Ethernet MTU of 1500 less the IP and UDP headers
  CHECK(count["EVAL/GENOME"] == 5 * pieces);
  CHECK(farm.counters().genomes_sent == 5);
  CHECK(farm.counters().pieces_resent == 0);
  CHECK(count["EVAL/REQUEST"] == 6);
  CHECK(count["EVAL/WANT"] == 0);
}

TEST_CASE("workers that lose pieces ask for them and give the same results, with no re-issue") {
  bus::LcmBus bus("memq://");
  std::vector<std::unique_ptr<LossyView>> views;
  std::vector<std::unique_ptr<WorkerNode>> workers;
  for (int w = 0; w < 2; ++w) {
    views.push_back(std::make_unique<LossyView>(&bus, bus::kEvalGenomeChannel, 0.3, 11 + w));
    workers.push_back(std::make_unique<WorkerNode>(views.back().get(), "w" + std::to_string(w),
                                                   "host", Good, std::chrono::milliseconds(50),
                                                   std::chrono::milliseconds(20)));
  }
  FarmEvaluator::Hooks hooks;
  hooks.interrupted = [&] {
    for (auto& w : workers) w->Poll(std::chrono::microseconds(0));
    return false;
  };
  FarmOptions options = FastFarm();
  options.piece_resend = std::chrono::milliseconds(10);
  FarmEvaluator farm(&bus, options, hooks);
  BigBatch batch(8);
  const auto results = farm.Evaluate(batch.jobs);
  for (std::size_t k = 0; k < batch.jobs.size(); ++k)
    CHECK(results[k].fitness == FakeFitness(*batch.jobs[k].genome, batch.jobs[k].seed));
  CHECK(views[0]->dropped() + views[1]->dropped() > 10);
  CHECK(workers[0]->counters().wants + workers[1]->counters().wants > 0);
  CHECK(farm.counters().wants > 0);
  CHECK(farm.counters().pieces_resent > 0);
  CHECK(farm.counters().reissued == 0);
  CHECK(workers[0]->counters().evaluations + workers[1]->counters().evaluations == 8);
}

TEST_CASE("a job whose genome never comes is dropped at its deadline, asked for until then") {
  bus::LcmBus bus("memq://");
  WorkerNode worker(&bus, "w", "host", Good, std::chrono::milliseconds(1000),
                    std::chrono::milliseconds(20));
  std::vector<genome_want_t> wants;
  auto spy = bus::SubscribeTyped<genome_want_t>(
      bus, bus::kEvalWantChannel,
      [&](const std::string&, const genome_want_t& w) { wants.push_back(w); });
  FarmJob job = OneJob("w");
  job.deadline_utime = bus::NowUtime() + 200'000;
  SendJob(bus, job, /*pieces=*/false);
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(400);
  while (std::chrono::steady_clock::now() < end) worker.Poll(std::chrono::milliseconds(5));
  bus.Handle(std::chrono::milliseconds(0));
  REQUIRE(wants.size() >= 3);
  CHECK(wants[0].run == "r");
  CHECK(wants[0].worker == "w");
  CHECK(static_cast<std::uint64_t>(wants[0].genome_hash) == modules::GenomeHash(job.genome));
  CHECK(wants[0].num_missing ==
        static_cast<int>(SplitGenome(1, EncodeGenome(job.genome).bytes).size()));
  CHECK(worker.counters().expired_waits == 1);
  CHECK(worker.counters().evaluations == 0);
}

TEST_CASE("pieces that are not the genome named are asked for again, then the job is refused") {
  bus::LcmBus bus("memq://");
  WorkerNode worker(&bus, "w", "host", Good, std::chrono::milliseconds(1000),
                    std::chrono::milliseconds(20));
  std::vector<eval_result_t> results;
  auto spy = bus::SubscribeTyped<eval_result_t>(
      bus, bus::kEvalResultChannel,
      [&](const std::string&, const eval_result_t& r) { results.push_back(r); });
  Batch batch(2);
  FarmJob job = OneJob("w");
  job.genome = batch.genomes[0];
  // The pieces of another genome of the same size, labelled with this genome's hash.
  const EncodedGenome other = EncodeGenome(batch.genomes[1]);
  const std::uint64_t hash = EncodeGenome(job.genome).hash;
  REQUIRE(other.bytes.size() == EncodeGenome(job.genome).bytes.size());
  auto send_wrong_pieces = [&] {
    for (const auto& p : SplitGenome(hash, other.bytes))
      bus::PublishTyped(bus, bus::kEvalGenomeChannel, PieceMessage(p));
  };
  send_wrong_pieces();
  SendJob(bus, job, /*pieces=*/false);
  worker.Poll(std::chrono::milliseconds(10));
  worker.Poll(std::chrono::milliseconds(10));
  CHECK(worker.counters().damaged_genomes == 1);
  CHECK(results.empty());  // asked again first
  send_wrong_pieces();
  worker.Poll(std::chrono::milliseconds(10));
  worker.Poll(std::chrono::milliseconds(10));
  bus.Handle(std::chrono::milliseconds(0));
  CHECK(worker.counters().damaged_genomes == 2);
  REQUIRE(results.size() == 1);
  CHECK(results[0].status == eval_result_t::ERROR);
  CHECK_THAT(results[0].message, Catch::Contains("another genome than the request names"));
  CHECK(worker.counters().evaluations == 0);
}
