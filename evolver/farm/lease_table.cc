#include "evolver/farm/lease_table.h"

#include <algorithm>
#include <tuple>

namespace ahhs::evolver {

void LeaseTable::AddJob(std::int64_t job) { jobs_.emplace(job, Job{}); }

void LeaseTable::OnWorkerStatus(const std::string& worker, int slots,
                                const std::vector<std::int64_t>& listed, int busy_with_others,
                                FarmClock::time_point now, std::int64_t evaluations_done) {
  Worker& w = workers_[worker];
  w.slots = std::max(0, slots);
  w.busy_with_others = std::max(0, busy_with_others);
  w.last_heard = now;
  const bool restarted = evaluations_done >= 0 && evaluations_done < w.evaluations_done;
  if (evaluations_done >= 0) w.evaluations_done = evaluations_done;
  if (restarted) {
    // A new process under the old id: what the old one held is gone.
    for (auto& [id, job] : jobs_)
      if (!job.done && job.lease && job.lease->worker == worker) {
        job.lease->deadline = now;
        job.lease->lost = "worker restarted";
      }
    return;
  }
  // A lease the worker should have seen by now but does not list was lost on the way (or its
  // result was): issue it again.
  for (auto& [id, job] : jobs_) {
    if (job.done || !job.lease || job.lease->worker != worker) continue;
    if (now - job.lease->dispatched < options_.status_grace) continue;
    if (std::find(listed.begin(), listed.end(), id) == listed.end())
      job.lease->deadline = now;  // Expire() re-issues it with this reason
  }
}

std::vector<Dispatch> LeaseTable::Schedule(FarmClock::time_point now) {
  std::vector<Dispatch> out;
  for (auto& [id, job] : jobs_) {
    if (job.done || job.failed || job.lease) continue;
    // The live worker with room ranked by: did not fail this job, did not lose a lease of it,
    // is not passed over, most free capacity (then the first name).
    Worker* best = nullptr;
    const std::string* best_name = nullptr;
    std::tuple<bool, bool, bool, int> best_rank{};
    for (auto& [name, w] : workers_) {
      if (!Alive(w, now)) continue;
      const int free = w.slots + options_.prefetch - w.busy_with_others - w.leased;
      if (free <= 0 || w.slots == 0) continue;
      const std::tuple<bool, bool, bool, int> rank{job.excluded.count(name) > 0,
                                                   job.lost_by.count(name) > 0,
                                                   now < w.passed_over_until, -free};
      if (!best || rank < best_rank) {
        best = &w;
        best_name = &name;
        best_rank = rank;
      }
    }
    const bool best_excluded = best != nullptr && std::get<0>(best_rank);
    if (!best) break;  // every live worker is full
    if (!best_excluded && std::get<2>(best_rank)) {
      // Only passed-over workers have room: wait for one that is not, while one is alive.
      bool other_exists = false;
      for (auto& [name, w] : workers_)
        if (Alive(w, now) && w.slots > 0 && now >= w.passed_over_until) other_exists = true;
      if (other_exists) continue;
    }
    if (best_excluded) {
      // Only workers that failed this job have room: wait for another one while one exists.
      bool other_exists = false;
      for (auto& [name, w] : workers_)
        if (Alive(w, now) && w.slots > 0 && job.excluded.count(name) == 0) other_exists = true;
      if (other_exists) continue;
    }
    Lease lease{*best_name, job.next_attempt++, now, now + options_.job_deadline, ""};
    ++best->leased;
    job.lease = lease;
    out.push_back({id, lease.attempt, lease.worker, lease.deadline});
  }
  return out;
}

void LeaseTable::EndLease(Job& job) {
  if (!job.lease) return;
  auto it = workers_.find(job.lease->worker);
  if (it != workers_.end() && it->second.leased > 0) --it->second.leased;
  job.lease.reset();
}

LeaseTable::Verdict LeaseTable::OnResult(std::int64_t id, int attempt, const std::string& worker,
                                         bool valid, FarmClock::time_point now) {
  auto it = jobs_.find(id);
  if (it == jobs_.end() || it->second.done || attempt < 0 || attempt >= it->second.next_attempt)
    return Verdict::kIgnored;
  Job& job = it->second;
  auto w = workers_.find(worker);
  if (w != workers_.end()) w->second.last_heard = now;
  if (valid) {
    if (w != workers_.end()) w->second.losses = 0;
    EndLease(job);
    job.done = true;
    ++done_;
    return Verdict::kAccepted;
  }
  // An invalid answer counts once per (worker, attempt): only the current lease's.
  if (!job.lease || job.lease->worker != worker || job.lease->attempt != attempt)
    return Verdict::kIgnored;
  EndLease(job);
  job.excluded.insert(worker);
  if (++job.invalid >= options_.max_invalid) {
    job.failed = true;
    return Verdict::kFailed;
  }
  return Verdict::kReissued;
}

LeaseTable::Verdict LeaseTable::OnRefusal(std::int64_t id, int attempt, const std::string& worker) {
  auto it = jobs_.find(id);
  if (it == jobs_.end() || it->second.done) return Verdict::kIgnored;
  Job& job = it->second;
  if (!job.lease || job.lease->worker != worker || job.lease->attempt != attempt)
    return Verdict::kIgnored;
  EndLease(job);
  job.excluded.insert(worker);
  return Verdict::kReissued;
}

std::vector<Reissue> LeaseTable::Expire(FarmClock::time_point now) {
  std::vector<Reissue> out;
  for (auto& [id, job] : jobs_) {
    if (job.done || !job.lease) continue;
    const auto w = workers_.find(job.lease->worker);
    std::string reason;
    if (w == workers_.end() || !Alive(w->second, now))
      reason = "worker silent";
    else if (now >= job.lease->deadline && job.lease->lost.empty())
      reason = "lease expired or job lost";
    else if (!job.lease->lost.empty())
      reason = job.lease->lost;
    if (reason.empty()) continue;
    Reissue r{id, job.lease->worker, reason, false};
    if (w != workers_.end()) {
      Worker& lost = w->second;
      job.lost_by.insert(w->first);
      if (++lost.losses >= options_.pass_over_after && now >= lost.passed_over_until) {
        lost.passed_over_until = now + options_.pass_over;
        r.passed_over = true;
      }
    }
    out.push_back(r);
    EndLease(job);
  }
  return out;
}

bool LeaseTable::PassedOver(const std::string& worker, FarmClock::time_point now) const {
  const auto it = workers_.find(worker);
  return it != workers_.end() && now < it->second.passed_over_until;
}

bool LeaseTable::Failed(std::int64_t id) const {
  auto it = jobs_.find(id);
  return it != jobs_.end() && it->second.failed;
}

int LeaseTable::LiveWorkers(FarmClock::time_point now) const {
  int n = 0;
  for (const auto& [name, w] : workers_)
    if (Alive(w, now) && w.slots > 0) ++n;
  return n;
}

int LeaseTable::attempts(std::int64_t id) const {
  auto it = jobs_.find(id);
  return it == jobs_.end() ? 0 : it->second.next_attempt;
}

}  // namespace ahhs::evolver
