// The one-process summary run; see summary.hpp.
#include "summary.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "accuracy.hpp"
#include "entry_view.hpp"
#include "inputs.hpp"
#include "machine.hpp"
#include "plot.hpp"
#include "report.hpp"
#include "targets.hpp"
#include "timing.hpp"

namespace blb {
namespace {

constexpr int kRepetitions = 5;
constexpr double kMinTime = 0.004;  // seconds per repetition

// Collects the per-repetition ns per call of every benchmark; prints one progress line per entry.
class Collector : public benchmark::BenchmarkReporter {
 public:
  std::map<std::string, std::vector<double>> ns;
  bool ReportContext(const Context&) override { return true; }
  void ReportRuns(const std::vector<Run>& runs) override {
    bool timed = false;
    for (const Run& r : runs) {
      if (r.run_type != Run::RT_Iteration || r.error_occurred) continue;
      const auto c = r.counters.find("per_call");
      if (c == r.counters.end()) continue;
      ns[r.run_name.function_name].push_back(c->second.value * 1e9);
      timed = true;
    }
    if (timed && ++done_ % 200 == 0) std::cerr << "  timed " << done_ << " benchmarks\n";
  }

 private:
  int done_ = 0;
};

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::vector<BenchId> summary_benchmarks() {
  std::vector<BenchId> ids;
  const int n = static_cast<int>(double_entries().size());
  for (int i = 0; i < n; ++i) {
    for (Method m : kMethods) ids.push_back({false, i, m});
    ids.push_back({true, i, Method::Plain});
    ids.push_back({true, i, Method::Smoothed});
  }
  return ids;
}

std::vector<Row> make_rows(const Collector& c) {
  std::vector<Row> rows;
  auto ns_of = [&](const BenchId& id) {
    auto it = c.ns.find(id.name());
    return it == c.ns.end() ? NAN : median(it->second);
  };
  for (int i = 0; i < static_cast<int>(double_entries().size()); ++i) {
    const EntryView<double>& v = double_entries()[i];
    if (!c.ns.count(BenchId{false, i, Method::Smoothed}.name())) continue;  // filtered out
    Row r;
    r.name = v.name;
    r.kernel = v.entry->kernel;
    r.family = v.family;
    for (Method m : kMethods) {
      r.ns[static_cast<int>(m)] = ns_of({false, i, m});
      r.err[static_cast<int>(m)] = cached_error({false, i, m});
    }
    r.ref_rms = rms_reference(v, make_inputs(*v.entry->atomic));
    r.f32_plain_ns = ns_of({true, i, Method::Plain});
    r.f32_smoothed_ns = ns_of({true, i, Method::Smoothed});
    r.f32_smoothed_err = cached_error({true, i, Method::Smoothed});
    rows.push_back(r);
  }
  return rows;
}

}  // namespace

int run_summary(const std::string& prefix, const std::string& command) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<BenchId> ids = summary_benchmarks();
  std::cerr << "bench_table --summary: errors of " << ids.size() << " (entry, method) pairs\n";
  for (const BenchId& id : ids) cached_error(id);
  std::cerr << "bench_table --summary: timing (" << kRepetitions << " repetitions each)\n";
  for (benchmark::internal::Benchmark* b : register_benchmarks(ids))
    b->MinTime(kMinTime)->Repetitions(kRepetitions)->ReportAggregatesOnly(false);
  Collector collector;
  benchmark::RunSpecifiedBenchmarks(&collector);
  const std::vector<Row> rows = make_rows(collector);
  if (rows.empty()) {
    std::cerr << "bench_table --summary: no benchmark ran (check --benchmark_filter)\n";
    return 1;
  }
  RunInfo info{machine_info(), kRepetitions, kMinTime, kNumInputs, kErrorSeeds, 0, command, prefix};
  info.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::string png = prefix + ".png";
  try {
    write_csv(prefix + ".csv", rows);
    write_markdown(prefix + ".md", png.substr(png.find_last_of('/') + 1), rows, info);
    std::vector<std::string> panels;
    for (const std::string& f : families())
      if (std::any_of(rows.begin(), rows.end(), [&](const Row& r) { return r.family == f; }))
        panels.push_back(f);
    write_plot(prefix + ".csv", png, panels);
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  std::ostringstream targets;
  const int missed = write_targets(targets, rows);
  std::cerr << targets.str() << "bench_table --summary: " << missed << " speed target(s) missed\n";
  std::cerr << "bench_table --summary: wrote " << prefix << ".{md,csv,png} (" << rows.size() << " entries, "
            << static_cast<int>(info.wall_s) << " s)\n";
  return 0;
}

}  // namespace blb
