#include "evolver/farm/worker_node.h"

#include <ahhs/eval_request_t.hpp>
#include <ahhs/genome_want_t.hpp>
#include <algorithm>
#include <iostream>

#include "bus/channels.h"
#include "evolver/farm/farm_codec.h"

namespace ahhs::evolver {

WorkerNode::WorkerNode(bus::Bus* bus, std::string id, std::string host, EvaluateFn evaluate,
                       std::chrono::milliseconds status_period,
                       std::chrono::milliseconds want_period)
    : bus_(bus),
      id_(std::move(id)),
      host_(std::move(host)),
      evaluate_(std::move(evaluate)),
      status_period_(status_period),
      want_period_(want_period) {
  request_subscription_ = bus::SubscribeTyped<eval_request_t>(
      *bus_, bus::kEvalRequestChannel,
      [this](const std::string&, const eval_request_t& m) { OnRequest(m); }, &counters_.requests);
  piece_subscription_ = bus::SubscribeTyped<genome_chunk_t>(
      *bus_, bus::kEvalGenomeChannel,
      [this](const std::string&, const genome_chunk_t& m) { OnPiece(m); }, &counters_.pieces);
  // The first status goes out with the first Poll, once ServeOnlyRun may have been called: one
  // sent from here said "any run" for a worker dedicated to one.
}

WorkerNode::~WorkerNode() = default;

void WorkerNode::OnRequest(const eval_request_t& msg) {
  if (msg.worker != id_) return;  // addressed to another worker
  FarmResult answer;
  answer.run = msg.run;
  answer.job = msg.job;
  answer.attempt = msg.attempt;
  answer.worker = id_;
  if (msg.protocol_version != kFarmProtocolVersion) {
    ++counters_.refused;
    answer.status = FarmResult::Status::kRefused;
    answer.message = "worker " + id_ + " speaks evaluation protocol version " +
                     std::to_string(kFarmProtocolVersion) + ", the request version " +
                     std::to_string(msg.protocol_version);
    std::cerr << "ahhs-worker: refused job " << msg.job << " of run " << msg.run << ": "
              << answer.message << '\n';
    SendResult(answer);
    return;
  }
  if (!serve_run_.empty() && !SameRun(serve_run_, msg.run)) {
    ++counters_.refused;
    answer.status = FarmResult::Status::kRefused;
    answer.message = "worker " + id_ + " serves run " + serve_run_ + " only";
    SendResult(answer);
    return;
  }
  // A run measured in a physics this build does not simulate: never an answer in another one.
  if (const std::string why = PhysicsRefusal(msg); !why.empty()) {
    ++counters_.refused;
    answer.status = FarmResult::Status::kRefused;
    answer.message = "worker " + id_ + ": " + why;
    std::cerr << "ahhs-worker: refused job " << msg.job << " of run " << msg.run << ": " << why
              << '\n';
    SendResult(answer);
    return;
  }
  if (!seen_.insert({msg.run, msg.job, msg.attempt}).second) return;  // a repeat
  FarmJob job;
  const std::string error = JobFromMessage(msg, &job);
  if (!error.empty()) {
    ++counters_.bad_requests;
    answer.status = FarmResult::Status::kError;
    answer.message = "bad request: " + error;
    SendResult(answer);
    return;
  }
  std::string why;
  switch (FindGenome(&job, &why)) {
    case Found::kYes:
      queue_.push_back(std::move(job));
      break;
    case Found::kNotYet:
      waiting_.push_back({std::move(job), {}});
      SendWant(&waiting_.back());
      break;
    case Found::kBad:
      SendError(job, "bad request: genome: " + why);
      return;
  }
  PublishStatus();
}

void WorkerNode::OnPiece(const genome_chunk_t& msg) {
  if (msg.protocol_version != kFarmProtocolVersion) return;
  GenomePiece piece;
  if (!PieceFromMessage(msg, &piece).empty()) {
    ++counters_.pieces.dropped;
    return;
  }
  cache_.Add(piece);
}

// A genome whose assembled pieces are not the genome named is asked for again (a piece was
// damaged or came from a confused sender); the second time, the request itself is bad.
WorkerNode::Found WorkerNode::FindGenome(FarmJob* job, std::string* error) {
  const std::vector<std::uint8_t>* bytes = cache_.Find(job->genome_hash);
  if (bytes == nullptr) return Found::kNotYet;
  *error = DecodeGenome(*bytes, job->genome_hash, &job->genome);
  if (error->empty()) return Found::kYes;
  ++counters_.damaged_genomes;
  cache_.Drop(job->genome_hash);
  return ++damaged_[job->genome_hash] >= 2 ? Found::kBad : Found::kNotYet;
}

void WorkerNode::SendWant(Waiting* w) {
  GenomeWant want;
  want.run = w->job.run;
  want.worker = id_;
  want.genome_hash = w->job.genome_hash;
  want.missing = cache_.Missing(w->job.genome_hash, w->job.genome_chunks);
  bus::PublishTyped(*bus_, bus::kEvalWantChannel, WantMessage(want));
  w->last_want = std::chrono::steady_clock::now();
  ++counters_.wants;
}

void WorkerNode::ServeWaiting() {
  bool changed = false;
  const auto now = std::chrono::steady_clock::now();
  const std::int64_t now_utime = bus::NowUtime();
  for (auto it = waiting_.begin(); it != waiting_.end();) {
    std::string why;
    const Found found = FindGenome(&it->job, &why);
    if (found == Found::kYes) {
      queue_.push_back(std::move(it->job));
    } else if (found == Found::kBad) {
      SendError(it->job, "bad request: genome: " + why);
    } else if (now_utime > it->job.deadline_utime) {
      ++counters_.expired_waits;  // the evolver has re-issued it by now
      std::cerr << "ahhs-worker: dropped job " << it->job.job << " of run " << it->job.run
                << ": its genome was still incomplete at the deadline\n";
    } else {
      if (now - it->last_want >= want_period_) SendWant(&*it);
      ++it;
      continue;
    }
    it = waiting_.erase(it);
    changed = true;
  }
  if (changed) PublishStatus();
}

void WorkerNode::SendError(const FarmJob& job, const std::string& message) {
  ++counters_.bad_requests;
  FarmResult answer;
  answer.run = job.run;
  answer.job = job.job;
  answer.attempt = job.attempt;
  answer.worker = id_;
  answer.status = FarmResult::Status::kError;
  answer.message = message;
  SendResult(answer);
}

// A result that is not sent is counted (and logged by the bus); the evolver then gets an error
// result for the job instead of waiting for its lease to run out.
void WorkerNode::SendResult(const FarmResult& result) {
  if (bus::PublishTyped(*bus_, bus::kEvalResultChannel, ResultMessage(result))) return;
  ++counters_.unsent_results;
  FarmResult error = result;
  error.status = FarmResult::Status::kError;
  error.fitness = 0;
  error.message = "worker " + id_ + " could not send the result of job " +
                  std::to_string(result.job) + " (see its log)";
  bus::PublishTyped(*bus_, bus::kEvalResultChannel, ResultMessage(error));
}

void WorkerNode::PublishStatus() {
  WorkerStatus s;
  s.worker = id_;
  s.host = host_;
  s.slots = 1;
  s.free_slots = current_job_ < 0 && queue_.empty() && waiting_.empty() ? 1 : 0;
  s.evaluations_done = counters_.evaluations;
  if (current_job_ >= 0) {
    s.jobs.push_back(current_job_);
    s.run = current_run_;
  }
  // A status names one run; jobs of other runs are reported by count only via free_slots.
  auto list = [&s](const FarmJob& j) {
    if (s.run.empty()) s.run = j.run;
    if (j.run == s.run) s.jobs.push_back(j.job);
  };
  for (const auto& j : queue_) list(j);
  for (const auto& w : waiting_) list(w.job);
  if (s.run.empty()) s.run = serve_run_;
  bus::PublishTyped(*bus_, bus::kWorkerStatusChannel, StatusMessage(s));
  last_status_ = std::chrono::steady_clock::now();
}

void WorkerNode::Poll(std::chrono::microseconds wait) {
  const std::chrono::microseconds idle =
      waiting_.empty() ? wait : std::min<std::chrono::microseconds>(wait, want_period_ / 5);
  bus_->Handle(queue_.empty() ? idle : std::chrono::microseconds(0));
  if (!waiting_.empty()) ServeWaiting();
  if (!queue_.empty()) {
    FarmJob job = std::move(queue_.front());
    queue_.pop_front();
    current_job_ = job.job;
    current_run_ = job.run;
    const auto start = std::chrono::steady_clock::now();
    FarmResult outcome;
    try {
      outcome = evaluate_(job);
    } catch (const std::exception& e) {
      outcome.status = FarmResult::Status::kError;
      outcome.message = e.what();
    }
    outcome.protocol_version = kFarmProtocolVersion;
    outcome.run = job.run;
    outcome.job = job.job;
    outcome.attempt = job.attempt;
    outcome.worker = id_;
    outcome.wall_time =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ++counters_.evaluations;
    current_job_ = -1;
    current_run_.clear();
    SendResult(outcome);
    PublishStatus();
    return;
  }
  if (std::chrono::steady_clock::now() - last_status_ >= status_period_) PublishStatus();
}

void WorkerNode::Serve(const std::function<bool()>& stop) {
  while (!stop()) Poll(std::chrono::milliseconds(100));
}

}  // namespace ahhs::evolver
