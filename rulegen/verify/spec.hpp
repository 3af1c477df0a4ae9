// blverify: the description of one smoothed function that the references need: the kernel, the
// integrand g = f^power, where f jumps/kinks/blows up, its domain and range. Built from a registry
// entry (registry_view.cpp) or from a published-table row (published_tables.cpp).
#pragma once

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace blv {

enum class Kernel { Gaussian, Box, Tent };

inline const char* kernel_name(Kernel k) {
  switch (k) {
    case Kernel::Gaussian: return "gaussian";
    case Kernel::Box: return "box";
    case Kernel::Tent: return "tent";
  }
  return "?";
}

inline bool parse_kernel(const std::string& s, Kernel* k) {
  if (s == "gaussian") { *k = Kernel::Gaussian; return true; }
  if (s == "box") { *k = Kernel::Box; return true; }
  if (s == "tent") { *k = Kernel::Tent; return true; }
  return false;
}

// Half-width of the kernel's support in units of sigma (box sqrt(3), tent sqrt(6)); 0 for Gaussian.
inline double support_factor(Kernel k) {
  return k == Kernel::Box ? std::sqrt(3.0) : (k == Kernel::Tent ? std::sqrt(6.0) : 0.0);
}

// The rest b - bb of a break bb that is the double nearest a simple fraction b = p/q (q <= 1e6, as
// catalog breaks are: 3/10 is 0.3 + 1.1e-17), else 0. The references place breaks at bb + rest, so a
// kernel narrower than bb's rounding (sigma = 1e-12 at 0.3: 4e-6 of a jump) sees the break where the
// catalog puts it. The first continued-fraction convergent within half an ulp of bb is the fraction.
inline double break_rest(double bb) {
  if (!std::isfinite(bb) || bb == std::floor(bb)) return 0;
  const double half_ulp = 0.5 * (std::nextafter(std::fabs(bb), INFINITY) - std::fabs(bb));
  double x = bb, p0 = 1, q0 = 0, p1 = std::floor(x), q1 = 1;
  for (int n = 0; n < 40; ++n) {
    const double frac = x - std::floor(x);
    if (frac == 0) break;
    x = 1 / frac;
    const double a = std::floor(x), p2 = a * p1 + p0, q2 = a * q1 + q0;
    if (!(q2 <= 1e6)) break;
    const double r = std::fma(-q2, bb, p2);  // p - q bb, rounded once
    if (std::fabs(r) / q2 <= half_ulp) return r / q2;
    p0 = p1, q0 = q1, p1 = p2, q1 = q2;
  }
  return 0;
}

struct Spec {
  std::string name;                  // for messages (the entry's qualified C++ name)
  Kernel kernel = Kernel::Gaussian;
  int power = 1;                     // integrand g = f^power: 2 for squared entries, n for moments
  bool compact = false;              // half-width min(h, lambda * distance to nearest singular point)
  double lambda = 0;
  double period = 0;                 // > 0: breaks and singular points repeat with this period
  bool periodic = false;             // catalog class "periodic" (f itself repeats)
  std::vector<double> breaks;        // jumps, kinks, singularities (first period when period > 0)
  std::vector<double> singular;      // poles and domain ends
  double domain_lo = -std::numeric_limits<double>::infinity();
  double domain_hi = std::numeric_limits<double>::infinity();
  double range_lo = -std::numeric_limits<double>::infinity();  // of f
  double range_hi = std::numeric_limits<double>::infinity();
  std::function<double(double)> plain;  // f in double

  // The integrand g is bounded when f is bounded (then Gaussian tails beyond 12 sigma are negligible).
  bool bounded() const { return std::isfinite(range_lo) && std::isfinite(range_hi); }
  bool in_domain(double x) const { return x > domain_lo && x < domain_hi; }
  double g(double s) const {
    if (power == 0) return 1;  // moment of order 0: E[(x+U)^0] = 1
    double f = plain(s), r = f;
    for (int i = 1; i < power; ++i) r *= f;
    return r;
  }
  // Distance from x to the nearest singular point (infinity when there is none).
  double singular_distance(double x) const {
    double r = std::numeric_limits<double>::infinity();
    for (double s : singular) {
      if (period > 0) {
        double k = std::floor((x - s) / period);
        for (double kk : {k - 1, k, k + 1, k + 2}) r = std::fmin(r, std::fabs(x - (s + kk * period)));
      } else {
        r = std::fmin(r, std::fabs(x - s));
      }
    }
    return r;
  }
  // The kernel's scale at (x, sigma): sigma for the Gaussian, the (possibly compact-limited)
  // half-width for box and tent. 0 means "no smoothing": the reference is g(x).
  double scale(double x, double sigma) const {
    if (kernel == Kernel::Gaussian) return sigma;
    double h = support_factor(kernel) * sigma;
    if (compact) h = std::fmin(h, lambda * singular_distance(x));
    return h;
  }
};

}  // namespace blv
