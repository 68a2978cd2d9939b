// The human-readable report of stairs-eval: the thesis' tables 6.1-6.4, the
// final model's steps and per-stage latency.
#pragma once

#include "tools/result_json.hpp"

#include <ostream>

namespace stairs::eval {

void print_report(std::ostream& out, const RunResult& r);

}  // namespace stairs::eval
