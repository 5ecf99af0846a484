// The farm's lease bookkeeping against a fake clock.
#include "evolver/farm/lease_table.h"

#include <catch2/catch.hpp>

using namespace ahhs::evolver;
using std::chrono::milliseconds;

namespace {

LeaseOptions FastLeases() {
  LeaseOptions o;
  o.job_deadline = milliseconds(1000);
  o.worker_silence = milliseconds(500);
  o.status_grace = milliseconds(200);
  o.prefetch = 1;
  o.max_invalid = 3;
  return o;
}

const FarmClock::time_point t0{};

}  // namespace

TEST_CASE("jobs go to live workers up to slots + prefetch, lowest job first") {
  LeaseTable t(FastLeases());
  for (int j = 0; j < 10; ++j) t.AddJob(j);
  CHECK(t.Schedule(t0).empty());  // nobody to give them to
  t.OnWorkerStatus("a", 1, {}, 0, t0);
  t.OnWorkerStatus("b", 2, {}, 0, t0);
  const auto d = t.Schedule(t0);
  REQUIRE(d.size() == 5);  // a: 1 + 1, b: 2 + 1
  for (std::size_t k = 0; k < d.size(); ++k) {
    CHECK(d[k].job == static_cast<std::int64_t>(k));
    CHECK(d[k].attempt == 0);
  }
  CHECK(std::count_if(d.begin(), d.end(), [](const Dispatch& x) { return x.worker == "b"; }) == 3);
  CHECK(t.Schedule(t0).empty());  // all full
  // A worker busy with another run's jobs has less room.
  LeaseTable u(FastLeases());
  u.AddJob(0);
  u.AddJob(1);
  u.OnWorkerStatus("c", 1, {}, 2, t0);
  CHECK(u.Schedule(t0).empty());
}

TEST_CASE("a result frees the slot, duplicates and unknown jobs are ignored") {
  LeaseTable t(FastLeases());
  t.AddJob(0);
  t.AddJob(1);
  t.AddJob(2);
  t.OnWorkerStatus("a", 1, {}, 0, t0);
  REQUIRE(t.Schedule(t0).size() == 2);
  CHECK(t.OnResult(0, 0, "a", true, t0) == LeaseTable::Verdict::kAccepted);
  CHECK(t.OnResult(0, 0, "a", true, t0) == LeaseTable::Verdict::kIgnored);
  CHECK(t.OnResult(7, 0, "a", true, t0) == LeaseTable::Verdict::kIgnored);
  CHECK(t.OnResult(2, 5, "a", true, t0) == LeaseTable::Verdict::kIgnored);  // never issued
  const auto d = t.Schedule(t0);
  REQUIRE(d.size() == 1);
  CHECK(d[0].job == 2);
  CHECK(t.done() == 1);
}

TEST_CASE("an expired lease is re-issued with the next attempt, the first valid result wins") {
  LeaseTable t(FastLeases());
  t.AddJob(0);
  t.OnWorkerStatus("a", 1, {}, 0, t0);
  REQUIRE(t.Schedule(t0).size() == 1);
  // The worker keeps listing the job (it is slow), so only the deadline ends the lease.
  t.OnWorkerStatus("a", 1, {0}, 0, t0 + milliseconds(900));
  CHECK(t.Expire(t0 + milliseconds(900)).empty());
  t.OnWorkerStatus("a", 1, {0}, 0, t0 + milliseconds(1000));
  const auto r = t.Expire(t0 + milliseconds(1000));
  REQUIRE(r.size() == 1);
  CHECK(r[0].worker == "a");
  t.OnWorkerStatus("b", 1, {}, 0, t0 + milliseconds(1000));
  const auto d = t.Schedule(t0 + milliseconds(1000));
  REQUIRE(d.size() == 1);
  CHECK(d[0].attempt == 1);
  // The slow first attempt's result arrives first: it is valid, so it wins.
  CHECK(t.OnResult(0, 0, "a", true, t0 + milliseconds(1100)) == LeaseTable::Verdict::kAccepted);
  CHECK(t.OnResult(0, 1, d[0].worker, true, t0 + milliseconds(1200)) ==
        LeaseTable::Verdict::kIgnored);
  CHECK(t.AllDone());
}

TEST_CASE("a silent worker's jobs are re-issued") {
  LeaseTable t(FastLeases());
  t.AddJob(0);
  t.AddJob(1);
  t.OnWorkerStatus("a", 1, {}, 0, t0);
  REQUIRE(t.Schedule(t0).size() == 2);
  CHECK(t.Expire(t0 + milliseconds(400)).empty());
  CHECK(t.Expire(t0 + milliseconds(600)).size() == 2);
  CHECK(t.LiveWorkers(t0 + milliseconds(600)) == 0);
  t.OnWorkerStatus("b", 1, {}, 0, t0 + milliseconds(600));
  const auto d = t.Schedule(t0 + milliseconds(600));
  REQUIRE(d.size() == 2);
  CHECK(d[0].worker == "b");
  CHECK(d[0].attempt == 1);
}

TEST_CASE("a job missing from the worker's status after the grace time was lost") {
  LeaseTable t(FastLeases());
  t.AddJob(0);
  t.OnWorkerStatus("a", 1, {}, 0, t0);
  REQUIRE(t.Schedule(t0).size() == 1);
  // A status right after the dispatch may predate the request: no verdict yet.
  t.OnWorkerStatus("a", 1, {}, 0, t0 + milliseconds(100));
  CHECK(t.Expire(t0 + milliseconds(100)).empty());
  t.OnWorkerStatus("a", 1, {}, 0, t0 + milliseconds(300));
  CHECK(t.Expire(t0 + milliseconds(300)).size() == 1);
  CHECK(t.Schedule(t0 + milliseconds(300)).at(0).attempt == 1);
}

TEST_CASE("an invalid result sends the job elsewhere, too many fail it") {
  LeaseTable t(FastLeases());
  t.AddJob(0);
  t.OnWorkerStatus("bad", 1, {}, 0, t0);
  t.OnWorkerStatus("good", 1, {}, 0, t0);
  auto d = t.Schedule(t0);
  REQUIRE(d.size() == 1);
  const std::string first = d[0].worker;
  CHECK(t.OnResult(0, 0, first, false, t0) == LeaseTable::Verdict::kReissued);
  d = t.Schedule(t0);
  REQUIRE(d.size() == 1);
  CHECK(d[0].worker != first);
  CHECK(d[0].attempt == 1);
  // An invalid answer to an attempt that is no longer leased does not count twice.
  CHECK(t.OnResult(0, 0, first, false, t0) == LeaseTable::Verdict::kIgnored);
  CHECK(t.OnResult(0, 1, d[0].worker, false, t0) == LeaseTable::Verdict::kReissued);
  // Both workers failed it: it may go back to either.
  d = t.Schedule(t0);
  REQUIRE(d.size() == 1);
  CHECK(t.OnResult(0, 2, d[0].worker, false, t0) == LeaseTable::Verdict::kFailed);
  CHECK(t.Failed(0));
  CHECK(t.Schedule(t0).empty());
}

TEST_CASE("a refusal sends the job elsewhere and never fails it") {
  // Workers dedicated to another run refuse; however many refuse, the job is not failed
  // (ahhs-evolve failed a run when 5 refusals hit one job, 1 in 40 concurrent runs).
  LeaseTable t(FastLeases());
  t.AddJob(0);
  for (const char* w : {"other-a", "other-b", "other-c", "other-d"})
    t.OnWorkerStatus(w, 1, {}, 0, t0);
  for (int k = 0; k < 4; ++k) {
    const auto d = t.Schedule(t0);
    REQUIRE(d.size() == 1);
    CHECK(t.OnRefusal(0, d[0].attempt, d[0].worker) == LeaseTable::Verdict::kReissued);
    CHECK(t.OnRefusal(0, d[0].attempt, d[0].worker) == LeaseTable::Verdict::kIgnored);
    t.Forget(d[0].worker);
  }
  CHECK_FALSE(t.Failed(0));
  t.OnWorkerStatus("ours", 1, {}, 0, t0);
  const auto d = t.Schedule(t0);
  REQUIRE(d.size() == 1);
  CHECK(d[0].worker == "ours");
  CHECK(t.OnResult(0, d[0].attempt, "ours", true, t0) == LeaseTable::Verdict::kAccepted);
}

TEST_CASE("a job whose lease expired goes to another worker, even one that sorts later") {
  LeaseTable t(FastLeases());
  t.AddJob(0);
  t.OnWorkerStatus("a-lossy", 1, {}, 0, t0);
  t.OnWorkerStatus("b-clean", 1, {}, 0, t0);
  auto d = t.Schedule(t0);
  REQUIRE(d.size() == 1);
  CHECK(d[0].worker == "a-lossy");  // ties go to the first name
  const auto t1 = t0 + milliseconds(1001);
  t.OnWorkerStatus("a-lossy", 1, {0}, 0, t1 - milliseconds(1));  // alive, but no result came
  t.OnWorkerStatus("b-clean", 1, {}, 0, t1 - milliseconds(1));
  REQUIRE(t.Expire(t1).size() == 1);
  d = t.Schedule(t1);
  REQUIRE(d.size() == 1);
  CHECK(d[0].worker == "b-clean");
  CHECK(d[0].attempt == 1);
}

TEST_CASE("a worker that loses leases in a row is passed over for a while, not for ever") {
  auto o = FastLeases();
  o.pass_over_after = 2;
  o.pass_over = milliseconds(5000);
  LeaseTable t(o);
  for (int j = 0; j < 6; ++j) t.AddJob(j);
  auto now = t0;
  auto heard = [&](std::vector<std::int64_t> a_jobs) {
    t.OnWorkerStatus("a", 1, a_jobs, 0, now);
    t.OnWorkerStatus("b", 1, {}, 0, now);
  };
  heard({});
  // Jobs 0 and 1 go to a (first name, prefetch 1); b takes 2 and 3.
  auto d = t.Schedule(now);
  REQUIRE(d.size() == 4);
  for (const auto& x : d)
    if (x.worker == "b")
      CHECK(t.OnResult(x.job, x.attempt, "b", true, now) == LeaseTable::Verdict::kAccepted);
  now += milliseconds(1001);
  heard({0, 1});
  const auto lost = t.Expire(now);  // a lost both of its leases
  REQUIRE(lost.size() == 2);
  CHECK_FALSE(lost[0].passed_over);
  CHECK(lost[1].passed_over);
  CHECK(t.PassedOver("a", now));
  // Jobs 0, 1, 4, 5: b (one slot + prefetch) takes two; the others wait for b, not for a.
  d = t.Schedule(now);
  REQUIRE(d.size() == 2);
  CHECK(d[0].worker == "b");
  CHECK(d[1].worker == "b");
  CHECK(t.OnResult(d[0].job, d[0].attempt, "b", true, now) == LeaseTable::Verdict::kAccepted);
  d = t.Schedule(now);
  REQUIRE(d.size() == 1);
  CHECK(d[0].worker == "b");
  // After the pass-over time a gets jobs again; a valid result clears its losses.
  now += milliseconds(5001);
  heard({});
  CHECK_FALSE(t.PassedOver("a", now));
  d = t.Schedule(now);
  REQUIRE(d.size() == 1);
  CHECK(d[0].worker == "a");
  CHECK(t.OnResult(d[0].job, d[0].attempt, "a", true, now) == LeaseTable::Verdict::kAccepted);
}

TEST_CASE("when every live worker is passed over, they still get jobs") {
  auto o = FastLeases();
  o.pass_over_after = 1;
  LeaseTable t(o);
  t.AddJob(0);
  t.OnWorkerStatus("a", 1, {}, 0, t0);
  REQUIRE(t.Schedule(t0).size() == 1);
  const auto t1 = t0 + milliseconds(1001);
  t.OnWorkerStatus("a", 1, {0}, 0, t1 - milliseconds(1));
  REQUIRE(t.Expire(t1).size() == 1);
  CHECK(t.PassedOver("a", t1));
  const auto d = t.Schedule(t1);
  REQUIRE(d.size() == 1);
  CHECK(d[0].worker == "a");
}

TEST_CASE("a worker restarted under the same id loses its leases at once, not after the grace") {
  LeaseTable t(FastLeases());
  t.AddJob(0);
  t.AddJob(1);
  t.OnWorkerStatus("w", 1, {}, 0, t0, 7);
  auto d = t.Schedule(t0);
  REQUIRE(d.size() == 2);
  // 50 ms later (status_grace is 200 ms) the new process says it has done nothing yet.
  const auto t1 = t0 + milliseconds(50);
  t.OnWorkerStatus("w", 1, {}, 0, t1, 0);
  const auto lost = t.Expire(t1);
  REQUIRE(lost.size() == 2);
  CHECK(lost[0].reason == "worker restarted");
  d = t.Schedule(t1);
  REQUIRE(d.size() == 2);
  CHECK(d[0].attempt == 1);
  // Its count going up again is no restart.
  t.OnWorkerStatus("w", 1, {0, 1}, 0, t1 + milliseconds(10), 1);
  CHECK(t.Expire(t1 + milliseconds(10)).empty());
}
