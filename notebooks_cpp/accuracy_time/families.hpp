// Summaries of the benchmark rows: per family (and per kernel) medians of time and of relative error
// (absolute RMS error / RMS of the exact smoothed values), and the cheapest way to reach an error.
#pragma once

#include <string>
#include <vector>

#include "bench_csv.hpp"

namespace nb::acc {

// The ways of getting E[g(x + U)] the benchmark times, in order of the columns below.
enum Way { kPlain = 0, kMc4, kMc16, kMc64, kSmoothedF32, kSmoothed, kWays };
const char* way_name(int w);

struct FamilyStats {
  std::string family;
  int entries = 0;
  double ns[kWays];   // medians over the family's entries
  double err[kWays];  // relative RMS error, medians (kSmoothed: 0 by construction, not measured)
};

double median(std::vector<double> v);
std::vector<std::string> families_in_order(const std::vector<EntryRow>& rows);  // first appearance
FamilyStats family_stats(const std::vector<EntryRow>& rows, const std::string& family,
                         const std::string& kernel = "");  // kernel "" = all kernels

// The cheapest way in double (median ns; the float smoothed entry is left out) whose median relative
// error is <= target; -1 when none does. The double smoothed entry counts as error 1e-9 (blverify's
// bound for every entry).
int cheapest_way(const FamilyStats& f, double target);
inline constexpr double kSmoothedDoubleBound = 1e-9;

// Monte Carlo samples needed for a relative error, extrapolated from MC-64 as 1/sqrt(N).
double mc_samples_for(const FamilyStats& f, double target);

}  // namespace nb::acc
