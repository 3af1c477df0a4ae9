// blverify: the double-precision reference E[g(x + U)] by Boost.Math quadrature.
//
//  - sigma = 0 (or a compact half-width of 0): g(x).
//  - Gaussian: t = u / sigma over [-12, 12]; for unbounded g also 12..40 unless the integrand is
//    negligible there (probes out to 40 * 2^24 sigma guard exp-like growth).
//  - Box / tent: t = u / half-width over [-1, 1] (tent: also split at its kink t = 0).
//  - Every range is split at every break (period repeats included) and at s = 0, +-1, +-2, +-4, ..
//    (features the catalog may not list: tanh's step, smoothstep's kinks). Each piece is mapped to
//    [-1, 1] for tanh_sinh (Boost 1.74 loses accuracy on short intervals far from 0); pieces wider
//    than 2 units of s are cross-checked by adaptive Gauss-Kronrod, cut into parts when the two
//    disagree, and reported unresolved when they still do (tanh_sinh's own error estimate misses
//    unresolved oscillation).
//  - Period > 0 and more than 40 periods under the kernel: a period model. The integrals of g and
//    of tau g, tau^2 g over period k (k T + tau, tau in [0, T)) are fitted as quadratics in k from
//    k = 0, 1, 2 (and separately k = -1, -2, -3), and the fit is checked at k = 3 and at far k
//    (10 .. 4e6 / T): periodic f gives constants, floor-like f linear, their squares quadratics.
//    Then
//      Gaussian, f periodic:  a0 + sum_n exp(-2 pi^2 n^2 sigma^2 / T^2) (a_n cos + b_n sin),
//                             coefficients by quadrature over one period, until terms < 1e-19;
//      Gaussian, otherwise:   the same mean over a period of the quadratic-in-s model;
//      box / tent:            whole periods summed in closed form (power sums of k) plus the
//                             partial periods at both ends by quadrature.
//    f with a different structure on each side of 0 (trunc) gets direct quadrature up to 4000
//    pieces; beyond, a piecewise-constant g (trunc^2 = floor(|s|)^2) gets the exact sum of its
//    jumps times Gaussian tail probabilities (erfc), else no reference.
#pragma once

#include <memory>
#include <string>

#include "spec.hpp"

namespace blv {

constexpr double kGaussWindow = 12;      // Gaussian window for bounded integrands (units of sigma)
constexpr double kGaussWindowWide = 40;  // for unbounded integrands
constexpr double kManyPeriods = 40;      // beyond this many periods under the kernel: period model

struct Ref {
  bool ok = false;
  double value = std::numeric_limits<double>::quiet_NaN();
  double err = 0;          // absolute error estimate (sum over the quadrature pieces)
  double l1 = 0;           // integral of |integrand|: rounding error ~ eps * l1 (cancellation)
  double sens = 0;         // rounding sensitivity of g over the support: max |g(s+ulp) - g(s)|
  std::string why;         // when !ok
  std::string method;      // point | direct | fourier | period-mean | period-sum
  long pieces = 0;
};

class RefEngine {
 public:
  explicit RefEngine(const Spec& spec);
  ~RefEngine();
  RefEngine(const RefEngine&) = delete;
  RefEngine& operator=(const RefEngine&) = delete;

  Ref at(double x, double sigma);        // E[g(x + U)], U the spec's kernel at sigma
  std::string period_model_summary();    // empty when no period model was needed
  // The spec the references use: the entry's, except that a bounded, break-free f that the catalog
  // gives no period is tested for the periods 2 pi, pi, 1, 2 (g(s + T) = g(s) to 1e-12 at 40 points
  // from -1e6 to 1e6); one that passes is used (the Fourier reference needs it for large sigma).
  const Spec& effective_spec() const;
  std::string inferred_period_note() const;  // empty when the catalog's period was used

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace blv
