// See targets.hpp.
#include "targets.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace blb {
namespace {

constexpr double kKernelMedian = 3.0;     // per-kernel median smoothed/plain, float
constexpr double kPeriodicMax = 6.0;      // every periodic-family entry, float
constexpr double kEntryMax = 10.0;        // every entry, float
constexpr double kDoubleOverFloat = 2.0;  // double's ratio within this factor of float's

std::string num(double v, const char* f = "%.2f") {
  char buf[32];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

double f32_ratio(const Row& r) {
  return r.f32_smoothed_ns / r.f32_plain_ns;
}
double f64_ratio(const Row& r) {
  return r.ns[static_cast<int>(Method::Smoothed)] / r.ns[static_cast<int>(Method::Plain)];
}

// Median of the finite values (NaN when none).
double median(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double d) { return !std::isfinite(d); }), v.end());
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

const char* verdict(bool ok) {
  return ok ? "**met**" : "**missed**";
}

// The rows above `limit` by `key`, worst first, as "name (ratio)".
template <class F>
std::string over(const std::vector<const Row*>& rows, double limit, F key) {
  std::vector<const Row*> v;
  for (const Row* r : rows)
    if (!(key(*r) <= limit)) v.push_back(r);
  std::sort(v.begin(), v.end(), [&](const Row* a, const Row* b) { return key(*a) > key(*b); });
  std::string s;
  for (const Row* r : v) s += (s.empty() ? "" : ", ") + r->name + " " + num(key(*r), "%.1f") + "x";
  return s.empty() ? "none" : s;
}

}  // namespace

int write_targets(std::ostream& o, const std::vector<Row>& rows) {
  int missed = 0;
  o << "## Speed targets (issue 14; float unless marked, this run)\n\n"
    << "| target | measured | verdict |\n|---|---|---|\n";
  for (const char* k : {"gaussian", "box", "tent"}) {
    std::vector<double> f, d;
    for (const Row& r : rows)
      if (r.kernel == k) f.push_back(f32_ratio(r)), d.push_back(f64_ratio(r));
    if (f.empty()) continue;
    const double mf = median(f), md = median(d);
    const bool ok = mf <= kKernelMedian;
    missed += !ok;
    o << "| " << k << ": median smoothed/plain <= " << num(kKernelMedian, "%.0f") << "x | " << num(mf)
      << "x (double " << num(md) << "x) | " << verdict(ok) << " |\n";
  }
  std::vector<const Row*> all, periodic;
  for (const Row& r : rows) {
    all.push_back(&r);
    if (r.family == "periodic") periodic.push_back(&r);
  }
  double pmax = 0, emax = 0;
  for (const Row* r : periodic) pmax = std::max(pmax, f32_ratio(*r));
  for (const Row* r : all) emax = std::max(emax, f32_ratio(*r));
  const bool pok = pmax <= kPeriodicMax, eok = emax <= kEntryMax;
  missed += !pok + !eok;
  o << "| every periodic entry <= " << num(kPeriodicMax, "%.0f") << "x | worst " << num(pmax)
    << "x; above: " << over(periodic, kPeriodicMax, f32_ratio) << " | " << verdict(pok) << " |\n";
  o << "| no entry > " << num(kEntryMax, "%.0f") << "x | worst " << num(emax)
    << "x; above: " << over(all, kEntryMax, f32_ratio) << " | " << verdict(eok) << " |\n";
  auto dof = [](const Row& r) { return f64_ratio(r) / f32_ratio(r); };
  auto fod = [](const Row& r) { return f32_ratio(r) / f64_ratio(r); };
  const std::string hi = over(all, kDoubleOverFloat, dof), lo = over(all, kDoubleOverFloat, fod);
  const bool dok = hi == "none" && lo == "none";
  missed += !dok;
  o << "| double's ratio within " << num(kDoubleOverFloat, "%.0f") << "x of float's | "
    << "double/float above 2: " << hi << "; float/double above 2: " << lo << " | " << verdict(dok) << " |\n\n"
    << "Ratios divide the smoothed function's time by the plain function's, both in the same "
    << "precision and run; one noisy row can cross a line between runs, so read a miss by a few "
    << "percent as marginal.\n\n";
  return missed;
}

}  // namespace blb
