// The evolver's bookkeeping of one batch of evaluation jobs (docs/protocol.md, "Evaluation
// farm"): which worker holds which job under a lease, until when, and what to re-issue. Pure
// logic over an injected clock: no LCM, no I/O, tested with a fake time.
//
// Rules:
// - A job is leased to one worker at a time; its attempt number grows with every issue.
// - A lease ends with a result, or is re-issued when its deadline passes, when its worker has
//   been silent for `worker_silence`, or when a status from its worker heard more than
//   `status_grace` after the dispatch does not list it (the request or the result was lost).
// - Results are idempotent: the first valid result of a job wins, whatever its attempt;
//   duplicates and results of finished jobs are ignored.
// - An invalid result (error, non-finite fitness) re-issues the job to another worker when
//   there is one; after `max_invalid` invalid results the job has failed.
// - A worker gets at most slots + `prefetch` jobs at once, so that it never waits for the
//   evolver between two evaluations.
// - Fair retries: a job goes preferably to a worker that has not lost a lease of it, and a
//   worker that lost `pass_over_after` leases in a row (expired: lossy link, overloaded host)
//   gets no new job for `pass_over` while a worker that is not passed over is alive (the job
//   waits for that one); a valid result ends its run of losses. Among equals the worker with
//   the most free capacity wins, then the first name.
// - A worker that restarted under the same id (its evaluations_done count went down) has lost
//   its leases: they are re-issued at once, without waiting for `status_grace`.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace ahhs::evolver {

using FarmClock = std::chrono::steady_clock;

struct LeaseOptions {
  std::chrono::milliseconds job_deadline{120000};  // longest one evaluation may take
  std::chrono::milliseconds worker_silence{10000};
  std::chrono::milliseconds status_grace{3000};
  int prefetch = 1;
  int max_invalid = 5;
  int pass_over_after = 2;
  std::chrono::milliseconds pass_over{30000};
};

struct Dispatch {
  std::int64_t job = 0;
  int attempt = 0;
  std::string worker;
  FarmClock::time_point deadline;
};

struct Reissue {
  std::int64_t job = 0;
  std::string worker;  // who had it
  std::string reason;
  bool passed_over = false;  // this loss made `worker` passed over for a while
};

class LeaseTable {
 public:
  explicit LeaseTable(LeaseOptions options) : options_(options) {}

  void AddJob(std::int64_t job);

  // A status of `worker` heard at `now`: its slots, the jobs of this batch's run it lists, and
  // how many slots jobs of other runs occupy.
  // `evaluations_done` counts the worker's evaluations since it started (-1: unknown); a count
  // lower than the last one means the worker restarted.
  void OnWorkerStatus(const std::string& worker, int slots, const std::vector<std::int64_t>& jobs,
                      int busy_with_others, FarmClock::time_point now,
                      std::int64_t evaluations_done = -1);

  // Stops using `worker`: it gets no new jobs, and its leases end at the next Expire().
  void Forget(const std::string& worker) { workers_.erase(worker); }

  // Leases pending jobs (lowest job first) to the live workers with free capacity.
  std::vector<Dispatch> Schedule(FarmClock::time_point now);

  enum class Verdict { kAccepted, kIgnored, kReissued, kFailed };
  // A refusal of (job, attempt) by `worker` (it serves another run only): the job goes to
  // another worker without counting as an invalid answer (kReissued), or kIgnored when it is
  // not the current lease.
  Verdict OnRefusal(std::int64_t job, int attempt, const std::string& worker);
  // A result for (job, attempt) from `worker`; `valid` = status OK and finite fitness.
  Verdict OnResult(std::int64_t job, int attempt, const std::string& worker, bool valid,
                   FarmClock::time_point now);

  // Ends overdue leases (deadline, silent worker, missing from the worker's status).
  std::vector<Reissue> Expire(FarmClock::time_point now);

  bool AllDone() const { return done_ == jobs_.size(); }
  std::size_t done() const { return done_; }
  std::size_t size() const { return jobs_.size(); }
  bool Failed(std::int64_t job) const;
  int LiveWorkers(FarmClock::time_point now) const;
  int attempts(std::int64_t job) const;  // issues so far
  bool PassedOver(const std::string& worker, FarmClock::time_point now) const;

 private:
  struct Lease {
    std::string worker;
    int attempt = 0;
    FarmClock::time_point dispatched, deadline;
    std::string lost;  // why it ended early ("" until then)
  };
  struct Job {
    bool done = false;
    bool failed = false;
    int next_attempt = 0;
    int invalid = 0;
    std::optional<Lease> lease;
    std::set<std::string> excluded;  // workers that returned an invalid result for it
    std::set<std::string> lost_by;   // workers whose lease of it expired
  };
  struct Worker {
    int slots = 0;
    int busy_with_others = 0;
    int leased = 0;
    FarmClock::time_point last_heard;
    std::int64_t evaluations_done = -1;
    int losses = 0;  // leases lost in a row
    FarmClock::time_point passed_over_until{};
  };
  bool Alive(const Worker& w, FarmClock::time_point now) const {
    return now - w.last_heard <= options_.worker_silence;
  }
  void EndLease(Job& job);

  LeaseOptions options_;
  std::map<std::int64_t, Job> jobs_;
  std::map<std::string, Worker> workers_;
  std::size_t done_ = 0;
};

}  // namespace ahhs::evolver
