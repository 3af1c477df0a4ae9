// Writes the summary's CSV and Markdown files; see report.hpp.
#include "report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "entry_view.hpp"
#include "targets.hpp"

namespace blb {
namespace {

std::string fmt(const char* f, double v) {
  if (std::isnan(v)) return "nan";
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::ofstream open_out(const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("bench_table: cannot write " + path);
  return out;
}

// Median (and 10th/90th percentiles) of the finite values; NaN when there are none.
double quantile(std::vector<double> v, double q) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double d) { return !std::isfinite(d); }), v.end());
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const double pos = q * (v.size() - 1);
  const size_t i = static_cast<size_t>(pos);
  return i + 1 < v.size() ? v[i] + (pos - i) * (v[i + 1] - v[i]) : v[i];
}

double rel(const Row& r, Method m) {
  const double e = r.err[static_cast<int>(m)];
  return r.ref_rms > 0 ? e / r.ref_rms : NAN;
}

double ratio(const Row& r, Method a, Method b) {
  return r.ns[static_cast<int>(a)] / r.ns[static_cast<int>(b)];
}

template <class F>
std::vector<double> collect(const std::vector<const Row*>& rows, F f) {
  std::vector<double> v;
  for (const Row* r : rows) v.push_back(f(*r));
  return v;
}

void write_intro(std::ostream& o, const std::vector<Row>& rows, const RunInfo& info) {
  o << "# What accuracy costs in time\n\n"
    << "Reproduce with `cmake -S . -B build -DBL_BUILD_BENCH=ON && cmake --build build --target "
    << "bench_table && ./build/bin/bench_table --summary " << info.prefix
    << "` (Release build; one process writes `" << info.prefix << ".md`, `.csv` and `.png`, in "
    << fmt("%.0f", info.wall_s) << " s here). For every entry of the generated registry (" << rows.size()
    << " entries: convolutions of f and of f^2 with the Gaussian, box and tent "
    << "kernels, and the raw moments E[(x+U)^n]) it times five ways of obtaining the smoothed "
    << "value E[g(x+U)] (g = f, f^2 or x^n) on the same " << info.inputs
    << " (x, sigma) pairs (x uniform in [-4, 4] clipped to the domain, sigma log-uniform in "
    << "[0.01, 1]): the plain function g(x) (no smoothing), the emitted smoothed function, and "
    << "Monte Carlo estimates with 4, 16 and 64 samples drawn from the entry's kernel. Times are "
    << "CPU ns per call in double precision, the median of " << info.repetitions
    << " Google Benchmark repetitions (each at least " << fmt("%g", info.min_time_s * 1e3)
    << " ms); every ratio compares times measured in this same run. Errors are RMS over the "
    << "inputs (and over " << info.error_seeds << " seeds for Monte Carlo) of the difference "
    << "from the emitted double-precision smoothed function, which is the reference here (blverify "
    << "checks it against quadrature to 1e-9), so its own error is 0 by construction and is not "
    << "listed; the float column is the measured error of the float instantiation against it. "
    << "**This machine is shared and noisy**: single rows can be off by tens of percent between "
    << "runs; read ratios and orders of magnitude, not the last digit.\n\n";
  o << "## Run\n\n"
    << "- command: `" << info.command << "`\n"
    << "- machine: " << info.machine.nproc << " cores (`nproc`), " << info.machine.cpu << "\n"
    << "- compiler: " << info.machine.compiler << "\n"
    << "- " << info.repetitions << " repetitions per benchmark, min time " << fmt("%g", info.min_time_s * 1e3)
    << " ms, " << info.inputs << " inputs per call batch, " << info.error_seeds
    << " seeds for the Monte Carlo errors\n\n";
  o << "## How it is measured\n\n"
    << "- Every call goes through the registry's function pointers (`smoothed`, `plain`), so "
    << "each costs an indirect call (about 1 ns) that inlined shader code would not pay: for the "
    << "cheapest plain functions (step, abs, x^n) the call dominates and the smoothed/plain "
    << "ratio understates the relative cost. A Monte Carlo estimate pays it once per sample.\n"
    << "- Monte Carlo draws its random numbers inside the timed region (a renderer pays for them "
    << "too): splitmix64, Box-Muller for the Gaussian (a pair of samples per two uniforms), one "
    << "uniform per box sample, the sum of two per tent sample.\n"
    << "- Compact entries (box/tent of tan, log, sqrt, inv, inv2) limit the kernel's half-width "
    << "to 0.5 x the distance to the nearest singularity, as the emitted function does; the "
    << "Monte Carlo estimate samples that same limited kernel.\n"
    << "- A Gaussian break (piecewise, periodic and staircase entries, float and double) reads "
    << "phi and Phic from a generated table of piecewise polynomials on [0, tail_cut] "
    << "(generated/bandlimit/normal_table.hpp: degree 4 in float, 9 in double, h = 1/4; absolute "
    << "error 4.3e-8 and 2.2e-16, normal_table_test against 50-digit erfc/exp): two short Horner "
    << "chains from one row, no exp, erfc or division. Other float Gaussian entries take erfc from "
    << "support.hpp's erfc_f (relative error < 6e-7), not from libm's erfcf.\n"
    << "- Plain x^n is f^n by repeated squaring, and the benchmark pads jumps off 32-byte "
    << "boundaries (Intel's JCC erratum made functions of a few ns move by up to 2x with code "
    << "layout alone).\n"
    << "- Errors are absolute; `ref RMS` (RMS of the exact smoothed values) gives their scale, "
    << "and the family table divides by it.\n"
    << "- Debian's libbenchmark warns that it was built as DEBUG; its code runs only between "
    << "batches of " << info.inputs << " calls, so it does not enter the per-call times.\n\n";
}

void write_headline(std::ostream& o, const std::vector<Row>& rows) {
  std::vector<const Row*> all;
  for (const Row& r : rows) all.push_back(&r);
  auto sp = collect(all, [](const Row& r) { return ratio(r, Method::Smoothed, Method::Plain); });
  auto m16 = collect(all, [](const Row& r) { return ratio(r, Method::MC16, Method::Smoothed); });
  auto e16 = collect(all, [](const Row& r) { return rel(r, Method::MC16); });
  auto e64 = collect(all, [](const Row& r) { return rel(r, Method::MC64); });
  auto ep = collect(all, [](const Row& r) { return rel(r, Method::Plain); });
  o << "## Headline (this run)\n\n"
    << "Over all " << rows.size() << " entries, the smoothed function costs a median "
    << fmt("%.2g", quantile(sp, 0.5)) << "x the plain function (10th-90th percentile "
    << fmt("%.2g", quantile(sp, 0.1)) << "-" << fmt("%.2g", quantile(sp, 0.9)) << "x); MC-16 costs a median "
    << fmt("%.2g", quantile(m16, 0.5))
    << "x the smoothed function and still has a median relative RMS error of "
    << fmt("%.2g", quantile(e16, 0.5)) << " (MC-64: " << fmt("%.2g", quantile(e64, 0.5))
    << ", plain f: " << fmt("%.2g", quantile(ep, 0.5))
    << "), where the smoothed function is exact to rounding.\n\n";
}

void write_family_table(std::ostream& o, const std::vector<Row>& rows) {
  o << "## Per family (medians over the family's entries)\n\n"
    << "| family | entries | smoothed/plain | MC4/smoothed | MC16/smoothed | MC64/smoothed | "
    << "rel. err plain | rel. err MC4 | rel. err MC16 | rel. err MC64 |\n"
    << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const std::string& fam : families()) {
    std::vector<const Row*> fr;
    for (const Row& r : rows)
      if (r.family == fam) fr.push_back(&r);
    if (fr.empty()) continue;
    auto med_ratio = [&](Method a, Method b) {
      return fmt("%.3g", quantile(collect(fr, [&](const Row& r) { return ratio(r, a, b); }), 0.5));
    };
    auto med_err = [&](Method m) {
      return fmt("%.2e", quantile(collect(fr, [&](const Row& r) { return rel(r, m); }), 0.5));
    };
    o << "| " << fam << " | " << fr.size() << " | " << med_ratio(Method::Smoothed, Method::Plain) << " | "
      << med_ratio(Method::MC4, Method::Smoothed) << " | " << med_ratio(Method::MC16, Method::Smoothed)
      << " | " << med_ratio(Method::MC64, Method::Smoothed) << " | " << med_err(Method::Plain) << " | "
      << med_err(Method::MC4) << " | " << med_err(Method::MC16) << " | " << med_err(Method::MC64) << " |\n";
  }
  o << "\nFamilies: trig (sin, cos), exp-like (exp, sinh, cosh), powers (pow2..pow8 and the raw "
    << "moments), piecewise (abs, sign, step, saturate, smoothstep), periodic (fract, triangle, "
    << "square, floor, ceil, trunc), singular (tan, tanh, log, sqrt, inv, inv2).\n\n";
}

void write_entry_table(std::ostream& o, const std::vector<Row>& rows) {
  o << "## All entries\n\n"
    << "ns per call (double, median); RMS errors absolute. The double smoothed function is the "
    << "reference (error 0 by construction).\n\n"
    << "| entry | plain ns | smoothed ns | MC4 ns | MC16 ns | MC64 ns | smoothed/plain | "
    << "RMS err plain | RMS err MC4 | RMS err MC16 | RMS err MC64 | ref RMS | float smoothed ns "
    << "| float smoothed RMS err |\n"
    << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const Row& r : rows) {
    o << "| " << r.name;
    for (Method m : kMethods) o << " | " << fmt("%.3g", r.ns[static_cast<int>(m)]);
    o << " | " << fmt("%.3g", ratio(r, Method::Smoothed, Method::Plain));
    for (Method m : {Method::Plain, Method::MC4, Method::MC16, Method::MC64})
      o << " | " << fmt("%.2e", r.err[static_cast<int>(m)]);
    o << " | " << fmt("%.2e", r.ref_rms) << " | " << fmt("%.3g", r.f32_smoothed_ns) << " | "
      << fmt("%.2e", r.f32_smoothed_err) << " |\n";
  }
}

}  // namespace

void write_csv(const std::string& path, const std::vector<Row>& rows) {
  std::ofstream o = open_out(path);
  o << "entry,kernel,family,plain_ns,smoothed_ns,mc4_ns,mc16_ns,mc64_ns,smoothed_over_plain,"
    << "err_plain,err_mc4,err_mc16,err_mc64,ref_rms,f32_plain_ns,f32_smoothed_ns,"
    << "f32_smoothed_err\n";
  for (const Row& r : rows) {
    o << r.name << "," << r.kernel << "," << r.family;
    for (Method m : kMethods) o << "," << fmt("%.6g", r.ns[static_cast<int>(m)]);
    o << "," << fmt("%.6g", ratio(r, Method::Smoothed, Method::Plain));
    for (Method m : {Method::Plain, Method::MC4, Method::MC16, Method::MC64})
      o << "," << fmt("%.6e", r.err[static_cast<int>(m)]);
    o << "," << fmt("%.6e", r.ref_rms) << "," << fmt("%.6g", r.f32_plain_ns) << ","
      << fmt("%.6g", r.f32_smoothed_ns) << "," << fmt("%.6e", r.f32_smoothed_err) << "\n";
  }
}

void write_markdown(const std::string& path, const std::string& png_name, const std::vector<Row>& rows,
                    const RunInfo& info) {
  std::ofstream o = open_out(path);
  write_intro(o, rows, info);
  write_headline(o, rows);
  write_targets(o, rows);
  write_family_table(o, rows);
  o << "## Plot\n\n![RMS error against time per call, one panel per family](" << png_name
    << ")\n\nx: ns per call (log); y: RMS error (log). Errors of exactly 0 (the double smoothed "
    << "function, and plain f where smoothing changes nothing, e.g. moments of order 0 and 1) are "
    << "drawn at 1e-17.\n\n";
  write_entry_table(o, rows);
}

}  // namespace blb
