// `bench_table --summary PREFIX`: times every entry (double: plain, smoothed, MC-4/16/64; float:
// plain, smoothed) in this one process, measures the errors, and writes PREFIX.md, PREFIX.csv and
// PREFIX.png.
#pragma once

#include <string>

namespace blb {

// Call after benchmark::Initialize (a --benchmark_filter restricts the entries). Returns the
// process exit code.
int run_summary(const std::string& prefix, const std::string& command);

}  // namespace blb
