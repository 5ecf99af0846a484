#include "evolver/farm/farm_evaluator.h"

#include <ahhs/eval_request_t.hpp>
#include <ahhs/eval_result_t.hpp>
#include <ahhs/worker_status_t.hpp>
#include <algorithm>
#include <cmath>

#include "bus/channels.h"
#include "evolver/farm/farm_codec.h"

namespace ahhs::evolver {

FarmEvaluator::FarmEvaluator(bus::Bus* bus, FarmOptions options, Hooks hooks)
    : bus_(bus), options_(std::move(options)), hooks_(std::move(hooks)) {
  subscriptions_.push_back(bus::SubscribeTyped<worker_status_t>(
      *bus_, bus::kWorkerStatusChannel,
      [this](const std::string&, const worker_status_t& m) { OnStatus(m); }, &counters_.statuses));
  subscriptions_.push_back(bus::SubscribeTyped<eval_result_t>(
      *bus_, bus::kEvalResultChannel,
      [this](const std::string&, const eval_result_t& m) { OnResult(m); }, &counters_.results));
  subscriptions_.push_back(bus::SubscribeTyped<genome_want_t>(
      *bus_, bus::kEvalWantChannel,
      [this](const std::string&, const genome_want_t& m) { OnWant(m); }, &counters_.wants_decoded));
}

FarmEvaluator::~FarmEvaluator() = default;

void FarmEvaluator::OnStatus(const worker_status_t& msg) {
  if (msg.protocol_version != kFarmProtocolVersion) {
    if (refused_.insert(msg.worker).second)
      hooks_.report("refused worker " + msg.worker + " on " + msg.host +
                    ": it speaks evaluation protocol version " +
                    std::to_string(msg.protocol_version) + ", this evolver version " +
                    std::to_string(kFarmProtocolVersion));
    return;
  }
  if (msg.worker.empty()) return;
  known_.emplace(msg.worker, msg.host);
  seen_[msg.worker] = {StatusFromMessage(msg), FarmClock::now()};
}

void FarmEvaluator::OnResult(const eval_result_t& msg) {
  if (msg.run != options_.run) return;  // another run's, or a stale session's
  inbox_.push_back(OutcomeFromMessage(msg));
}

void FarmEvaluator::OnWant(const genome_want_t& msg) {
  if (msg.run != options_.run || msg.protocol_version != kFarmProtocolVersion) return;
  ++counters_.wants;
  wants_.push_back(WantFromMessage(msg));
}

bool FarmEvaluator::Usable(const std::string& name, const WorkerSeen& w,
                           FarmClock::time_point now) const {
  return now - w.heard <= options_.lease.worker_silence && !quarantined_.count(name) &&
         !declined_.count(name);
}

int FarmEvaluator::ReadyWorkers(FarmClock::time_point now) const {
  int ready = 0;
  for (const auto& [name, w] : seen_)
    ready += Usable(name, w, now) && (w.status.run.empty() || SameRun(w.status.run, options_.run));
  return ready;
}

int FarmEvaluator::WaitForWorkers(int count, std::chrono::milliseconds timeout) {
  const auto end = FarmClock::now() + timeout;
  while (ReadyWorkers(FarmClock::now()) < count && FarmClock::now() < end) {
    hooks_.poll();
    if (hooks_.interrupted()) throw FarmInterrupted();
    bus_->Handle(std::chrono::milliseconds(20));
  }
  return ReadyWorkers(FarmClock::now());
}

// One generation's jobs on their way through the farm.
struct FarmEvaluator::Batch {
  Batch(const std::vector<EvaluationJob>& j, const LeaseOptions& lease) : jobs(j), table(lease) {}
  const std::vector<EvaluationJob>& jobs;
  LeaseTable table;
  std::map<std::int64_t, std::size_t> slot_of;  // job id -> position in `jobs`
  std::vector<Evaluation> results;
  FarmClock::time_point last_worker_seen = FarmClock::now();
  // The genomes of this batch, by hash, once a job needed them: their pieces and when each
  // piece last went out.
  struct Sent {
    std::vector<GenomePiece> pieces;
    std::vector<FarmClock::time_point> at;
  };
  std::map<std::uint64_t, Sent> genomes;
  std::vector<std::uint64_t> hash_of;  // per job slot, once sent
};

std::vector<Evaluation> FarmEvaluator::Evaluate(const std::vector<EvaluationJob>& jobs) {
  Batch batch(jobs, options_.lease);
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    const std::int64_t id =
        (static_cast<std::int64_t>(jobs[k].generation) * options_.population + jobs[k].index) *
            options_.trials +
        jobs[k].trial;
    batch.slot_of[id] = k;
    batch.table.AddJob(id);
  }
  batch.results.resize(jobs.size());
  batch.hash_of.resize(jobs.size());
  wants_.clear();
  std::size_t last_done = 0;
  auto last_turn = FarmClock::now();
  while (!batch.table.AllDone()) {
    hooks_.poll();
    if (hooks_.interrupted()) throw FarmInterrupted();
    const auto now = FarmClock::now();
    // The evolver did not run for a while (SIGSTOP, a suspended machine, a starved CPU): its
    // local workers were stopped with it, so the time without workers counts from now, not from
    // before the pause (a 60 s pause used to end the run with "no evaluation worker").
    if (now - last_turn > std::chrono::seconds(1)) batch.last_worker_seen = now;
    last_turn = now;
    FeedStatuses(&batch, now);
    for (const auto& r : batch.table.Expire(now)) {
      ++counters_.reissued;
      hooks_.report("job " + std::to_string(r.job) + " re-issued (" + r.reason + ", worker " +
                    r.worker + ")");
      if (r.passed_over)
        hooks_.report(
            "worker " + r.worker + " lost " + std::to_string(options_.lease.pass_over_after) +
            " leases in a row: passed over for " +
            std::to_string(options_.lease.pass_over.count() / 1000) + " s while others have room");
    }
    Dispatch(&batch, now);
    CheckWorkers(&batch, now);
    bus_->Handle(std::chrono::milliseconds(20));
    TakeResults(&batch, FarmClock::now());
    AnswerWants(&batch, FarmClock::now());
    if (batch.table.done() != last_done) {
      last_done = batch.table.done();
      hooks_.progress(last_done, jobs.size());
    }
  }
  return std::move(batch.results);
}

void FarmEvaluator::FeedStatuses(Batch* batch, FarmClock::time_point now) {
  for (const auto& [name, w] : seen_) {
    if (!Usable(name, w, now)) continue;
    std::vector<std::int64_t> ours;
    int others = 0;
    if (SameRun(w.status.run, options_.run))
      ours = w.status.jobs;
    else if (!w.status.run.empty())  // busy with, or dedicated to, another run
      others = std::max(static_cast<int>(w.status.jobs.size()), w.status.slots);
    batch->table.OnWorkerStatus(name, w.status.slots, ours, others, w.heard,
                                w.status.evaluations_done);
  }
}

void FarmEvaluator::Dispatch(Batch* batch, FarmClock::time_point now) {
  for (const auto& d : batch->table.Schedule(now)) {
    const EvaluationJob& j = batch->jobs[batch->slot_of.at(d.job)];
    FarmJob job;
    job.run = options_.run;
    job.job = d.job;
    job.attempt = d.attempt;
    job.worker = d.worker;
    job.config = options_.config;
    job.seed = j.seed;
    job.deadline_utime =
        bus::NowUtime() +
        std::chrono::duration_cast<std::chrono::microseconds>(options_.lease.job_deadline).count();
    SendGenome(batch, batch->slot_of.at(d.job), &job);
    bus::PublishTyped(*bus_, bus::kEvalRequestChannel, RequestMessage(job));
    ++counters_.dispatched;
  }
}

void FarmEvaluator::SendGenome(Batch* batch, std::size_t slot, FarmJob* job) {
  std::uint64_t& hash = batch->hash_of[slot];
  if (hash == 0 || batch->genomes.count(hash) == 0) {
    EncodedGenome encoded = EncodeGenome(*batch->jobs[slot].genome);
    hash = encoded.hash;
    auto [it, first] = batch->genomes.try_emplace(hash);
    if (first) {  // a genome several jobs share goes out once
      it->second.pieces = SplitGenome(hash, encoded.bytes);
      it->second.at.assign(it->second.pieces.size(), FarmClock::now());
      for (const GenomePiece& p : it->second.pieces)
        bus::PublishTyped(*bus_, bus::kEvalGenomeChannel, PieceMessage(p));
      counters_.pieces_sent += static_cast<std::int64_t>(it->second.pieces.size());
      ++counters_.genomes_sent;
    }
  }
  const Batch::Sent& sent = batch->genomes.at(hash);
  job->genome_hash = hash;
  job->genome_bytes = sent.pieces.front().genome_bytes;
  job->genome_chunks = static_cast<int>(sent.pieces.size());
}

void FarmEvaluator::AnswerWants(Batch* batch, FarmClock::time_point now) {
  for (const GenomeWant& w : wants_) {
    auto it = batch->genomes.find(w.genome_hash);
    if (it == batch->genomes.end()) continue;  // not a genome of this generation
    Batch::Sent& sent = it->second;
    for (int index : w.missing) {
      if (index < 0 || static_cast<std::size_t>(index) >= sent.pieces.size()) continue;
      const auto k = static_cast<std::size_t>(index);
      if (now - sent.at[k] < options_.piece_resend) continue;  // several workers asked
      bus::PublishTyped(*bus_, bus::kEvalGenomeChannel, PieceMessage(sent.pieces[k]));
      sent.at[k] = now;
      ++counters_.pieces_sent;
      ++counters_.pieces_resent;
    }
  }
  wants_.clear();
}

void FarmEvaluator::CheckWorkers(Batch* batch, FarmClock::time_point now) {
  if (batch->table.LiveWorkers(now) > 0) {
    batch->last_worker_seen = now;
    return;
  }
  const bool starved = hooks_.workers_starved();
  if (now - batch->last_worker_seen <= options_.no_worker_timeout) return;
  if (starved) {
    // Alive, but the machine gives them no CPU: waited for, as the evolver's own pause is.
    hooks_.report("no worker has answered for " +
                  std::to_string(options_.no_worker_timeout.count() / 1000) +
                  " s, but the local workers are waiting for a CPU (a busy machine): waiting on");
    batch->last_worker_seen = now;
    return;
  }
  std::string why = "no evaluation worker has answered for " +
                    std::to_string(options_.no_worker_timeout.count() / 1000) +
                    " s (start one with ahhs-worker, or give ahhs-evolve --workers N)";
  if (!quarantined_.empty()) {
    why += "; workers given no more jobs after invalid results:";
    for (const auto& q : quarantined_) why += " " + q;
  }
  throw FarmError(why);
}

void FarmEvaluator::TakeResults(Batch* batch, FarmClock::time_point heard) {
  for (const FarmResult& o : inbox_) {
    auto slot = batch->slot_of.find(o.job);
    if (slot == batch->slot_of.end()) {
      ++counters_.duplicates;
      continue;
    }
    if (o.status == FarmResult::Status::kRefused) {
      // A worker dedicated to another run: not the job's fault, and no more jobs for it.
      if (batch->table.OnRefusal(o.job, o.attempt, o.worker) == LeaseTable::Verdict::kReissued &&
          declined_.insert(o.worker).second) {
        batch->table.Forget(o.worker);
        hooks_.report("worker " + o.worker + " refused job " + std::to_string(o.job) + " (" +
                      o.message + "); it gets no jobs from this run");
      }
      continue;
    }
    const bool valid = o.status == FarmResult::Status::kOk && std::isfinite(o.fitness) &&
                       std::isfinite(o.cost) &&
                       std::all_of(o.descriptor.begin(), o.descriptor.end(),
                                   [](double x) { return std::isfinite(x); });
    const auto verdict = batch->table.OnResult(o.job, o.attempt, o.worker, valid, heard);
    if (verdict == LeaseTable::Verdict::kAccepted) {
      Evaluation& e = batch->results[slot->second];
      e.fitness = o.fitness;
      e.cost = o.cost;
      e.descriptor = o.descriptor;
      e.worker = o.worker;
      e.attempt = o.attempt;
      e.wall_time = o.wall_time;
      e.message = o.message;
      counters_.states_missed += o.states_missed;
    } else if (verdict == LeaseTable::Verdict::kIgnored) {
      ++counters_.duplicates;
    } else {
      OnInvalid(batch, o, verdict == LeaseTable::Verdict::kFailed);
    }
  }
  inbox_.clear();
}

void FarmEvaluator::OnInvalid(Batch* batch, const FarmResult& o, bool failed) {
  ++counters_.invalid_results;
  const std::string what =
      o.status == FarmResult::Status::kOk ? "a non-finite fitness" : "an error: " + o.message;
  hooks_.report("worker " + o.worker + " returned " + what + " for job " + std::to_string(o.job) +
                (failed ? "; giving up" : "; re-issued"));
  if (++invalid_by_worker_[o.worker] == options_.quarantine_after &&
      quarantined_.insert(o.worker).second) {
    batch->table.Forget(o.worker);
    hooks_.report("worker " + o.worker + " returned " + std::to_string(options_.quarantine_after) +
                  " invalid results; it gets no more jobs from this run");
  }
  if (failed)
    throw FarmError("job " + std::to_string(o.job) + " failed " +
                    std::to_string(options_.lease.max_invalid) + " times; last answer: " + what);
}

}  // namespace ahhs::evolver
