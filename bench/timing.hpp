// Google Benchmark registration: one benchmark per (scalar type, registry entry, method), named
// "<kernel>/<function>/<method>" for double and "float/<kernel>/<function>/<method>" for float.
// Each iteration evaluates the method on the entry's kNumInputs (x, sigma) pairs; the counters are
// per_call (seconds per call, shown as ns) and rms_err (accuracy.hpp; absent for the double
// smoothed function, which is the reference).
#pragma once

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "methods.hpp"

namespace blb {

struct BenchId {
  bool is_float;
  int entry;  // index into double_entries() / float_entries()
  Method method;
  std::string name() const;
};

// Every entry, every method, double and float.
std::vector<BenchId> all_benchmarks();

std::vector<benchmark::internal::Benchmark*> register_benchmarks(const std::vector<BenchId>& ids);

// The RMS error of the benchmark's method (NaN for the double smoothed function), computed once.
double cached_error(const BenchId& id);

}  // namespace blb
