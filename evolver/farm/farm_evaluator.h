// The evolver's side of the evaluation farm (docs/protocol.md, "Evaluation farm"): a
// FitnessEvaluator that hands a generation's jobs to the workers heard on WORKER/STATUS,
// collects EVAL/RESULT and re-issues what is lost, late or invalid (LeaseTable). Each genome's
// pieces go out on EVAL/GENOME once per generation, before its first request; the pieces a
// worker asks for on EVAL/WANT go out again, each at most every `piece_resend`. Which worker
// evaluated what never changes the results: an evaluation is a pure function of (scenario,
// genome, seed).
#pragma once

#include <ahhs/eval_result_t.hpp>
#include <ahhs/genome_want_t.hpp>
#include <ahhs/worker_status_t.hpp>
#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "bus/bus.h"
#include "bus/typed.h"
#include "evolver/farm/farm_protocol.h"
#include "evolver/farm/lease_table.h"
#include "evolver/ga/ga.h"

namespace ahhs::evolver {

class FarmError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
class FarmInterrupted : public std::runtime_error {
 public:
  FarmInterrupted() : std::runtime_error("interrupted") {}
};

struct FarmOptions {
  std::string run;  // run id on the wire
  sim::ScenarioConfig config;
  int population = 1;  // job id = (generation * population + index) * trials + trial
  int trials = 1;
  LeaseOptions lease;
  // A worker that returns this many invalid results gets no more jobs from this evolver.
  int quarantine_after = 3;
  // Give up when no usable worker has been heard for this long while jobs wait.
  std::chrono::milliseconds no_worker_timeout{60000};
  std::chrono::milliseconds piece_resend{100};
};

struct FarmCounters {
  std::int64_t dispatched = 0;
  std::int64_t reissued = 0;         // leases ended without a valid result
  std::int64_t invalid_results = 0;  // error status or non-finite fitness
  std::int64_t duplicates = 0;       // results ignored (late, repeated, unknown)
  std::int64_t states_missed = 0;    // reported by process arenas
  std::int64_t genomes_sent = 0;     // genomes whose pieces went out (once per generation)
  std::int64_t pieces_sent = 0;      // EVAL/GENOME messages, first sends and resends
  std::int64_t pieces_resent = 0;    // of which sent again on EVAL/WANT
  std::int64_t wants = 0;            // EVAL/WANT of this run heard
  bus::DecodeCounters results, statuses, wants_decoded;  // garbage on the farm channels
};

class FarmEvaluator : public FitnessEvaluator {
 public:
  // `interrupted()` is asked every loop (Ctrl-C); `poll()` is called every loop for the owner's
  // housekeeping (e.g. restarting local workers); `progress(done, total)` after every result;
  // `report(text)` gets one line per notable event (refused worker, re-issue, invalid result).
  // `workers_starved()` is asked every loop while no worker is heard: true when the owner's
  // local workers are alive but waiting for a CPU (a busy machine runs them at idle priority);
  // then the time without workers does not count.
  struct Hooks {
    std::function<bool()> interrupted = [] { return false; };
    std::function<void()> poll = [] {};
    std::function<void(std::size_t, std::size_t)> progress = [](std::size_t, std::size_t) {};
    std::function<void(const std::string&)> report = [](const std::string&) {};
    std::function<bool()> workers_starved = [] { return false; };
  };

  FarmEvaluator(bus::Bus* bus, FarmOptions options, Hooks hooks);
  ~FarmEvaluator() override;
  FarmEvaluator(const FarmEvaluator&) = delete;
  FarmEvaluator& operator=(const FarmEvaluator&) = delete;

  // Throws FarmInterrupted, or FarmError when no worker serves or a job keeps failing.
  std::vector<Evaluation> Evaluate(const std::vector<EvaluationJob>& jobs) override;

  // Waits until at least `count` workers are ready to serve this run (or the timeout, or an
  // interrupt); returns how many are. Ready: heard lately, idle or serving this run, and not
  // quarantined or dedicated to another run.
  int WaitForWorkers(int count, std::chrono::milliseconds timeout);

  const FarmCounters& counters() const { return counters_; }
  // Workers heard so far: id -> host.
  const std::map<std::string, std::string>& workers() const { return known_; }

 private:
  struct WorkerSeen {
    WorkerStatus status;
    FarmClock::time_point heard;
  };
  void OnStatus(const worker_status_t& msg);
  void OnResult(const eval_result_t& msg);
  void OnWant(const genome_want_t& msg);
  // Heard within worker_silence, and neither quarantined nor declined by a refusal.
  bool Usable(const std::string& name, const WorkerSeen& w, FarmClock::time_point now) const;
  int ReadyWorkers(FarmClock::time_point now) const;
  // The steps of one Evaluate() round.
  struct Batch;
  void FeedStatuses(Batch* batch, FarmClock::time_point now);
  void Dispatch(Batch* batch, FarmClock::time_point now);
  void CheckWorkers(Batch* batch, FarmClock::time_point now);
  void TakeResults(Batch* batch, FarmClock::time_point heard);
  void AnswerWants(Batch* batch, FarmClock::time_point now);
  // Publishes the genome of jobs[slot] the first time a job of the batch needs it.
  void SendGenome(Batch* batch, std::size_t slot, FarmJob* job);
  void OnInvalid(Batch* batch, const FarmResult& result, bool failed);

  bus::Bus* bus_;
  FarmOptions options_;
  Hooks hooks_;
  FarmCounters counters_;
  std::vector<bus::Subscription> subscriptions_;
  std::map<std::string, WorkerSeen> seen_;  // latest status of every compatible worker
  std::map<std::string, std::string> known_;
  std::set<std::string> refused_;
  std::map<std::string, int> invalid_by_worker_;
  std::set<std::string> quarantined_;
  std::set<std::string> declined_;  // workers that refused a job: they serve another run only
  std::vector<FarmResult> inbox_;   // results received during the current Handle()
  std::vector<GenomeWant> wants_;   // wants received during the current Handle()
};

}  // namespace ahhs::evolver
