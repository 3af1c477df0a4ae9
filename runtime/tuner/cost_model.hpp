// The tuner's time axis: a per-instruction cost model. Every LOp and every generated function (by
// its C++ name) has a cost in ns per pixel, calibrated on this machine by timing the batch evaluator
// (calibrate.hpp). cost(Program) is the sum over instructions, so the search is deterministic given
// the model file, and the file is keyed by machine (the CPU model string) so that one checkout can
// carry calibrations of several machines.
#pragma once

#include <map>
#include <string>

#include "compiler/lir.hpp"

namespace bl::tuner {

struct CostModel {
  std::string machine;                  // CPU model string the numbers were measured on
  std::map<std::string, double> op_ns;  // LOp name -> ns per pixel
  std::map<std::string, double> fn_ns;  // Function::cpp -> ns per pixel (the call's instruction)

  // ns per pixel of p. Throws std::out_of_range naming an op or function the model lacks.
  double cost(const compiler::Program& p) const;
  // True when every LOp and every current generated function has an entry.
  bool covers_all() const;
  // The names covers_all() misses (for messages).
  std::string missing() const;
};

const char* lop_name(compiler::LOp op);
std::string cpu_model();  // "model name" of /proc/cpuinfo, or "unknown-cpu"

// File format: {"machines": {"<cpu>": {"ops": {...}, "functions": {...}}}}. load throws
// std::runtime_error naming the file when it is unreadable, malformed or has no entry for `machine`.
CostModel load_cost_model(const std::string& path, const std::string& machine);
// Adds or replaces the model's machine entry, keeping the other machines' entries.
void save_cost_model(const std::string& path, const CostModel& m);

}  // namespace bl::tuner
