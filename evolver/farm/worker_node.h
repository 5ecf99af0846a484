// The worker's protocol role (docs/protocol.md, "Evaluation farm"): takes the EVAL/REQUEST jobs
// addressed to it, finds each job's genome among the pieces heard on EVAL/GENOME (asking on
// EVAL/WANT, every `want_period`, for pieces it misses until the job's deadline), evaluates the
// jobs one at a time through an injected function, publishes each EVAL/RESULT, and announces
// itself on WORKER/STATUS about once a second and on every change.
// One evaluation at a time per worker process: ODE's solver RNG is process-global, so a host
// with several cores runs several worker processes (ahhs-worker --slots N).
#pragma once

#include <ahhs/eval_request_t.hpp>
#include <ahhs/genome_chunk_t.hpp>
#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <tuple>

#include "bus/bus.h"
#include "bus/typed.h"
#include "evolver/farm/farm_protocol.h"
#include "evolver/farm/genome_pieces.h"

namespace ahhs::evolver {

struct WorkerCounters {
  std::int64_t evaluations = 0;
  std::int64_t refused = 0;          // requests of another protocol version or another run
  std::int64_t bad_requests = 0;     // addressed to us but unusable (bad scenario or genome)
  std::int64_t unsent_results = 0;   // results the bus did not send (answered by an error result)
  std::int64_t wants = 0;            // EVAL/WANT sent (pieces of a job's genome missing)
  std::int64_t damaged_genomes = 0;  // assembled pieces that were not the genome named
  std::int64_t expired_waits = 0;    // jobs dropped at their deadline, genome still incomplete
  bus::DecodeCounters requests;      // garbage on EVAL/REQUEST is counted here and dropped
  bus::DecodeCounters pieces;        // garbage on EVAL/GENOME (and malformed pieces)
};

class WorkerNode {
 public:
  // Evaluates one job; must fill status, fitness, cost, states_missed and message.
  using EvaluateFn = std::function<FarmResult(const FarmJob&)>;

  WorkerNode(bus::Bus* bus, std::string id, std::string host, EvaluateFn evaluate,
             std::chrono::milliseconds status_period = std::chrono::milliseconds(1000),
             std::chrono::milliseconds want_period = std::chrono::milliseconds(250));
  ~WorkerNode();
  WorkerNode(const WorkerNode&) = delete;
  WorkerNode& operator=(const WorkerNode&) = delete;

  // Serves until `stop()` is true (asked at least every 100 ms between evaluations).
  void Serve(const std::function<bool()>& stop);
  // One round: handle messages for at most `wait`, evaluate one queued job if any, heartbeat.
  void Poll(std::chrono::microseconds wait);

  // Serve the run with this id only (ahhs-worker --run): requests of other runs are refused, and
  // every status names the run, so that other evolvers pass this worker over. "" = any run.
  // Call it before the first Poll or Serve: the first status goes out then.
  void ServeOnlyRun(std::string run_id) { serve_run_ = std::move(run_id); }

  const WorkerCounters& counters() const { return counters_; }
  const std::string& id() const { return id_; }

 private:
  struct Waiting {
    FarmJob job;
    std::chrono::steady_clock::time_point last_want;
  };
  void OnRequest(const eval_request_t& msg);
  void OnPiece(const genome_chunk_t& msg);
  // Moves the waiting jobs whose genome is complete to the queue, drops those past their
  // deadline, and asks again for the pieces of the others.
  void ServeWaiting();
  enum class Found { kYes, kNotYet, kBad };
  Found FindGenome(FarmJob* job, std::string* error);
  void SendWant(Waiting* waiting);
  void PublishStatus();
  void SendResult(const FarmResult& result);
  void SendError(const FarmJob& job, const std::string& message);

  bus::Bus* bus_;
  std::string id_, host_;
  EvaluateFn evaluate_;
  std::chrono::milliseconds status_period_, want_period_;
  std::chrono::steady_clock::time_point last_status_{};
  GenomeCache cache_;
  std::map<std::uint64_t, int> damaged_;  // genome hash -> assemblies that were not it
  std::deque<Waiting> waiting_;           // jobs whose genome is still incomplete
  std::deque<FarmJob> queue_;
  std::int64_t current_job_ = -1;
  std::string current_run_;
  std::string serve_run_;  // "" = any run
  // (run, job, attempt) already taken: a repeated request is not evaluated twice.
  std::set<std::tuple<std::string, std::int64_t, int>> seen_;
  WorkerCounters counters_;
  bus::Subscription request_subscription_, piece_subscription_;
};

}  // namespace ahhs::evolver
