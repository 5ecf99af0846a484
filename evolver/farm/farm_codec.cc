#include "evolver/farm/farm_codec.h"

#include <algorithm>
#include <limits>

#include "bus/channels.h"
#include "bus/codec.h"
#include "bus/wire_text.h"
#include "modules/node/genome_codec.h"
#include "sim/node/sim_codec.h"

namespace ahhs::evolver {

EncodedGenome EncodeGenome(const modules::Genome& genome) {
  const genome_t msg = modules::GenomeMessage(genome, 0);  // the job id travels in the request
  return {static_cast<std::uint64_t>(msg.genome_hash), bus::Encode(msg)};
}

std::string DecodeGenome(const std::vector<std::uint8_t>& bytes, std::uint64_t hash,
                         modules::Genome* out) {
  genome_t msg;
  if (!bus::Decode(bytes.data(), bytes.size(), &msg)) return "its pieces do not decode";
  if (static_cast<std::uint64_t>(msg.genome_hash) != hash)
    return "its pieces are another genome than the request names";
  return modules::GenomeFromMessage(msg, out);
}

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
  m.genome_hash = static_cast<std::int64_t>(job.genome_hash);
  m.genome_bytes = job.genome_bytes;
  m.genome_chunks = static_cast<std::int16_t>(job.genome_chunks);
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
  if (m.genome_bytes < 0 || m.genome_bytes > kMaxGenomeBytes)
    return "genome: size " + std::to_string(m.genome_bytes) + " out of range";
  if (m.genome_chunks < 1 || m.genome_chunks > std::max(1, m.genome_bytes))
    return "genome: " + std::to_string(m.genome_chunks) + " pieces for " +
           std::to_string(m.genome_bytes) + " bytes";
  job.genome_hash = static_cast<std::uint64_t>(m.genome_hash);
  job.genome_bytes = m.genome_bytes;
  job.genome_chunks = m.genome_chunks;
  *out = std::move(job);
  return "";
}

std::string PhysicsRefusal(const eval_request_t& m) {
  if (m.scenario != "gait" && m.scenario != "pendulum") return "";
  if (m.joints != sim_control_t::JOINTS_DAMPED && m.joints != sim_control_t::JOINTS_FIXED)
    return "";
  const sim::DockingKind docking = m.joints == sim_control_t::JOINTS_FIXED
                                       ? sim::DockingKind::kFixed
                                       : sim::DockingKind::kDamped;
  return sim::CheckPhysics(sim::ParseScenarioKind(m.scenario), docking, m.physics);
}

genome_chunk_t PieceMessage(const GenomePiece& p) {
  genome_chunk_t m;
  m.utime = bus::NowUtime();
  m.protocol_version = kFarmProtocolVersion;
  m.genome_hash = static_cast<std::int64_t>(p.genome_hash);
  m.genome_bytes = p.genome_bytes;
  m.index = static_cast<std::int16_t>(p.index);
  m.count = static_cast<std::int16_t>(p.count);
  m.size = static_cast<std::int16_t>(p.data.size());
  m.data = p.data;
  return m;
}

std::string PieceFromMessage(const genome_chunk_t& m, GenomePiece* out) {
  GenomePiece p;
  p.genome_hash = static_cast<std::uint64_t>(m.genome_hash);
  p.genome_bytes = m.genome_bytes;
  p.index = m.index;
  p.count = m.count;
  p.data = m.data;
  const std::string error = CheckPiece(p);
  if (!error.empty()) return error;
  *out = std::move(p);
  return "";
}

genome_want_t WantMessage(const GenomeWant& w) {
  genome_want_t m;
  m.utime = bus::NowUtime();
  m.protocol_version = w.protocol_version;
  m.run = w.run;
  m.worker = w.worker;
  m.genome_hash = static_cast<std::int64_t>(w.genome_hash);
  const std::size_t n =
      std::min<std::size_t>(w.missing.size(), std::numeric_limits<std::int16_t>::max());
  m.num_missing = static_cast<std::int16_t>(n);
  for (std::size_t k = 0; k < n; ++k) m.missing.push_back(static_cast<std::int16_t>(w.missing[k]));
  return m;
}

GenomeWant WantFromMessage(const genome_want_t& m) {
  GenomeWant w;
  w.protocol_version = m.protocol_version;
  w.run = m.run;
  w.worker = m.worker;
  w.genome_hash = static_cast<std::uint64_t>(m.genome_hash);
  w.missing.assign(m.missing.begin(), m.missing.end());
  return w;
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
  m.descriptor = o.descriptor;
  m.descriptor_size = static_cast<std::int8_t>(m.descriptor.size());
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
  o.descriptor = m.descriptor;
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
