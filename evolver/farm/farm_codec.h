// Farm structs <-> LCM messages (eval_request_t, eval_result_t, worker_status_t). Pure functions.
#pragma once

#include <ahhs/eval_request_t.hpp>
#include <ahhs/eval_result_t.hpp>
#include <ahhs/worker_status_t.hpp>
#include <string>

#include "evolver/farm/farm_protocol.h"

namespace ahhs::evolver {

eval_request_t RequestMessage(const FarmJob& job);
// Decodes and validates (scenario, genome). Returns "" or why the request is unusable. The
// protocol version is copied, not checked: the worker answers a foreign version itself.
std::string JobFromMessage(const eval_request_t& msg, FarmJob* out);

eval_result_t ResultMessage(const FarmResult& outcome);
FarmResult OutcomeFromMessage(const eval_result_t& msg);

worker_status_t StatusMessage(const WorkerStatus& status);
WorkerStatus StatusFromMessage(const worker_status_t& msg);

}  // namespace ahhs::evolver
