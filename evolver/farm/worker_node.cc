#include "evolver/farm/worker_node.h"

#include <ahhs/eval_request_t.hpp>
#include <iostream>

#include "bus/channels.h"
#include "evolver/farm/farm_codec.h"

namespace ahhs::evolver {

WorkerNode::WorkerNode(bus::Bus* bus, std::string id, std::string host, EvaluateFn evaluate,
                       std::chrono::milliseconds status_period)
    : bus_(bus),
      id_(std::move(id)),
      host_(std::move(host)),
      evaluate_(std::move(evaluate)),
      status_period_(status_period) {
  subscription_ = bus::SubscribeTyped<eval_request_t>(
      *bus_, bus::kEvalRequestChannel,
      [this](const std::string&, const eval_request_t& m) { OnRequest(m); }, &counters_.requests);
  PublishStatus();
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
  queue_.push_back(std::move(job));
  PublishStatus();
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
  s.free_slots = current_job_ < 0 && queue_.empty() ? 1 : 0;
  s.evaluations_done = counters_.evaluations;
  if (current_job_ >= 0) {
    s.jobs.push_back(current_job_);
    s.run = current_run_;
  }
  for (const auto& j : queue_) {
    // A status names one run; jobs of other runs are reported by count only via free_slots.
    if (s.run.empty()) s.run = j.run;
    if (j.run == s.run) s.jobs.push_back(j.job);
  }
  if (s.run.empty()) s.run = serve_run_;
  bus::PublishTyped(*bus_, bus::kWorkerStatusChannel, StatusMessage(s));
  last_status_ = std::chrono::steady_clock::now();
}

void WorkerNode::Poll(std::chrono::microseconds wait) {
  bus_->Handle(queue_.empty() ? wait : std::chrono::microseconds(0));
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
