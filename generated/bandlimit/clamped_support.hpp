// Runtime support of the clamped-domain rules (generated/bandlimit/rules_clamped.hpp), copied
// verbatim by `rulegen emit`: truncated-normal moments, Rule 1 (kernel renormalized on a valid
// range, eqs. 5-8 of Li et al. 2020), Rule 3 (second-order Taylor under the truncated normal,
// eqs. 16-20) and the bimodal box truncation at a single jump (Yang & Barnes 2018, 4.6).
// Everything is computed in double (also for float: the tails need double's exponent range).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "emit_helpers.hpp"
#include "support.hpp"

namespace bl {
namespace truncnorm {

// X ~ N(mu, sigma^2) conditioned on a <= X <= b (either bound may be infinite).
template <class T>
struct Moments {
  T mass;  // P(a <= X <= b) (0 when it underflows)
  T mean;  // E[X | a <= X <= b]
  T var;   // central moments of the conditional distribution: E[(X - mean)^k | ...], k = 2, 3, 4
  T mu3;
  T mu4;
};

// The partial moments of eqs. 18-20: int_a^b (u - mu)^k G(u; mu, sigma^2) du, k = 0, 1, 2.
template <class T>
struct Partial {
  T m0, m1, m2;
};

namespace detail {

using bl::detail::kGL20w;
using bl::detail::kGL20x;

inline double nan() {
  return std::numeric_limits<double>::quiet_NaN();
}
inline double inf() {
  return std::numeric_limits<double>::infinity();
}
inline double phi(double z) {
  return std::isinf(z) ? 0.0 : 0.3989422804014327 * std::exp(-0.5 * z * z);
}
inline double z_pow_phi(double z, int k) {  // z^k phi(z), 0 at infinite z
  if (std::isinf(z)) return 0.0;
  double p = phi(z);
  for (int i = 0; i < k; ++i) p *= z;
  return p;
}

// Raw moments v[1..4] -> central moments c[2..4].
inline void central(const double* v, double* c) {
  const double m = v[1];
  c[2] = v[2] - m * m;
  c[3] = v[3] - 3 * m * v[2] + 2 * m * m * m;
  c[4] = v[4] - 4 * m * v[3] + 6 * m * m * v[2] - 3 * m * m * m * m;
  if (c[2] < 0) c[2] = 0;
  if (c[4] < 0) c[4] = 0;
}

// E[t^k | t >= 0], k = 1..4, for the density proportional to phi(al + t), al >= 3: the ratios
// r_k = u_k / u_{k-1} satisfy r_k = k / (al + r_{k+1}) (from phi' = -z phi), a continued fraction
// evaluated backwards. Every term is positive: no cancellation however far the tail. 60 levels
// reach 3e-15 at al = 3 and machine precision beyond 5.
inline void upper_tail(double al, double* u) {
  double r[6] = {0, 0, 0, 0, 0, 0};
  double next = 0;
  for (int k = 60; k >= 1; --k) {
    next = k / (al + next);
    if (k <= 5) r[k] = next;
  }
  u[0] = 1;
  for (int k = 1; k <= 4; ++k) u[k] = u[k - 1] * r[k];
}

// Standard normal Z conditioned on [al, be], al < be. Out: mass, mean, central moments c[2..4].
inline void standard(double al, double be, double* mass, double* mean, double* c) {
  const bool reflect = be < inf() && (al == -inf() || al + be < 0);
  if (reflect) {
    const double t = al;
    al = -be;
    be = -t;
  }
  double v[5] = {1, 0, 0, 0, 0};
  if (al == -inf()) {  // the whole line
    *mass = 1;
    *mean = 0;
    c[2] = 1;
    c[3] = 0;
    c[4] = 3;
    return;
  }
  const double zmin = al > 0 ? al : 0;  // after the reflection be >= |al|
  const double zfar = std::max(std::abs(al), std::abs(be));
  const double drop = 0.5 * (zfar - zmin) * (zfar + zmin);  // log-density drop over the interval
  if (drop <= 4) {
    // Narrow: 20-point Gauss-Legendre of the density relative to its maximum (exact to rounding for
    // a drop this small), central moments summed directly about the mean.
    const double mid = 0.5 * (al + be), half = 0.5 * (be - al);
    double t[20], w[20], s0 = 0, s1 = 0;
    for (int i = 0; i < 10; ++i)
      for (int sgn = -1; sgn <= 1; sgn += 2) {
        const int j = 2 * i + (sgn > 0);
        t[j] = sgn * half * kGL20x[i];
        const double z = mid + t[j];
        w[j] = kGL20w[i] * std::exp(-0.5 * (z - zmin) * (z + zmin));
        s0 += w[j];
        s1 += w[j] * t[j];
      }
    const double mt = s1 / s0;
    double s2 = 0, s3 = 0, s4 = 0;
    for (int j = 0; j < 20; ++j) {
      const double d = t[j] - mt, d2 = d * d;
      s2 += w[j] * d2;
      s3 += w[j] * d2 * d;
      s4 += w[j] * d2 * d2;
    }
    *mass = half * s0 * phi(zmin);
    *mean = mid + mt;
    c[2] = s2 / s0;
    c[3] = s3 / s0;
    c[4] = s4 / s0;
  } else if (al >= 3) {
    // Right tail: moments of t = z - al by the continued fraction, minus the part beyond be.
    double ua[5], ub[5];
    upper_tail(al, ua);
    double q = 0, L = be - al;
    if (be < inf()) {
      upper_tail(be, ub);
      // q = Phic(be) / Phic(al) = phi(be) lambda(al) / (phi(al) lambda(be)), lambda = z + u_1.
      q = std::exp(-L * (al + 0.5 * L)) * (al + ua[1]) / (be + ub[1]);
    }
    for (int k = 1; k <= 4; ++k) {
      double tail = 0;
      if (q > 0) {  // E[(L + t')^k] beyond be
        double binom = 1, Lp = 1;
        for (int j = k; j >= 0; --j) {
          tail += binom * Lp * ub[j];
          binom = binom * j / (k - j + 1);
          Lp *= L;
        }
      }
      v[k] = (ua[k] - q * tail) / (1 - q);
    }
    central(v, c);
    *mass = phi(al) / (al + ua[1]) * (1 - q);
    *mean = al + v[1];
  } else {
    // The interval reaches the bulk: partial moments about 0 (J_k = int z^k phi), erfc on the
    // side where the mass is small.
    const double m = al >= 0
                         ? 0.5 * std::erfc(al / std::sqrt(2.0)) - 0.5 * std::erfc(be / std::sqrt(2.0))
                         : 1 - 0.5 * std::erfc(-al / std::sqrt(2.0)) - 0.5 * std::erfc(be / std::sqrt(2.0));
    double J[5];
    J[0] = m;
    J[1] = phi(al) - phi(be);
    for (int k = 2; k <= 4; ++k) J[k] = (k - 1) * J[k - 2] + z_pow_phi(al, k - 1) - z_pow_phi(be, k - 1);
    for (int k = 1; k <= 4; ++k) v[k] = J[k] / m;
    central(v, c);
    *mass = m;
    *mean = v[1];
  }
  if (reflect) {
    *mean = -*mean;
    c[3] = -c[3];
  }
}

inline Moments<double> moments(double mu, double sigma, double a, double b) {
  const double n = nan();
  if (!(sigma >= 0) || std::isnan(mu) || std::isnan(a) || std::isnan(b) || !(a <= b) || std::isinf(mu))
    return {n, n, n, n, n};
  const double al = (a - mu) / sigma, be = (b - mu) / sigma;
  if (sigma == 0 || a == b || al == be) {
    // Point mass: at mu when it is inside, else at the nearer bound (the sigma -> 0 limit).
    const double m = mu < a ? a : (mu > b ? b : mu);
    return {(mu > a && mu < b) ? 1.0 : (mu == a || mu == b) && a < b ? 0.5 : 0.0, m, 0, 0, 0};
  }
  double mass, mean, c[5];
  standard(al, be, &mass, &mean, c);
  const double s2 = sigma * sigma;
  double m = mu + sigma * mean;
  m = m < a ? a : (m > b ? b : m);  // rounding only
  return {mass, m, s2 * c[2], s2 * sigma * c[3], s2 * s2 * c[4]};
}

}  // namespace detail

// Stable for infinite bounds and bounds far in the tail (no 1 - Phi, no raw moments about 0 there).
template <class T>
Moments<T> moments(T mu, T sigma, T a, T b) {
  const Moments<double> m = detail::moments(double(mu), double(sigma), double(a), double(b));
  return {T(m.mass), T(m.mean), T(m.var), T(m.mu3), T(m.mu4)};
}

// Eqs. 18-20 from the conditional moments (mass * conditional moments about mu).
template <class T>
Partial<T> partial(T mu, T sigma, T a, T b) {
  const Moments<double> m = detail::moments(double(mu), double(sigma), double(a), double(b));
  const double d = m.mean - double(mu);
  return {T(m.mass), T(m.mass * d), T(m.mass * (m.var + d * d))};
}

}  // namespace truncnorm

namespace rule3 {

// Rule 3: f replaced by its second-order Taylor polynomial at the expansion point c, averaged under
// the truncated normal whose conditional moments are m (c = m.mean: the linear term vanishes and c
// lies inside the domain). Y = f0 + f1 E + f2 E^2 / 2 with E = X - c, so
// mean = f0 + f2 var / 2 and Var = f1^2 var + f1 f2 mu3 + f2^2 (mu4 - var^2) / 4 (exact for the polynomial).
template <class T>
stat<T> from_derivatives(T f0, T f1, T f2, const truncnorm::Moments<T>& m) {
  const T mean = f0 + T(0.5) * f2 * m.var;
  if (m.var == T(0)) return {mean, T(0)};  // no spread: avoids 0 * inf from huge derivatives
  T var = f1 * f1 * m.var + f1 * f2 * m.mu3 + T(0.25) * f2 * f2 * (m.mu4 - m.var * m.var);
  if (var < T(0)) var = T(0);
  return {mean, var};
}

// The Taylor polynomial leaves f's range when sigma is large (exp(-|x|) at sigma = 1000: mean
// 1 + sigma^2/2): the true mean lies in [lo, hi] and, when both are finite, the true variance is at
// most (hi - lo)^2/4 (Popoviciu), so the rule is clamped to both (infinite ends clamp nothing).
template <class T>
stat<T> in_range(stat<T> s, T lo, T hi) {
  if (s.mean < lo) s.mean = lo;
  if (s.mean > hi) s.mean = hi;
  const T pop = T(0.25) * (hi - lo) * (hi - lo);
  if (s.var > pop) s.var = pop;
  return s;
}

}  // namespace rule3

namespace rule1 {

enum class Kernel { gaussian, box, tent };

// A kernel (location `center`, standard deviation `sigma` before truncation) restricted to [a, b]
// and renormalized there; `steps`: Newton steps the Gaussian solver used.
template <class T>
struct Params {
  T center;
  T sigma;
  int steps;
};

namespace detail {

using truncnorm::detail::inf;
using truncnorm::detail::nan;

// Variance of the density proportional to e^(k t) on [0, 1] whose mean is t (0 < t < 1): the
// theta_2 -> 0 limit of the truncated Gaussian on a finite interval. k by bisection on the mean
// 1/(1 - e^-k) - 1/k (series near k = 0), then var = 1/k^2 - 1/(4 sinh(k/2)^2).
inline double exp_family_var(double t) {
  auto mean = [](double k) { return std::abs(k) < 1e-3 ? 0.5 + k / 12 : 1 / (-std::expm1(-k)) - 1 / k; };
  double lo = -1e4, hi = 1e4;
  for (int i = 0; i < 200 && hi - lo > 1e-12 * (1 + std::abs(lo)); ++i) {
    const double mid = 0.5 * (lo + hi);
    (mean(mid) < t ? lo : hi) = mid;
  }
  const double k = 0.5 * (lo + hi);
  if (std::abs(k) < 1e-3) return 1.0 / 12 - k * k / 720;
  const double sh = std::sinh(0.5 * k);
  return 1 / (k * k) - 1 / (4 * sh * sh);
}

// The most the variance can be for mean m on [a, b]: at fixed mean a truncated Gaussian has less
// variance than its theta_2 -> 0 limit, the truncated exponential ((m - a)^2 on a half line).
inline double max_var(double m, double a, double b) {
  if (a > -inf() && b < inf()) return (b - a) * (b - a) * exp_family_var((m - a) / (b - a));
  if (a > -inf()) return (m - a) * (m - a);
  if (b < inf()) return (b - m) * (b - m);
  return inf();
}

inline constexpr int kMaxSteps = 40;

// Eq. 8: (center, sigma) of the Gaussian that, truncated to [a, b] and renormalized, has mean m and
// variance v. Newton's method in the natural parameters theta = (c / s^2, -1 / (2 s^2)) of the
// standardized problem (u = (x - m) / sqrt(v)): the moment map is the gradient of the convex
// log-partition function and its Jacobian is the covariance of (u, u^2), computed from the
// truncated moments. Steps leaving theta_2 < 0 are halved. Targets beyond max_var are clamped to
// 0.98 of it (the paper's "valid range"). Stops when both residuals are below 1e-13 (or, never
// seen in the tests, when a step would leave the doubles: the last iterate is returned).
inline Params<double> gaussian(double m, double v, double a, double b) {
  const double n = nan();
  if (!(v >= 0) || std::isnan(m) || !(a <= b) || !(m >= a && m <= b)) return {n, n, 0};
  if (v == 0 || a == b) return {m, 0, 0};
  v = std::min(v, 0.98 * max_var(m, a, b));
  if (!(v > 0)) return {m, 0, 0};  // m at a bound: a point mass
  const double sd = std::sqrt(v);
  const double A = (a - m) / sd, B = (b - m) / sd;
  double t1 = 0, t2 = -0.5;  // start at the untruncated N(0, 1) (the paper's initial guess)
  auto eval = [&](double th1, double th2, double* r, double* J) {
    const double s = std::sqrt(-0.5 / th2), c = th1 * s * s;
    const auto M = truncnorm::detail::moments(c, s, A, B);
    const double e1 = M.mean, k2 = M.var, k3 = M.mu3, k4 = M.mu4;
    r[0] = e1;                // target 0
    r[1] = k2 + e1 * e1 - 1;  // target E u^2 = 1
    if (J) {
      J[0] = k2;
      J[1] = J[2] = k3 + 2 * e1 * k2;
      J[3] = k4 + 4 * e1 * k3 + 4 * e1 * e1 * k2 - k2 * k2;
    }
  };
  int steps = 0;
  double r[2], J[4];
  eval(t1, t2, r, J);
  while (steps < kMaxSteps && !(std::abs(r[0]) < 1e-13 && std::abs(r[1]) < 1e-13)) {
    const double det = J[0] * J[3] - J[1] * J[2];
    double d1 = -(J[3] * r[0] - J[1] * r[1]) / det, d2 = -(-J[2] * r[0] + J[0] * r[1]) / det;
    const double norm0 = std::abs(r[0]) + std::abs(r[1]);
    double rn[2];
    for (int half = 0; half < 30; ++half, d1 *= 0.5, d2 *= 0.5) {
      if (!(t2 + d2 < 0)) continue;
      eval(t1 + d1, t2 + d2, rn, nullptr);
      if (std::abs(rn[0]) + std::abs(rn[1]) < norm0 || half == 29) break;
    }
    double r2[2], J2[4];
    eval(t1 + d1, t2 + d2, r2, J2);
    if (!(std::isfinite(r2[0]) && std::isfinite(r2[1]) && std::isfinite(J2[0]) && std::isfinite(J2[3]))) break;
    t1 += d1;
    t2 += d2;
    ++steps;
    for (int q = 0; q < 4; ++q) J[q] = J2[q];
    r[0] = r2[0];
    r[1] = r2[1];
  }
  const double s = std::sqrt(-0.5 / t2), c = t1 * s * s;
  return {m + sd * c, sd * s, steps};
}

// Box and tent: the symmetric kernel about m with the largest standard deviation <= sqrt(v) that
// fits in [a, b] (a truncated box is again a box: its mean and variance match only when it fits).
inline Params<double> compact(Kernel k, double m, double v, double a, double b) {
  const double n = nan();
  if (!(v >= 0) || std::isnan(m) || !(a <= b) || !(m >= a && m <= b)) return {n, n, 0};
  const double c = k == Kernel::box ? std::sqrt(3.0) : std::sqrt(6.0);  // half-width / sigma
  const double h = std::min(c * std::sqrt(v), std::min(m - a, b - m));
  return {m, h / c, 0};
}

// tanh-sinh nodes on [l, r] (h = 1/8, |t| <= 3.25): integrand evaluated at the offsets from the
// nearer end computed without rounding to the end itself (endpoint singularities of log, sqrt).
template <class F>
void tanh_sinh(double l, double r, F&& visit) {
  const double hpi = 1.5707963267948966, h = 0.125, width = r - l;
  for (int k = -26; k <= 26; ++k) {
    const double t = k * h, s = hpi * std::sinh(t), e = std::exp(-2 * std::abs(s));
    const double off = width * e / (1 + e);  // distance to the nearer end
    const double u = k < 0 ? l + off : r - off;
    const double ch = std::cosh(s);
    const double w = h * 0.5 * width * hpi * std::cosh(t) / (ch * ch);
    if (off > 0 && u > l && u < r) visit(u, w);
  }
}

}  // namespace detail

// Eq. 8 / eqs. 5-7: the kernel renormalized on [a, b] whose mean is m and variance v (box and tent:
// as close to v as fits).
template <class T>
Params<T> renormalize(Kernel k, T m, T v, T a, T b) {
  const Params<double> p = k == Kernel::gaussian
                               ? detail::gaussian(double(m), double(v), double(a), double(b))
                               : detail::compact(k, double(m), double(v), double(a), double(b));
  return {T(p.center), T(p.sigma), p.steps};
}

// Mean and variance of g(X) for X the kernel p restricted to [a, b] and renormalized (eqs. 3-4),
// by tanh-sinh quadrature on pieces (below). Two passes: the variance is summed about the
// mean, so it does not cancel when it is tiny.
template <class T, class G>
stat<T> expect(Kernel k, const Params<T>& p, T a, T b, G&& g) {
  const double c = double(p.center), s = double(p.sigma), n = detail::nan();
  if (std::isnan(c) || !(s >= 0)) return {T(n), T(n)};
  if (s == 0) return {T(g(T(c))), T(0)};
  // Support: the kernel's; for the Gaussian, where the density exceeds e^-40 of its maximum on
  // [a, b] (at z_m, the point of [a, b] nearest the centre in z = (u - c) / s). The density is taken
  // relative to that maximum, so a centre far outside [a, b] (a clamped renormalization) does not
  // underflow.
  const double A = (double(a) - c) / s, B = (double(b) - c) / s;
  const double zm = std::min(std::max(0.0, A), B);
  const double reach = k == Kernel::gaussian ? std::sqrt(zm * zm + 80)
                                             : (k == Kernel::box ? std::sqrt(3.0) : std::sqrt(6.0));
  const double l = std::max(double(a), c - reach * s), r = std::min(double(b), c + reach * s);
  if (!(l <= r)) return {T(n), T(n)};
  if (l == r) return {T(g(T(l))), T(0)};  // the support rounds to one point: a point mass
  auto density = [&](double u) {
    const double z = (u - c) / s;
    if (k == Kernel::gaussian) return std::exp(-0.5 * (z - zm) * (z + zm));
    if (k == Kernel::box) return 1.0;
    return std::max(0.0, 1 - std::abs(z) / std::sqrt(6.0));
  };
  double ws[318], gs[318];
  int cnt = 0;
  auto collect = [&](double u, double w) {
    ws[cnt] = w * density(u);
    gs[cnt] = double(g(T(u)));
    ++cnt;
  };
  // Pieces: split at the centre (kink of the tent) and, for the Gaussian, where the density has
  // dropped by e^-4 and e^-12 from z_m on either side; on each piece tanh-sinh reaches ~1e-13.
  double inner[5] = {c, c, c, c, c};
  if (k == Kernel::gaussian)
    for (int i = 0; i < 2; ++i) {
      const double z = std::sqrt(zm * zm + (i == 0 ? 8.0 : 24.0));
      inner[1 + 2 * i] = c + z * s;
      inner[2 + 2 * i] = c - z * s;
    }
  std::sort(inner, inner + 5);
  double cuts[7] = {l};
  int nc = 1;
  for (double v : inner)
    if (v > cuts[nc - 1] && v < r) cuts[nc++] = v;
  cuts[nc++] = r;
  for (int i = 0; i + 1 < nc; ++i) detail::tanh_sinh(cuts[i], cuts[i + 1], collect);
  double s0 = 0, s1 = 0;
  for (int i = 0; i < cnt; ++i) {
    s0 += ws[i];
    s1 += ws[i] * gs[i];
  }
  // A support narrower than the spacing of doubles near it (a point mass at a bound: centre 0.5 on
  // [0, 0.5], sigma 1e-16) leaves no node strictly inside: the renormalized kernel is that point.
  if (!(s0 > 0)) return {T(g(T(0.5 * (l + r)))), T(0)};
  const double mean = s1 / s0;
  double s2 = 0;
  for (int i = 0; i < cnt; ++i) s2 += ws[i] * (gs[i] - mean) * (gs[i] - mean);
  return {T(mean), T(s2 / s0)};
}

}  // namespace rule1

namespace bimodal {

// Yang & Barnes 2018, 4.6: when the box footprint [mu - sqrt(3) sigma, mu + sqrt(3) sigma] of the
// input contains exactly one jump of f, the box is cut at the jump and the side holding mu is kept
// (mu on the jump: the right side, f being right-continuous). Otherwise the plain box convolution.
// Jumps at jumps[i] + k period (period 0: not repeating). box_f, box_f_sq: the table's box entries.
template <class T, class F, class G>
stat<T> truncated_box(T mu, T sigma, double period, const double* jumps, int njumps, F&& box_f,
                      G&& box_f_sq) {
  using std::floor;
  using std::sqrt;
  if (!(sigma >= T(0)) || mu != mu) return {bl::detail::nan<T>(), bl::detail::nan<T>()};
  if (sigma == T(0)) return {box_f(mu, T(0)), T(0)};
  const T h = T(1.7320508075688772) * sigma, lo = mu - h, hi = mu + h;
  int count = 0;
  T at = T(0);
  for (int i = 0; i < njumps && count < 2; ++i) {
    if (period > 0) {
      const T P = T(period), j = T(jumps[i]);
      const T kh = floor((hi - j) / P), kl = floor((lo - j) / P);
      count += static_cast<int>(kh - kl);
      if (kh > kl) at = j + P * kh;
    } else if (lo < T(jumps[i]) && T(jumps[i]) <= hi) {
      ++count;
      at = T(jumps[i]);
    }
  }
  T c = mu, s = sigma;
  if (count == 1) {
    const T l = mu >= at ? at : lo, r = mu >= at ? hi : at;
    c = T(0.5) * (l + r);
    s = (r - l) / (T(2) * T(1.7320508075688772));
  }
  const T m = box_f(c, s);
  T v = box_f_sq(c, s) - m * m;
  if (v < T(0)) v = T(0);
  return {m, v};
}

}  // namespace bimodal

namespace compact {

// Yang & Barnes 2018, 4.6: the compact kernel's half-width near a singularity at distance r.
inline constexpr double kLambda = 0.5;
template <class T>
T halfwidth(T h, T r) {
  return T(kLambda) * r < h ? T(kLambda) * r : h;
}

}  // namespace compact
}  // namespace bl
