// bench_table: what accuracy costs in time. Google Benchmark of every registry entry (plain f,
// smoothed, Monte Carlo with 4/16/64 samples; double and float) with RMS-error counters, or, with
// `--summary PREFIX`, the one-process summary PREFIX.{md,csv,png} (summary.hpp).
#include <benchmark/benchmark.h>

#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "summary.hpp"
#include "timing.hpp"

namespace {

// Removes `--summary PREFIX` / `--summary=PREFIX` from argv; returns PREFIX ("" when absent).
std::string take_summary_flag(int* argc, char** argv, bool* bad) {
  std::string prefix;
  int out = 1;
  for (int i = 1; i < *argc; ++i) {
    const char* a = argv[i];
    if (std::strcmp(a, "--summary") == 0) {
      if (i + 1 >= *argc)
        *bad = true;
      else
        prefix = argv[++i];
    } else if (std::strncmp(a, "--summary=", 10) == 0) {
      prefix = a + 10;
      if (prefix.empty()) *bad = true;
    } else {
      argv[out++] = argv[i];
    }
  }
  *argc = out;
  return prefix;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string program = argv[0];
  bool bad = false;
  const std::string prefix = take_summary_flag(&argc, argv, &bad);
  if (bad) {
    std::cerr << "usage: " << program << " [--summary PREFIX] [--benchmark_...]\n";
    return 2;
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
  if (!prefix.empty()) return blb::run_summary(prefix, program + " --summary " + prefix);
  blb::register_benchmarks(blb::all_benchmarks());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
