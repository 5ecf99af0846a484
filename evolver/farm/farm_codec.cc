#include "evolver/farm/farm_codec.h"

#include <limits>

#include "bus/channels.h"
#include "bus/wire_text.h"
#include "modules/node/genome_codec.h"
#include "sim/node/sim_codec.h"

namespace ahhs::evolver {

eval_request_t RequestMessage(const FarmJob& job) {
  eval_request_t m;
  m.utime = bus::NowUtime();
  m.protocol_version = job.protocol_version;
  m.run = job.run;
  m.job = job.job;
  m.attempt = job.attempt;
  m.worker = job.worker;
  sim::ScenarioToWire(job.config, &m);
  m.seed = static_cast<std::int64_t>(job.seed);
  m.deadline_utime = job.deadline_utime;
  m.genome = modules::GenomeMessage(job.genome, 0);  // the job id travels in `job`
  return m;
}

std::string JobFromMessage(const eval_request_t& m, FarmJob* out) {
  FarmJob job;
  job.protocol_version = m.protocol_version;
  job.run = m.run;
  job.job = m.job;
  job.attempt = m.attempt;
  job.worker = m.worker;
  const std::string config_error = sim::ScenarioFromWire(m, &job.config);
  if (!config_error.empty()) return config_error;
  job.seed = static_cast<std::uint64_t>(m.seed);
  job.deadline_utime = m.deadline_utime;
  const std::string genome_error = modules::GenomeFromMessage(m.genome, &job.genome);
  if (!genome_error.empty()) return "genome: " + genome_error;
  *out = std::move(job);
  return "";
}

eval_result_t ResultMessage(const FarmResult& o) {
  eval_result_t m;
  m.utime = bus::NowUtime();
  m.protocol_version = o.protocol_version;
  m.run = o.run;
  m.job = o.job;
  m.attempt = o.attempt;
  m.worker = o.worker;
  m.status = o.status == FarmResult::Status::kOk      ? eval_result_t::OK
             : o.status == FarmResult::Status::kError ? eval_result_t::ERROR
                                                      : eval_result_t::REFUSED;
  m.fitness = o.fitness;
  m.cost = o.cost;
  m.wall_time = o.wall_time;
  m.late_messages = o.states_missed;  // the wire keeps its first name
  m.message = bus::ToWireText(o.message);
  return m;
}

FarmResult OutcomeFromMessage(const eval_result_t& m) {
  FarmResult o;
  o.protocol_version = m.protocol_version;
  o.run = m.run;
  o.job = m.job;
  o.attempt = m.attempt;
  o.worker = m.worker;
  o.status = m.status == eval_result_t::OK      ? FarmResult::Status::kOk
             : m.status == eval_result_t::ERROR ? FarmResult::Status::kError
                                                : FarmResult::Status::kRefused;
  o.fitness = m.fitness;
  o.cost = m.cost;
  o.wall_time = m.wall_time;
  o.states_missed = m.late_messages;
  o.message = m.message;
  return o;
}

worker_status_t StatusMessage(const WorkerStatus& s) {
  worker_status_t m;
  m.utime = bus::NowUtime();
  m.protocol_version = s.protocol_version;
  m.worker = s.worker;
  m.host = s.host;
  m.slots = s.slots;
  m.free_slots = s.free_slots;
  m.evaluations_done = s.evaluations_done;
  const std::size_t n =
      std::min<std::size_t>(s.jobs.size(), std::numeric_limits<std::int16_t>::max());
  m.num_jobs = static_cast<std::int16_t>(n);
  m.jobs.assign(s.jobs.begin(), s.jobs.begin() + static_cast<std::ptrdiff_t>(n));
  m.run = s.run;
  return m;
}

WorkerStatus StatusFromMessage(const worker_status_t& m) {
  WorkerStatus s;
  s.protocol_version = m.protocol_version;
  s.worker = m.worker;
  s.host = m.host;
  s.slots = m.slots;
  s.free_slots = m.free_slots;
  s.evaluations_done = m.evaluations_done;
  s.jobs = m.jobs;
  s.run = m.run;
  return s;
}

}  // namespace ahhs::evolver
