// Small helpers the generated table uses besides support.hpp (copied verbatim by `rulegen emit`).
#pragma once

#include <cmath>
#include <limits>
#if defined(__SSE2__)
#include <immintrin.h>
#endif

// Unqualified math calls in generated code resolve to std:: for float/double and, by ADL, to the
// multiprecision library's overloads when the verifier instantiates the table at 50 digits.
#define BL_MATH_USING  \
  using std::abs;      \
  using std::atan;     \
  using std::copysign; \
  using std::cos;      \
  using std::cosh;     \
  using std::exp;      \
  using std::expm1;    \
  using std::floor;    \
  using std::log;      \
  using std::rint;     \
  using std::sin;      \
  using std::sinh;     \
  using std::sqrt;     \
  using std::tan;      \
  using std::tanh;

// The general body of an entry whose pixel-sized path is inlined into the shader stays a call.
#if defined(__GNUC__) || defined(__clang__)
#define BL_NOINLINE __attribute__((noinline))
#elif defined(_MSC_VER)
#define BL_NOINLINE __declspec(noinline)
#else
#define BL_NOINLINE
#endif

namespace bl {

// Output of a rule that yields a distribution rather than one smoothed value (Rules 1-3, mode fit,
// bivariate operators): mean and variance of Y. Inputs of those rules are (mean, standard deviation).
template <class T>
struct stat {
  T mean;
  T var;
};

namespace detail {

// The type a float computation borrows where float's exponent range is too small (Taylor
// coefficients near singularities); other types use themselves.
template <class T>
struct wide {
  using type = T;
};
template <>
struct wide<float> {
  using type = double;
};
template <class T>
using wide_t = typename wide<T>::type;

template <class T>
T nan() {
  return T(std::numeric_limits<double>::quiet_NaN());
}
// v^4 as two squarings: the Gaussian sin^2 / cos^2 entries' e^{-2 sigma^2} = (e^{-sigma^2/2})^4,
// one exp shared with the same node's sin / cos entry.
template <class T>
inline T pow4(T v) {
  const T v2 = v * v;
  return v2 * v2;
}
// pi in the precision of T (atan folds to a constant for float and double).
template <class T>
T pi() {
  using std::atan;
  return T(4) * atan(T(1));
}
// Up to which hh / scale the antiderivative rules use their 7-term Taylor series instead of the
// difference quotient: the series' truncation error is about (hh/scale)^14, the quotient's rounding
// error about eps |F| / (hh |f|) (eps |F2| / (hh^2 |f|) for the tent). 0.05 keeps both below 1e-13
// in double; float needs the longer reach (0.35^14 = 4e-7 < 2e-5).
template <class T>
T series_reach() {
  return std::numeric_limits<T>::digits <= 24 ? T(0.35) : T(0.05);
}
// Clausen's function Cl2(t) = -int_0^t log|2 sin(u/2)| du (second antiderivative of tan): odd,
// 2 pi-periodic; on [-pi, pi] t - t log|t| + sum_k c_k t^{2k+1}, c_k = |B_2k| / (2k (2k+1)!)
// (computed by GiNaC; the ratio of terms is at most (t / 2 pi)^2 <= 1/4 there: 30 terms reach
// 1e-18 of the leading one, double precision; a 50-digit evaluation is limited to that).
template <class T>
T clausen2(T t) {
  using std::abs;
  using std::floor;
  using std::log;
  static constexpr double c[] = {
      0.013888888888888888,   6.9444444444444444e-05, 7.873519778281683e-07,  1.1482216343327455e-08,
      1.8978869988970999e-10, 3.3873013709535212e-12, 6.3726364431831808e-14, 1.2462059912950672e-15,
      2.5105444608999545e-17, 5.1782588060906232e-19, 1.0887357368300849e-20, 2.3257441143020871e-22,
      5.0351952131473897e-24, 1.1026499294381215e-25, 2.4386585509007344e-27, 5.4401426788562527e-29,
      1.2228340131217352e-30, 2.7672634689679508e-32, 6.3000905918320136e-34, 1.4420868388418476e-35,
      3.3170939991595428e-37, 7.6639135579206584e-39, 1.7778714733830659e-40, 4.1396058982341375e-42,
      9.6715570360811023e-44, 2.2667187016766123e-45, 5.3279563113282542e-47, 1.2557248389564336e-48,
      2.9670005422470941e-50, 7.0267873176007424e-52};
  const T two_pi = T(2) * pi<T>();
  const T r = t - two_pi * floor((t + pi<T>()) / two_pi);
  if (r == T(0)) return T(0);
  // Two independent Horner chains in r^4 (even and odd k): half the latency of one chain of 30
  // dependent steps (tent/tan calls this three times per value); the terms are all positive.
  const T r2 = r * r, r4 = r2 * r2;
  T se = T(c[28]), so = T(c[29]);
  for (int k = 26; k >= 0; k -= 2) {
    se = se * r4 + T(c[k]);
    so = so * r4 + T(c[k + 1]);
  }
  return r - r * log(abs(r)) + r * r2 * (se + r2 * so);
}

// Dilogarithm Li2(z) for z <= 0 (second antiderivative of tanh): the power series for
// |z| <= 1/2; Landen's identity Li2(z) = -Li2(z/(z-1)) - log(1-z)^2 / 2 for z in [-1, -1/2)
// (z/(z-1) in (1/3, 1/2]); the inversion Li2(z) = -pi^2/6 - log(-z)^2 / 2 - Li2(1/z) below -1.
// At most 60 terms of ratio <= 1/2.
template <class T>
T li2_series(T y) {
  using std::abs;
  T sum = T(0), p = y;
  // |y| <= 1/2 (li2's own arguments): the tail after term k is at most 2 |y|^(k+1)/(k+1)^2, so
  // stop once that is below eps |sum| (~45 terms in double, ~20 in float at |y| = 1/2, fewer
  // for small |y|: tanh's -exp(-2|x|)).
  const bool fast = abs(y) <= T(0.5);
  const T tol = std::numeric_limits<T>::epsilon() * T(0.5);
  for (int k = 1; k <= 60; ++k) {
    sum += p / T(k * k);
    p *= y;
    if (fast && T(2) * abs(p) <= tol * abs(sum) * T((k + 1) * (k + 1))) break;
  }
  return sum;
}
// Float and double on z in [-1, 1/2]: the Bernoulli series Li2(z) = sum_n B_n u^(n+1)/(n+1)!,
// u = -log(1 - z) (|u| <= log 2), i.e. u (1 - u/4 + sum_k c_2k u^2k) with c_2k = B_2k/(2k+1)!,
// |c_2k| ~ 2 (2 pi)^-2k: through c_18 the first neglected term is < 1e-20 relative, and u (1 - u/4
// + ...) has no cancellation for |u| < 1. One log1p and 9 multiply-adds in place of up to 45
// divisions of the power series (which made double tent/tanh 2.2x float's cost).
template <class T>
T li2_bernoulli(T z) {
  using std::log1p;
  const T u = -log1p(-z), u2 = u * u;
  T s = T(4.518980029619918e-16);
  s = s * u2 + T(-1.9939295860721074e-14);
  s = s * u2 + T(8.921691020456452e-13);
  s = s * u2 + T(-4.0647616451442256e-11);
  s = s * u2 + T(1.8978869988971e-09);
  s = s * u2 + T(-9.185773074661964e-08);
  s = s * u2 + T(4.72411186696901e-06);
  s = s * u2 + T(-0.0002777777777777778);
  s = s * u2 + T(0.027777777777777776);
  return u * (T(1) - T(0.25) * u + u2 * s);
}
template <class T>
T li2(T z) {
  using std::log;
  if (z < T(-1)) {
    const T l = log(-z);
    return -pi<T>() * pi<T>() / T(6) - l * l / T(2) - li2(T(1) / z);
  }
  if constexpr (std::numeric_limits<T>::digits <= 53) {
    if (z <= T(0.5)) return li2_bernoulli(z);
  }
  if (z >= T(-0.5)) return li2_series(z);
  const T l = log(T(1) - z);
  return -li2_series(z / (z - T(1))) - l * l / T(2);
}

// a * b with 0 * anything = 0: sinh(0) times a kernel factor that overflowed.
template <class T>
T prod0(T a, T b) {
  return a == T(0) ? T(0) : a * b;
}
template <class T>
T sgn(T x) {
  return x > T(0) ? T(1) : (x < T(0) ? T(-1) : T(0));
}

template <class T>
T min2(T a, T b) {
  return b < a ? b : a;
}

// max(v, 0) and min(v, 1) as the selects v > 0 ? v : 0 and v < 1 ? v : 1 (the same values, NaN
// included: maxss/minss return their second operand then, as the selects do), without a branch:
// GCC compiles such a select in a pixel-sized path to a conditional jump, mispredicted on the
// random side of a break a pixel falls on (box fract 0.8 ns per call at |x| ~ 10, 1.4 at |x| ~ 1).
template <class T>
T max0(T v) {
  return v > T(0) ? v : T(0);
}
template <class T>
T min1(T v) {
  return v < T(1) ? v : T(1);
}
#if defined(__SSE2__)
template <>
inline float max0<float>(float v) {
  return _mm_cvtss_f32(_mm_max_ss(_mm_set_ss(v), _mm_setzero_ps()));
}
template <>
inline double max0<double>(double v) {
  return _mm_cvtsd_f64(_mm_max_sd(_mm_set_sd(v), _mm_setzero_pd()));
}
template <>
inline float min1<float>(float v) {
  return _mm_cvtss_f32(_mm_min_ss(_mm_set_ss(v), _mm_set_ss(1.0f)));
}
template <>
inline double min1<double>(double v) {
  return _mm_cvtsd_f64(_mm_min_sd(_mm_set_sd(v), _mm_set_sd(1.0)));
}
#endif

// The stat entries' return (their GLSL twin is vec2(mean, var)).
template <class T>
stat<T> make_stat(T mean, T var) {
  return {mean, var};
}

}  // namespace detail
}  // namespace bl
