#include "evolver/run/shared_options.h"

#include <chrono>
#include <cstdint>
#include <sstream>

#include "base/format.h"
#include "sim/core/envelope.h"

namespace ahhs::evolver {

namespace cli = base::cli;

void AddFarmOptions(cli::App& app, FarmCliOptions* o, const std::string& worker_wait_help) {
  app.add_option("--workers", o->workers,
                 "local worker processes to start (default: one per core; 0: only external)")
      ->check(cli::Range(0, 256));
  app.add_option("--arena-kind", o->arena, "how local workers evaluate: direct, fused or processes")
      ->check(cli::IsMember({"direct", "fused", "processes"}))
      ->capture_default_str();
  app.add_option("--lcm-url", o->url, "LCM URL of the evaluation farm (ttl=1 to use LAN workers)")
      ->capture_default_str();
  app.add_option("--job-deadline", o->job_deadline, "seconds before an evaluation is re-issued")
      ->check(cli::PositiveNumber)
      ->capture_default_str();
  app.add_option("--worker-wait", o->worker_wait, worker_wait_help)
      ->check(cli::PositiveNumber)
      ->capture_default_str();
  app.add_option("--wait-for-workers", o->wait_for_workers,
                 "before the first evaluation, wait until N workers (local ones included) are "
                 "ready to serve, at most --worker-wait seconds; fewer is an error (exit 1)")
      ->check(cli::Range(0, 100000))
      ->capture_default_str();
}

std::string FarmArgs(const FarmCliOptions& o) {
  const FarmCliOptions d;
  std::ostringstream args;
  if (o.workers != d.workers) args << " --workers " << o.workers;
  if (o.arena != d.arena) args << " --arena-kind " << o.arena;
  if (o.url != d.url) args << " --lcm-url " << base::ShellWord(o.url);
  if (o.job_deadline != d.job_deadline) args << " --job-deadline " << o.job_deadline;
  if (o.worker_wait != d.worker_wait) args << " --worker-wait " << o.worker_wait;
  if (o.wait_for_workers != d.wait_for_workers)
    args << " --wait-for-workers " << o.wait_for_workers;
  return args.str();
}

std::string WaitForFarmWorkers(const FarmCliOptions& o, FarmEvaluator* farm) {
  if (o.wait_for_workers <= 0) return "";
  const auto wait = std::chrono::milliseconds(static_cast<std::int64_t>(o.worker_wait * 1000));
  const int ready = farm->WaitForWorkers(o.wait_for_workers, wait);
  if (ready < o.wait_for_workers) {
    std::ostringstream seconds;
    seconds << o.worker_wait;
    std::string heard;
    for (const auto& [worker, host] : farm->workers())
      heard += (heard.empty() ? "" : ", ") + worker + " on " + host;
    throw FarmError("only " + std::to_string(ready) + " of the " +
                    std::to_string(o.wait_for_workers) +
                    " workers asked for (--wait-for-workers) "
                    "were ready to serve after " +
                    seconds.str() + " s (heard: " + (heard.empty() ? "none" : heard) + ")");
  }
  return std::to_string(ready) + (ready == 1 ? " worker ready" : " workers ready");
}

void ApplyFarmOptions(const FarmCliOptions& o, FarmOptions* farm) {
  farm->lease.job_deadline =
      std::chrono::milliseconds(static_cast<std::int64_t>(o.job_deadline * 1000));
  farm->no_worker_timeout =
      std::chrono::milliseconds(static_cast<std::int64_t>(o.worker_wait * 1000));
}

void AddRunEndOptions(cli::App& app, RunEndCliOptions* o, const std::string& prefix,
                      const char* validation_default, const char* post_eval_default) {
  auto* validation =
      app.add_option("--validation", o->validation,
                     prefix +
                         "when the run ends, choose its best by the median of N validation "
                         "episodes among its --validation-candidates best genomes and its last "
                         "generation's (0: the highest training fitness; docs/evolution.md, "
                         "\"Validation\")")
          ->check(cli::Range(0, kMaxValidation));
  if (validation_default)
    validation->default_str(validation_default);
  else
    validation->capture_default_str();
  app.add_option("--validation-candidates", o->validation_candidates,
                 prefix +
                     "how many of the run's best distinct genomes, and of its last generation's, "
                     "the validation compares")
      ->check(cli::Range(1, kMaxValidation))
      ->capture_default_str();
  auto* post_eval =
      app.add_option("--post-eval", o->post_eval,
                     prefix +
                         "when the run ends, replay its best on N held-out episodes: median, "
                         "quartiles, min and the share that succeeds, also in RUN/post-eval.json")
          ->check(cli::Range(0, kMaxPostEval));
  if (post_eval_default)
    post_eval->default_str(post_eval_default);
  else
    post_eval->capture_default_str();
  app.add_option("--post-eval-envelope", o->post_eval_envelope,
                 prefix +
                     "envelope of the held-out episodes, PRESET[,KEY=W...] such as "
                     "paper,command-delay=0.5 (default: the run's, or paper for a run without "
                     "one)")
      ->check([](const std::string& spec) {
        try {
          sim::ParseEnvelopeSpec(spec);
          return std::string();
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
      });
}

void ApplyRunEndOptions(const RunEndCliOptions& o, EvolveConfig* config) {
  config->validation = o.validation;
  config->validation_candidates = o.validation_candidates;
  config->post_eval = o.post_eval;
  config->post_eval_envelope = !o.post_eval_envelope.empty()
                                   ? sim::ParseEnvelopeSpec(o.post_eval_envelope)
                               : config->scenario.envelope.none() ? sim::EnvelopePreset("paper")
                                                                  : config->scenario.envelope;
}

}  // namespace ahhs::evolver
