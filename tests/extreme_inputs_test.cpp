// Extreme inputs (issue 14): every bounded registry entry (convolution of an atomic whose range is
// finite), float and double, stays finite and inside the range of f (or f^2) on the grid
// x in {0, +-1e-12, +-0.5, +-1, +-37.5, +-1e6, +-1e30} x sigma in {0, 1e-30, 1e-12, 1e-6, 0.25, 2,
// 1e3, 1e6, 1e30}. The range comes from the catalog (registry AtomicInfo), not from the entries.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "bandlimit/registry.hpp"

namespace {

constexpr double kXs[] = {0, 1e-12, -1e-12, 0.5, -0.5, 1, -1, 37.5, -37.5, 1e6, -1e6, 1e30, -1e30};
constexpr double kSigmas[] = {0, 1e-30, 1e-12, 1e-6, 0.25, 2, 1e3, 1e6, 1e30};

// Closed range of f or f^2, from the catalog's range of f.
void range_of(const bl::registry::AtomicInfo& a, bool squared, double* lo, double* hi) {
  *lo = a.range_lo;
  *hi = a.range_hi;
  if (!squared) return;
  const double m = std::max(a.range_lo * a.range_lo, a.range_hi * a.range_hi);
  *lo =
      (a.range_lo <= 0 && a.range_hi >= 0) ? 0.0 : std::min(a.range_lo * a.range_lo, a.range_hi * a.range_hi);
  *hi = m;
}

template <class T>
void check_all(const char* type) {
  int n = 0;
  const auto* e = bl::registry::entries<T>(&n);
  int bounded = 0, checked = 0;
  std::ostringstream bad;
  int nbad = 0;
  for (int i = 0; i < n; ++i) {
    const auto& en = e[i];
    if (en.rule != std::string("convolution")) continue;
    if (!std::isfinite(en.atomic->range_lo) || !std::isfinite(en.atomic->range_hi)) continue;
    ++bounded;
    double lo, hi;
    range_of(*en.atomic, en.squared, &lo, &hi);
    for (double xd : kXs) {
      const T x = static_cast<T>(xd);
      if (!(x > en.atomic->domain_lo && x < en.atomic->domain_hi)) continue;
      for (double sd : kSigmas) {
        const T s = static_cast<T>(sd);
        const T v = en.smoothed(x, s);
        ++checked;
        if (!std::isfinite(v) || !(v >= T(lo) && v <= T(hi))) {
          if (++nbad <= 400)
            bad << "  " << en.cpp << "(" << xd << ", " << sd << ") = " << v << " not in [" << lo << ", " << hi
                << "]\n";
        }
      }
    }
  }
  EXPECT_GT(bounded, 50) << type;
  EXPECT_EQ(nbad, 0) << type << ": " << nbad << " of " << checked
                     << " evaluations non-finite or out of range:\n"
                     << bad.str();
}

TEST(ExtremeInputs, FloatStaysFiniteAndInRange) {
  check_all<float>("float");
}
TEST(ExtremeInputs, DoubleStaysFiniteAndInRange) {
  check_all<double>("double");
}

}  // namespace
