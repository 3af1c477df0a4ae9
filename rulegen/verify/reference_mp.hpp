// blverify: 50-digit references (cpp_bin_float_50, Gauss-Kronrod 61, tolerance 1e-40, depth 12) for the
// points double cannot decide, and the entry's own smoothed<cpp_bin_float_50> at those points
// ("formula error (50 digits)"). All multiprecision code lives in reference_mp.cpp (slow to compile).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "registry_view.hpp"
#include "spec.hpp"

namespace blv {

struct MpResult {
  bool ok = false;
  std::string why;                // when !ok
  double ref = std::numeric_limits<double>::quiet_NaN();  // the 50-digit reference, rounded
  double ref_err = 0;             // its quadrature error estimate
  long pieces = 0;
  bool formula_finite = false;    // smoothed<cpp_bin_float_50>(x, sigma) is finite
  double formula_rel = std::numeric_limits<double>::quiet_NaN();  // |smoothed - ref| / max(1, |ref|)
};

// Direct quadrature only; at most this many pieces (else !ok).
constexpr int kMpPieceCap = 64;

// The reference for registry entry `index` (geometry from `spec`) at (x, sigma), with the plain and
// smoothed functions of the cpp_bin_float_50 instantiation.
MpResult mp_check(int index, const Spec& spec, double x, double sigma);

// The cpp_bin_float_50 instantiation lists the same entries (by C++ name) as the double one.
bool mp_registry_matches(const std::vector<EntryView>& entries, std::string* error);

// Computes the Gauss-Kronrod nodes once, before worker threads start.
void mp_warm_up();

}  // namespace blv
