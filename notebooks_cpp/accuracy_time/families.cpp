// See families.hpp.
#include "families.hpp"

#include <algorithm>
#include <cmath>

namespace nb::acc {

const char* way_name(int w) {
  static const char* names[] = {"plain f", "MC-4", "MC-16", "MC-64", "smoothed (float)", "smoothed (double)"};
  return names[w];
}

double median(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::vector<std::string> families_in_order(const std::vector<EntryRow>& rows) {
  std::vector<std::string> out;
  for (const EntryRow& r : rows)
    if (std::find(out.begin(), out.end(), r.family) == out.end()) out.push_back(r.family);
  return out;
}

FamilyStats family_stats(const std::vector<EntryRow>& rows, const std::string& family,
                         const std::string& kernel) {
  FamilyStats f;
  f.family = family;
  std::vector<double> ns[kWays], err[kWays];
  for (const EntryRow& r : rows) {
    if (r.family != family || (!kernel.empty() && r.kernel != kernel)) continue;
    ++f.entries;
    const double scale = r.ref_rms > 0 ? r.ref_rms : NAN;
    ns[kPlain].push_back(r.plain_ns);
    err[kPlain].push_back(r.err_plain / scale);
    for (int k = 0; k < 3; ++k) {
      ns[kMc4 + k].push_back(r.mc_ns[k]);
      err[kMc4 + k].push_back(r.err_mc[k] / scale);
    }
    ns[kSmoothedF32].push_back(r.f32_smoothed_ns);
    err[kSmoothedF32].push_back(r.f32_smoothed_err / scale);
    ns[kSmoothed].push_back(r.smoothed_ns);
    err[kSmoothed].push_back(0);
  }
  for (int w = 0; w < kWays; ++w) {
    f.ns[w] = median(ns[w]);
    f.err[w] = median(err[w]);
  }
  return f;
}

int cheapest_way(const FamilyStats& f, double target) {
  int best = -1;
  for (int w = 0; w < kWays; ++w) {
    if (w == kSmoothedF32) continue;  // timed in float: not comparable with the double columns
    const double e = w == kSmoothed ? kSmoothedDoubleBound : f.err[w];
    if (!(e <= target)) continue;
    if (best < 0 || f.ns[w] < f.ns[best]) best = w;
  }
  return best;
}

double mc_samples_for(const FamilyStats& f, double target) {
  const double e = f.err[kMc64];
  return 64 * (e / target) * (e / target);
}

}  // namespace nb::acc
