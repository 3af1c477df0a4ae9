// bandlimit runtime support: numerically stable building blocks that the generated table calls.
// Copied verbatim into generated/bandlimit/support.hpp by `rulegen emit`. Header-only, C++17,
// no dependency beyond <cmath>/<limits>/<cstdint>. Every routine is a template over the scalar T
// (float, double, boost::multiprecision::cpp_bin_float_50): math functions are called unqualified
// after `using std::...` so ADL finds Boost's overloads, and float stays float throughout (the
// float result is what a GPU computes; rulegen/templates/support.glsl is the same code in GLSL).
//
// Conventions (shared with ../shared/DESIGN.md):
//   sigma >= 0 is the kernel's standard deviation. Gaussian: N(0, sigma^2).
//   Box: U[-h, h], h = sqrt(3) sigma. Tent: triangle on [-w, w], w = sqrt(6) sigma,
//   density (w - |u|) / w^2. kernel(x, sigma) = E[f(x + U)].
//   sigma == 0 returns f(x) (right-continuous at a jump: the piece whose [lo, hi) contains x).
//   A polynomial piece is f(t) = sum_k c[k] t^k on [lo, hi) in the *absolute* coordinate t;
//   lo may be -inf and hi +inf (std::numeric_limits<T>::infinity()).
//
// Internally every per-piece primitive works on the *offsets* of the piece ends from the kernel
// centre (dl = lo - x, dh = hi - x) and keeps the polynomial in its own coordinate. The periodic
// routines shift whole periods by computing (lo + m T) - x_r, which is exact or nearly so, instead
// of x_r - m T, whose rounding (eps T) would be divided by a tiny kernel width.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

namespace bl {
namespace detail {

inline constexpr int kMaxCoef = 8;  // polynomial pieces have degree <= 7

template <class T>
struct Piece {
  T lo;
  T hi;
  T c[kMaxCoef];
};

template <class T>
constexpr T inf() {
  return std::numeric_limits<T>::infinity();
}

// Truncation tolerance the series/sums aim for: 1e-13 in double, 1e-8 in float.
template <class T>
constexpr T series_tol() {
  return sizeof(T) >= 8 ? T(1e-13) : T(1e-8);
}

// ---------------------------------------------------------------------------------------------
// Constants. For float/double a rounded double literal (folded at compile time); for wider types
// computed in T so that multiprecision evaluation is not limited to double accuracy.
template <class T>
inline constexpr bool kWide = (std::numeric_limits<T>::digits > 53);

template <class T>
inline T k_pi() {
  using std::acos;
  if constexpr (kWide<T>)
    return acos(T(-1));
  else
    return T(3.141592653589793238462643);
}
template <class T>
inline T k_inv_sqrt2() {  // 1/sqrt(2)
  using std::sqrt;
  if constexpr (kWide<T>)
    return T(1) / sqrt(T(2));
  else
    return T(0.7071067811865475244008444);
}
template <class T>
inline T k_inv_sqrt_2pi() {  // 1/sqrt(2 pi)
  using std::sqrt;
  if constexpr (kWide<T>)
    return T(1) / sqrt(T(2) * k_pi<T>());
  else
    return T(0.3989422804014326779399461);
}
template <class T>
inline T k_sqrt3() {
  using std::sqrt;
  if constexpr (kWide<T>)
    return sqrt(T(3));
  else
    return T(1.732050807568877293527446);
}
template <class T>
inline T k_sqrt6() {
  using std::sqrt;
  if constexpr (kWide<T>)
    return sqrt(T(6));
  else
    return T(2.449489742783178098197284);
}
template <class T>
inline T k_ln2() {
  using std::log;
  if constexpr (kWide<T>)
    return log(T(2));
  else
    return T(0.6931471805599453094172321);
}

template <class T>
inline T min_of(T a, T b) {
  return b < a ? b : a;
}
template <class T>
inline T abs_of(T a) {
  return a < T(0) ? -a : a;
}

// Threshold below which the 5-term Taylor series of sin(t)/t or sinh(t)/t (up to t^8) is exact to
// rounding: the first neglected term t^10/11! must be below eps.
template <class T>
inline T small_series_limit() {
  using std::pow;
  if constexpr (std::numeric_limits<T>::digits <= 24) {
    return T(0.5);  // 0.5^10 / 11! = 2.4e-11 < float eps
  } else if constexpr (std::numeric_limits<T>::digits <= 53) {
    return T(0.1);  // 0.1^10 / 11! = 2.5e-18 < double eps
  } else {
    static const T lim = pow(T(39916800) * std::numeric_limits<T>::epsilon(), T(1) / T(10));
    return lim;
  }
}

// 1/n for n < 256 as constants (float and double): a series or moment term then costs a multiply,
// not a division (whose latency, on the term-to-term chains of the box/tent sums, dominated them).
struct RecipTable {
  double v[256];
  constexpr RecipTable() : v() {
    for (int n = 1; n < 256; ++n) v[n] = 1.0 / n;
  }
};
inline constexpr RecipTable kRecip{};
template <class T>
inline T recip(int n) {
  if constexpr (kWide<T>)
    return T(1) / T(n);
  else
    return n < 256 ? T(kRecip.v[n]) : T(1) / T(n);
}

// Highest index with a nonzero coefficient (0 for the zero polynomial). Loops stop there so that
// 0 * sigma^7 never turns into 0 * inf = NaN.
template <class T>
inline int degree(const T* c) {
  int d = kMaxCoef - 1;
  while (d > 0 && c[d] == T(0)) --d;
  return d;
}

// g[k] = q^(k)(t0) / k! (Taylor coefficients about t0), by repeated synthetic division: O(deg^2)
// multiply-adds, no powers of t0 formed separately. c and g hold kMaxCoef entries; all are copied
// (g[k] = c[k] above deg): a fixed-size copy is a few vector moves, whereas a copy of deg + 1
// entries became `rep movsq` in double with GCC -O3 (tens of cycles to start, and the loads
// after it cannot be forwarded from its stores) and made double tent entries 2.5-3.5x float's.
template <class T>
inline void taylor_shift(const T* c, int deg, T t0, T* g) {
  for (int k = 0; k < kMaxCoef; ++k) g[k] = c[k];
  if (t0 == T(0)) return;
  for (int i = 0; i < deg; ++i)
    for (int j = deg - 1; j >= i; --j) g[j] += t0 * g[j + 1];
}

// ---------------------------------------------------------------------------------------------
// Scalar helpers

// Horner: one rounding per coefficient, the standard stable evaluation.
template <class T>
inline T poly(const T* c, T t) {
  T r = c[kMaxCoef - 1];
  for (int k = kMaxCoef - 2; k >= 0; --k) r = r * t + c[k];
  return r;
}

// Standard normal pdf. exp(-z^2/2) underflows to 0 (never NaN) for huge or infinite |z|.
template <class T>
inline T phi(T z) {
  using std::exp;
  return k_inv_sqrt_2pi<T>() * exp(-(z * z) * T(0.5));
}

// Float erfcx(t) = e^{t^2} erfc(t), t >= 0, without a transcendental call: (1 + 2t) erfcx(t) is a
// degree-10 polynomial in q = (t - 2)/(t + 2) = 1 - 4/(t + 2) in [-1, 1] (Chebyshev fit, the form of
// N. Juffa's erfcf; q = 1 at t = inf gives 0). Relative error < 4e-7 for every t >= 0 in float
// up to 1e37 (support_test: against long double erfc on a dense grid and at hard points).
inline float erfcx_f(float t) {
  const float q = 1.0f - 4.0f / (t + 2.0f);
  float p = 0.000165867576f;
  p = p * q - 0.000182478019f;
  p = p * q - 0.00140835776f;
  p = p * q + 0.0010404808f;
  p = p * q + 0.00870021712f;
  p = p * q - 0.0079407068f;
  p = p * q - 0.0542159006f;
  p = p * q + 0.164035276f;
  p = p * q - 0.166030601f;
  p = p * q - 0.0927630365f;
  p = p * q + 1.27697837f;
  return p / (2.0f * t + 1.0f);
}

// Float erfc(y) = erfcx(|y|) e^{-y^2}; y^2 = h + l split exactly, e^{-y^2} = e^{-h} (1 - l), so
// the rounding of y^2 (up to 100 ulp of e^{-y^2} near y = 10) does not enter. Relative error < 6e-7
// for y >= 0 (absolute < 3e-7 for y < 0). l is formed in double: a^2 is exact there (48 bits) and so
// is a^2 - h, so l is fma(a, a, -h) to the bit, without the libm call fmaf is on hardware without
// FMA (the x86-64 baseline: it made float gauss_pw ~2x slower).
inline float erfc_f(float y) {
  using std::exp;
  const float a = abs_of(y);
  const float h = a * a, l = static_cast<float>(double(a) * double(a) - double(h));
  float r = erfcx_f(a) * exp(-h) * (1.0f - l);
  if (a > 10.1f) r = 0.0f;  // erfc(10.1) < 1e-45 (and a^2 may be inf, l NaN)
  return y < 0.0f ? 2.0f - r : r;
}

// Phi and its complement through erfc of the side where the result is small, so both tails keep
// full relative accuracy (1 - erf would cancel).
template <class T>
inline T Phi(T z) {
  using std::erfc;
  if constexpr (std::is_same<T, float>::value) return 0.5f * erfc_f(-z * k_inv_sqrt2<T>());
  return T(0.5) * erfc(-z * k_inv_sqrt2<T>());
}
template <class T>
inline T Phic(T z) {
  using std::erfc;
  if constexpr (std::is_same<T, float>::value) return 0.5f * erfc_f(z * k_inv_sqrt2<T>());
  return T(0.5) * erfc(z * k_inv_sqrt2<T>());
}

// phi(t) and Phic(t) for t >= 0 from one exp in float (Phic = phi sqrt(pi/2) erfcx(t/sqrt2)); the
// generated Gaussian piecewise entries take one of these per break.
template <class T>
inline void phi_Phic(T t, T& ph, T& pc) {
  ph = phi(t);
  if constexpr (std::is_same<T, float>::value)
    pc = ph * 1.25331414f * erfcx_f(t * k_inv_sqrt2<T>());
  else
    pc = Phic(t);
}

// Phic(t), t >= 0, alone (a break whose jump is a constant needs no phi): float through phi_Phic
// (one exp and a polynomial erfcx: cheaper than erfc_f, whose fma is a call without FMA hardware),
// double one erfc and no exp.
template <class T>
inline T Phic_tail(T t) {
  if constexpr (std::is_same<T, float>::value) {
    T ph, pc;
    phi_Phic(t, ph, pc);
    return pc;
  } else {
    return Phic(t);
  }
}

// Breaks farther than this many sd from x are skipped by the generated Gaussian piecewise entries:
// their term is below |e_k| sigma^k k! phi(t)/t^(k+1), phi(9) = 1e-18 (float), phi(12) = 2e-32
// (double); wider types keep 40.
template <class T>
inline T tail_cut() {
  return kWide<T> ? T(40) : sizeof(T) < sizeof(double) ? T(9) : T(12);
}

// max(x, lo) as a select the compiler keeps branch-free (maxss / maxsd): the generated Fourier
// regimes floor their damping factors at lo so that no product turns subnormal.
template <class T>
inline T at_least(T x, T lo) {
  return x < lo ? lo : x;
}

// sin(t)/t: Taylor series near 0 (exactly 1 at 0, no 0/0), the quotient elsewhere.
template <class T>
inline T sinc(T t) {
  using std::sin;
  if (abs_of(t) < small_series_limit<T>()) {
    T t2 = t * t;
    return T(1) + t2 * (T(-1) / T(6) +
                        t2 * (T(1) / T(120) + t2 * (T(-1) / T(5040) + t2 * (T(1) / T(362880)))));
  }
  return sin(t) / t;
}

// sinh(t)/t: series near 0, the quotient for moderate |t|, and exp(|t| - log 2|t|) (1 - e^{-2|t|})
// beyond, which stays finite past the point where sinh(t) alone overflows; +inf when the true
// value overflows, never inf/inf.
template <class T>
inline T sinhc(T t) {
  using std::exp;
  using std::expm1;
  using std::log;
  using std::sinh;
  T a = abs_of(t);
  if (a < small_series_limit<T>()) {
    T t2 = t * t;
    return T(1) + t2 * (T(1) / T(6) +
                        t2 * (T(1) / T(120) + t2 * (T(1) / T(5040) + t2 * (T(1) / T(362880)))));
  }
  if (a < T(40)) return sinh(a) / a;
  if (a == inf<T>()) return inf<T>();
  return exp(a - log(T(2) * a)) * (-expm1(T(-2) * a));
}

// exp(u) sinhc(v), v >= 0 (the sign of v is ignored: sinhc is even). For v > 1 the exponentials
// are merged, exp(u + v - log 2v) (1 - e^{-2v}), so e.g. u = -800, v = 800 gives 1/1600 instead
// of 0 * inf.
template <class T>
inline T exp_sinhc(T u, T v) {
  using std::exp;
  using std::expm1;
  using std::log;
  v = abs_of(v);
  if (!(v > T(1))) return exp(u) * sinhc(v);
  if (v == inf<T>()) return u == -inf<T>() ? T(0) : inf<T>();
  return exp(u + v - log(T(2) * v)) * (-expm1(T(-2) * v));
}

// exp(u) sinhc(v)^2, same merging: exp(u + 2v - 2 log 2v) (1 - e^{-2v})^2.
template <class T>
inline T exp_sinhc2(T u, T v) {
  using std::exp;
  using std::expm1;
  using std::log;
  v = abs_of(v);
  if (!(v > T(1))) {
    T s = sinhc(v);
    return exp(u) * s * s;
  }
  if (v == inf<T>()) return u == -inf<T>() ? T(0) : inf<T>();
  T e = -expm1(T(-2) * v);
  return exp(u + T(2) * v - T(2) * log(T(2) * v)) * e * e;
}

// log(cosh x). |x| >= 1: |x| + log1p(e^{-2|x|}) - log 2 (no overflow of cosh, no cancellation since
// |x| - log 2 > 0.3). |x| < 1: log1p(2 sinh^2(x/2)) = log1p(cosh x - 1), full relative accuracy
// near 0 where the first form would cancel to an absolute error of eps.
template <class T>
inline T logcosh(T x) {
  using std::exp;
  using std::log1p;
  using std::sinh;
  T a = abs_of(x);
  if (a < T(1)) {
    T s = sinh(T(0.5) * a);
    return log1p(T(2) * s * s);
  }
  return a + log1p(exp(T(-2) * a)) - k_ln2<T>();
}

// ---------------------------------------------------------------------------------------------
// Gauss-Legendre rule for narrow Gaussian pieces. float/double: 20 points (embedded; exact for the
// degree-7 polynomial times a degree-32 Taylor polynomial of the Gaussian factor). Wider types:
// 48 points computed once by Newton's method in T, so multiprecision keeps its accuracy.
inline constexpr double kGL20x[10] = {
    0.076526521133497338, 0.22778585114164507, 0.37370608871541955, 0.51086700195082713,
    0.63605368072651502,  0.7463319064601508,  0.83911697182221878, 0.91223442825132595,
    0.96397192727791381,  0.99312859918509488};
inline constexpr double kGL20w[10] = {
    0.15275338713072584,  0.14917298647260374, 0.14209610931838204,  0.13168863844917664,
    0.11819453196151841,  0.10193011981724044, 0.083276741576704755, 0.062672048334109068,
    0.040601429800386939, 0.017614007139152118};

template <class T, bool Wide = kWide<T>>
struct GaussLegendre {
  static constexpr int kHalf = 10;
  static T x(int i) { return T(kGL20x[i]); }
  static T w(int i) { return T(kGL20w[i]); }
};

template <class T>
struct GaussLegendre<T, true> {
  static constexpr int kHalf = 24;
  struct Table {
    T x[kHalf];
    T w[kHalf];
  };
  static const Table& table() {
    static const Table t = make();
    return t;
  }
  static Table make() {
    using std::abs;
    using std::cos;
    const int n = 2 * kHalf;
    Table t;
    // P_n(x) by the three-term recurrence; returns P_n, sets dp = P_n'(x).
    auto legendre = [n](const T& x, T& dp) {
      T p0 = T(1), p1 = x;
      for (int k = 2; k <= n; ++k) {
        T p2 = (T(2 * k - 1) * x * p1 - T(k - 1) * p0) / T(k);
        p0 = p1;
        p1 = p2;
      }
      dp = T(n) * (x * p1 - p0) / (x * x - T(1));
      return p1;
    };
    for (int i = 0; i < kHalf; ++i) {
      // Newton from the classical cos((i + 3/4) pi / (n + 1/2)) guess (quadratic convergence).
      T x = cos(k_pi<T>() * (T(i) + T(0.75)) / (T(n) + T(0.5))), dp;
      for (int it = 0; it < 100; ++it) {
        const T dx = legendre(x, dp) / dp;
        x -= dx;
        if (abs(dx) <= T(4) * std::numeric_limits<T>::epsilon()) break;
      }
      legendre(x, dp);
      t.x[i] = x;
      t.w[i] = T(2) / ((T(1) - x * x) * dp * dp);
    }
    return t;
  }
  static T x(int i) { return table().x[i]; }
  static T w(int i) { return table().w[i]; }
};

// U[k] = int_t^inf z^k phi(z) dz for t >= 0 (t may be +inf), k <= deg, by the upper-tail
// recursion U_k = t^{k-1} phi(t) + (k-1) U_{k-2}, U_0 = Phic(t), U_1 = phi(t). For t >= 0 every
// term is positive, so the recursion never cancels; t^{k-1} phi(t) is built as phi(t) t t ..., so
// an underflowed phi stays 0 instead of 0 * inf.
template <class T>
inline void upper_moments(T t, int deg, T* U) {
  if (t == inf<T>()) {
    for (int k = 0; k <= deg; ++k) U[k] = T(0);
    return;
  }
  T e = phi(t);
  U[0] = Phic(t);
  if (deg >= 1) U[1] = e;
  for (int k = 2; k <= deg; ++k) {
    e *= t;
    U[k] = e + T(k - 1) * U[k - 2];
  }
}

// Tail moments U_k(|t|) at one piece end, shared by the two pieces that meet there (gauss_pw):
// each finite break then costs one erfc and one exp, not two of each. deg < 0: not computed yet.
template <class T>
struct EndTails {
  int deg = -1;
  T U[kMaxCoef];
};

// U_k(t) for k <= deg (t >= 0), from the cache when it holds them (it is filled with cache_deg >= deg).
template <class T>
inline const T* end_tails(T t, int deg, EndTails<T>* cache, int cache_deg, T* local) {
  if (!cache) {
    upper_moments(t, deg, local);
    return local;
  }
  if (cache->deg < deg) {
    upper_moments(t, cache_deg, cache->U);
    cache->deg = cache_deg;
  }
  return cache->U;
}

// Core of gauss_piece on offsets: the piece [lo, hi) lies at [x + dl, x + dh) relative to the
// kernel centre, xq is the centre in the polynomial's own coordinate.
template <class T>
inline T gauss_core(T xq, T sigma, T dl, T dh, T lo, T hi, const T* c, EndTails<T>* cl = nullptr,
                    EndTails<T>* ch = nullptr, int cache_deg = kMaxCoef - 1) {
  const int deg = degree(c);
  if (!(hi > lo) || (deg == 0 && c[0] == T(0))) return T(0);  // empty piece or f = 0 on it
  const T a = dl / sigma, b = dh / sigma;                     // alpha, beta (possibly infinite)
  const T width = hi - lo;
  if (width < inf<T>()) {
    // A bounded piece 40 sd or more from the centre carries less than Phic(40) ~ 4e-350 of the
    // mass: 0 in double. Skipping it also keeps the Taylor shift about a huge x (x^7 overflows
    // float at |x| ~ 3e5) from turning a negligible piece into inf - inf.
    if (a >= T(40) || b <= T(-40)) return T(0);
    // Narrow piece (<= 2 standard deviations wide) not deep in a tail: the moment recursion would
    // subtract O(1) tail integrals to get an O(width/sigma) result while d_k ~ sigma^k, so use
    // Gauss-Legendre on q(t) phi((t - x)/sigma) directly. The Gaussian factor varies like
    // exp(-cz hw s), s in [-1, 1]; with |cz| hw <= 10 the 20-point rule is exact to rounding.
    const T hw = width / (T(2) * sigma);
    const T cz = (dl + dh) / (T(2) * sigma);
    if (hw <= T(1) && abs_of(cz) * hw <= T(10)) {
      using GL = GaussLegendre<T>;
      const T mid = (lo + hi) / T(2), half = width / T(2);
      T s = T(0);
      for (int i = 0; i < GL::kHalf; ++i) {
        const T xi = GL::x(i);
        s += GL::w(i) * (poly(c, mid + half * xi) * phi(cz + hw * xi) +
                         poly(c, mid - half * xi) * phi(cz - hw * xi));
      }
      return hw * s;
    }
  }
  // Wide piece (or narrow deep in a tail): q(x + sigma z) = sum d_k z^k, d_k = q^(k)(x) sigma^k/k!,
  // against the partial moments I_k = int_a^b z^k phi. Each I_k comes from tails evaluated at
  // non-negative arguments: straddling 0 it is m_k - tail_left - tail_right (full moment minus
  // two tails, no cancellation of nearly equal numbers), otherwise the difference of two tails on
  // the side of the interval, whose ratio is small once the interval is wider than 2 sd or deep
  // in a tail. Limitation: a piece many sd away (result < ~1e-15 of the scale) keeps absolute,
  // not relative, accuracy: the Taylor terms about x are then much larger than q on the piece.
  T g[kMaxCoef];
  taylor_shift(c, deg, xq, g);
  T La[kMaxCoef], Lb[kMaxCoef];
  T sum = T(0), sk = T(1);
  if (a < T(0) && b > T(0)) {
    const T* Ua = end_tails(-a, deg, cl, cache_deg, La);
    const T* Ub = end_tails(b, deg, ch, cache_deg, Lb);
    T m[kMaxCoef];  // full moments: m_0 = 1, m_1 = 0, m_k = (k-1) m_{k-2}
    for (int k = 0; k <= deg; ++k) {
      m[k] = k == 0 ? T(1) : (k == 1 ? T(0) : T(k - 1) * m[k - 2]);
      const T Ik = m[k] - ((k & 1) ? -Ua[k] : Ua[k]) - Ub[k];
      if (g[k] != T(0)) sum += g[k] * sk * Ik;
      if (k < deg) sk *= sigma;
    }
    return sum;
  }
  if (a >= T(0)) {
    const T* Ua = end_tails(a, deg, cl, cache_deg, La);
    const T* Ub = end_tails(b, deg, ch, cache_deg, Lb);
    for (int k = 0; k <= deg; ++k) {
      if (g[k] != T(0)) sum += g[k] * sk * (Ua[k] - Ub[k]);
      if (k < deg) sk *= sigma;
    }
    return sum;
  }
  // b <= 0: mirror, I_k = (-1)^k (U_k(-b) - U_k(-a)).
  const T* Ub = end_tails(-b, deg, ch, cache_deg, Lb);
  const T* Ua = end_tails(-a, deg, cl, cache_deg, La);
  for (int k = 0; k <= deg; ++k) {
    const T Ik = Ub[k] - Ua[k];
    if (g[k] != T(0)) sum += g[k] * sk * ((k & 1) ? -Ik : Ik);
    if (k < deg) sk *= sigma;
  }
  return sum;
}

// Core of box_piece on offsets. The covered length is formed from offsets (h - dl, dh + h, 2h,
// hi - lo), never as a difference of the rounded ends x +- h, so it survives |x| >> h; the mean of
// t^k over [a, b] uses the divided difference S_k = sum_j a^j b^{k-j} (S_k = b S_{k-1} + a^k),
// which has no 1/(b - a).
template <class T>
inline T box_core(T xq, T h, T dl, T dh, T lo, T hi, const T* c) {
  if (!(dl < h) || !(dh > -h)) return T(0);
  const bool cl = dl > -h, cr = dh < h;
  const T a = cl ? lo : xq - h;
  const T b = cr ? hi : xq + h;
  const T len = cl ? (cr ? hi - lo : h - dl) : (cr ? dh + h : T(2) * h);
  const int deg = degree(c);
  T S = T(1), ak = T(1), mean = c[0];
  for (int k = 1; k <= deg; ++k) {
    ak *= a;
    S = b * S + ak;
    mean += c[k] * S * recip<T>(k + 1);
  }
  return len / (T(2) * h) * mean;
}

// One side of the tent: int_0^L q(t0 + s v) (G - v) dv / w^2, s = +1 (right) or -1 (left), where
// t0 is the end of the integration interval nearest the kernel centre and G the distance from t0
// to the support edge (G >= L). Expanding q about t0 keeps every term local to the interval:
// sum_k g_k s^k L^k (L/w) (G/w/(k+1) - L/w/(k+2)); the bracket is >= (L/w)/((k+1)(k+2)), so it
// does not cancel, and nothing is divided by a tiny w beyond the ratios L/w, G/w <= 1.
template <class T>
inline T tent_side(const T* c, int deg, T t0, T G, T L, T w, bool left) {
  T g[kMaxCoef];
  taylor_shift(c, deg, t0, g);
  const T ell = L / w, gam = G / w;
  T sum = T(0), Lk = T(1);
  for (int k = 0; k <= deg; ++k) {
    if (g[k] != T(0)) {
      T term = g[k] * Lk * (gam * recip<T>(k + 1) - ell * recip<T>(k + 2));
      sum += (left && (k & 1)) ? -term : term;
    }
    if (k < deg) Lk *= L;
  }
  return sum * ell;
}

// Core of tent_piece on offsets: split at the kernel centre, each side handled by tent_side.
template <class T>
inline T tent_core(T xq, T w, T dl, T dh, T lo, T hi, const T* c) {
  if (!(dl < w) || !(dh > -w)) return T(0);
  const int deg = degree(c);
  T r = T(0);
  if (dh > T(0)) {  // right half: t in [max(lo, x), min(hi, x + w)]
    if (dl > T(0)) {
      const T G = w - dl;
      r += tent_side(c, deg, lo, G, min_of(hi - lo, G), w, false);
    } else {
      r += tent_side(c, deg, xq, w, min_of(dh, w), w, false);
    }
  }
  if (dl < T(0)) {  // left half: t in [max(lo, x - w), min(hi, x)]
    if (dh < T(0)) {
      const T G = w + dh;
      r += tent_side(c, deg, hi, G, min_of(hi - lo, G), w, true);
    } else {
      r += tent_side(c, deg, xq, w, min_of(-dl, w), w, true);
    }
  }
  return r;
}

// ---------------------------------------------------------------------------------------------
// Per-piece primitives (public).

// int_lo^hi q(t) phi((t - mu)/sigma)/sigma dt, sigma > 0. See gauss_core for the two regimes.
template <class T>
inline T gauss_piece(T mu, T sigma, T lo, T hi, const T* c) {
  return gauss_core(mu, sigma, lo - mu, hi - mu, lo, hi, c);
}

// (1/2h) int over [lo, hi) cap [x - h, x + h] of q. See box_core.
template <class T>
inline T box_piece(T x, T h, T lo, T hi, const T* c) {
  return box_core(x, h, lo - x, hi - x, lo, hi, c);
}

// int over [lo, hi) cap [x - w, x + w] of q(t) (w - |t - x|)/w^2. See tent_core.
template <class T>
inline T tent_piece(T x, T w, T lo, T hi, const T* c) {
  return tent_core(x, w, lo - x, hi - x, lo, hi, c);
}

// ---------------------------------------------------------------------------------------------
// Whole-line piecewise polynomials (sorted contiguous pieces, first lo = -inf, last hi = +inf).

// Right-continuous: the piece whose [lo, hi) contains x.
template <class T, int N>
inline T pw_eval(T x, const Piece<T> (&p)[N]) {
  for (int i = 0; i < N - 1; ++i)
    if (x < p[i].hi) return poly(p[i].c, x);
  return poly(p[N - 1].c, x);
}

// J-weighted tail sum of one break: sum_k e_k step^k J_k(t), J_k(t) = int_t^inf (z - t)^k phi(z) dz
// (see gauss_pw_breaks below), e the jump polynomial about the break, step = +-sigma.
template <class T>
inline T break_tail(const T* e, int dd, T t, T step) {
  T U[kMaxCoef];
  upper_moments(t, dd, U);
  T s = T(0), sk = T(1);
  for (int k = 0; k <= dd; ++k) {
    if (e[k] != T(0)) {
      T J = T(0), binom = T(1), tp = T(1);
      for (int m = k; m >= 0; --m) {
        J += binom * tp * U[m];
        binom = binom * T(m) / T(k - m + 1);
        tp *= -t;
      }
      s += e[k] * sk * J;
    }
    if (k < dd) sk *= step;
  }
  return s;
}

// Break decomposition. With j the piece containing x,
//   f = q_j + sum_{i >= j} (q_{i+1} - q_i) 1{y >= b_i} + sum_{i < j} (q_i - q_{i+1}) 1{y < b_i},
// so E f(x+U) = E q_j(x+U) (the exact polynomial moment sum_k g_k sigma^k m_k, m_k = (k-1)!!) plus
// one tail per break on its far side from x: t = |b - x|/sigma >= 0, D(b + s sigma v) = sum_k e_k
// (s sigma)^k v^k (s = +1 right of x, -1 left), and
//   E[D(x+U) 1{far side}] = sum_k e_k (s sigma)^k J_k(t),  J_k(t) = int_t^inf (z - t)^k phi(z) dz
//                         = sum_m C(k, m) (-t)^(k-m) U_m(t)   (U: upper_moments, t >= 0).
// One erfc and one exp per break within 40 sd (the others carry < Phic(40): 0 in double); the
// difference is expanded about the fixed break, never about a huge x. Each term is at most
// |e_k| sigma^k (k-1)!! ~ max|f| when sigma is at most the narrowest bounded piece, so nothing
// cancels beyond O(max|f| eps) there; gauss_pw takes the per-piece form for wider kernels.
template <class T, int N>
inline T gauss_pw_breaks(T x, T sigma, const Piece<T> (&p)[N]) {
  int j = N - 1;
  for (int i = 0; i < N - 1; ++i)
    if (x < p[i].hi) {
      j = i;
      break;
    }
  T g[kMaxCoef];
  const int dj = degree(p[j].c);
  taylor_shift(p[j].c, dj, x, g);
  T s = g[0];
  T s2k = T(1), mk = T(1);
  for (int k = 2; k <= dj; k += 2) {
    s2k *= sigma * sigma;
    mk *= T(k - 1);
    if (g[k] != T(0)) s += g[k] * s2k * mk;
  }
  for (int i = 0; i < N - 1; ++i) {
    const bool right = i >= j;
    const T b = p[i].hi;
    const T t = right ? (b - x) / sigma : (x - b) / sigma;
    if (!(t < T(40))) continue;
    T dc[kMaxCoef];
    for (int k = 0; k < kMaxCoef; ++k) dc[k] = right ? p[i + 1].c[k] - p[i].c[k] : p[i].c[k] - p[i + 1].c[k];
    const int dd = degree(dc);
    if (dd == 0 && dc[0] == T(0)) continue;  // f continuous and smooth there
    T e[kMaxCoef];
    taylor_shift(dc, dd, b, e);
    s += break_tail(e, dd, t, right ? sigma : -sigma);
  }
  return s;
}

// The pieces are contiguous (p[i].hi == p[i+1].lo), so both pieces at a break see the same
// |t| = |b - x|/sigma: its tail moments are computed once (EndTails), up to the highest degree.
// sigma at most the narrowest bounded piece (always, for a single break): gauss_pw_breaks.
template <class T, int N>
inline T gauss_pw(T x, T sigma, const Piece<T> (&p)[N]) {
  if (sigma == T(0)) return pw_eval(x, p);
  T wmin = inf<T>();
  int maxdeg = 0;
  for (int i = 0; i < N; ++i) {
    if (i > 0 && i < N - 1) wmin = min_of(wmin, p[i].hi - p[i].lo);
    maxdeg = degree(p[i].c) > maxdeg ? degree(p[i].c) : maxdeg;
  }
  // Degree > 3 (smoothstep^2: |e_6| 5!! = 60) keeps the terms small only for sigma <= width/4.
  if (sigma <= (maxdeg <= 3 ? wmin : T(0.25) * wmin)) return gauss_pw_breaks(x, sigma, p);
  EndTails<T> ends[N > 1 ? N - 1 : 1];
  T s = T(0);
  for (int i = 0; i < N; ++i)
    s += gauss_core(x, sigma, p[i].lo - x, p[i].hi - x, p[i].lo, p[i].hi, p[i].c,
                    i > 0 ? &ends[i - 1] : nullptr, i < N - 1 ? &ends[i] : nullptr, maxdeg);
  return s;
}

// Only pieces meeting the support [x - h, x + h] are integrated (sorted: stop at the first piece
// beyond it).
template <class T, int N>
inline T box_pw(T x, T sigma, const Piece<T> (&p)[N]) {
  if (sigma == T(0)) return pw_eval(x, p);
  const T h = k_sqrt3<T>() * sigma;
  T s = T(0);
  for (int i = 0; i < N; ++i) {
    const T dl = p[i].lo - x, dh = p[i].hi - x;
    if (!(dh > -h)) continue;
    if (!(dl < h)) break;
    s += box_core(x, h, dl, dh, p[i].lo, p[i].hi, p[i].c);
  }
  return s;
}

template <class T, int N>
inline T tent_pw(T x, T sigma, const Piece<T> (&p)[N]) {
  if (sigma == T(0)) return pw_eval(x, p);
  const T w = k_sqrt6<T>() * sigma;
  T s = T(0);
  for (int i = 0; i < N; ++i) {
    const T dl = p[i].lo - x, dh = p[i].hi - x;
    if (!(dh > -w)) continue;
    if (!(dl < w)) break;
    s += tent_core(x, w, dl, dh, p[i].lo, p[i].hi, p[i].c);
  }
  return s;
}

// ---------------------------------------------------------------------------------------------
// Exp-polynomial terms (piecewise exp-polynomial atomics and x^n e^{ax} in the entire class).
// A term is f(t) = e^{a s} sum_k c[k] s^k, s = t - ref, on [lo, hi); ref is a finite end of the
// interval (0 for a whole-line term), so on a piece that decays towards an infinite end e^{a s} <= 1.
// A piece of the catalog is a sum of such terms, one per rate a. Every routine below works on
// offsets from the kernel centre, as the polynomial primitives above, and never forms e^{a s} and a
// Gaussian or 1/h factor separately where one of them could overflow while the product is finite.
template <class T>
struct ExpTerm {
  T lo;
  T hi;
  T a;
  T ref;
  T c[kMaxCoef];
};

// erfcx(t) = e^{t^2} erfc(t), t >= 0 (the scaled complementary error function; finite for all t,
// ~ 1/(t sqrt(pi)) for large t). Float: erfcx_f; double: below. Wider types: the product up to
// t = 1000 (erfc has full relative accuracy, e^{t^2} carries the rounding of t^2), then the continued
// fraction 1/sqrt(pi) / (t + (1/2)/(t + 1/(t + (3/2)/(t + ...)))) cut after 30 levels.
template <class T>
inline T erfcx(T t) {
  using std::erfc;
  using std::exp;
  if (t < T(0)) return T(2) * exp(t * t) - erfcx(-t);
  if constexpr (std::is_same<T, float>::value) return erfcx_f(t);
  if constexpr (!kWide<T>) {
    // double: t^2 = h + l exactly (fma), so e^{t^2} = e^h (1 + l) carries no rounding of t^2, up to
    // t = 6.5; beyond, the fraction with the fewest levels that keeps it < 3e-16 (measured against
    // 400 levels in long double: 12 from 6.2, 8 from 10.4, 6 from 17.2, 4 from 41.5).
    using std::fma;
    if (t < T(6.5)) {
      const T h = t * t, l = fma(t, t, -h);
      return exp(h) * (T(1) + l) * erfc(t);
    }
    const int n = t >= T(42) ? 4 : t >= T(18) ? 6 : t >= T(11) ? 8 : 12;
    T f = t;
    for (int k = n; k >= 1; --k) f = t + T(k) * T(0.5) / f;
    return T(0.5641895835477563) / f;
  }
  if (t < T(3) || (kWide<T> && t < T(1000))) return exp(t * t) * erfc(t);
  T f = t;
  for (int k = 30; k >= 1; --k) f = t + T(k) * T(0.5) / f;
  return T(0.5641895835477563) / f;  // 1/sqrt(pi)
}

// e^{lw} U_k(t), U_k(t) = int_t^inf z^k phi(z) dz (upper_moments), t >= 0, with the scale folded in:
// e^{lw} U_0 = erfcx(t/sqrt2)/2 e^{lw - t^2/2} and e^{lw} phi(t) = e^{lw - t^2/2}/sqrt(2 pi). The
// caller passes lwt = lw - t^2/2, formed without overflow (a huge e^{lw} times an underflowing tail).
template <class T>
inline void upper_moments_scaled(T t, T lwt, int deg, T* U) {
  using std::exp;
  if (t == inf<T>()) {
    for (int k = 0; k <= deg; ++k) U[k] = T(0);
    return;
  }
  const T e0 = exp(lwt);
  T e = k_inv_sqrt_2pi<T>() * e0;
  U[0] = T(0.5) * erfcx(t * k_inv_sqrt2<T>()) * e0;
  if (deg >= 1) U[1] = e;
  for (int k = 2; k <= deg; ++k) {
    e *= t;
    U[k] = e + T(k - 1) * U[k - 2];
  }
}

// V_k(al) = int_0^inf u^k e^{-al u - u^2/2} du, al >= 0, k <= deg (the Gaussian tail seen from a
// piece end). V_0 = sqrt(pi/2) erfcx(al/sqrt2); the recurrence V_{k+1} = k V_{k-1} - al V_k is
// stable upwards only for small al (it loses a factor ~ al^2/k per step): al < 2 uses it (< 11x
// lost in total for k <= 8); al >= 2 takes the ratios r_k = V_{k-1}/V_k from Miller's backward
// recurrence r_k = (1/r_{k+1} + al)/k started at K (V dominates downwards), then V_k = V_{k-1}/r_k.
// Started at the fixed point of s = K/(s + al) (its value for large K), K = deg + n(al) levels
// suffice (measured against 400 levels in long double, k <= 7, one level of margin added): relative
// error < 2e-15 in double, < 1e-7 in float; each level costs a division.
template <class T>
inline int miller_start(T al, int deg) {
  if constexpr (kWide<T>) return al < T(5) ? 150 : 40;  // as before: multiprecision keeps its levels
  if (sizeof(T) < sizeof(double))
    return deg + (al < T(3)    ? 24
                  : al < T(4)  ? 16
                  : al < T(5)  ? 12
                  : al < T(6)  ? 10
                  : al < T(8)  ? 8
                  : al < T(12) ? 7
                  : al < T(20) ? 5
                  : al < T(30) ? 4
                               : 3);
  return deg + (al < T(3)    ? 87
                : al < T(4)  ? 50
                : al < T(5)  ? 35
                : al < T(6)  ? 27
                : al < T(8)  ? 22
                : al < T(12) ? 17
                : al < T(20) ? 12
                : al < T(30) ? 9
                             : 8);
}
template <class T>
inline void tail_laplace(T al, int deg, T* V) {
  using std::sqrt;
  V[0] = T(1.2533141373155003) * erfcx(al * k_inv_sqrt2<T>());  // sqrt(pi/2)
  if (deg == 0) return;
  // Upwards also in double for deg <= 3 below al = 5: it loses al^(2k)/k! <= 2604 (3e-13).
  const bool up = al < T(2) || (!kWide<T> && sizeof(T) >= sizeof(double) && deg <= 3 && al < T(5));
  if (up) {
    V[1] = T(1) - al * V[0];
    for (int k = 1; k < deg; ++k) V[k + 1] = T(k) * V[k - 1] - al * V[k];
    return;
  }
  // s_k = 1/r_k = k/(s_{k+1} + al): one division per level.
  using std::sqrt;
  const int K = miller_start(al, deg);
  T sk = kWide<T> ? T(K) / al : T(2 * K) / (al + sqrt(al * al + T(4 * K))), inv[kMaxCoef + 1];
  for (int k = K - 1; k >= 1; --k) {
    sk = T(k) / (sk + al);
    if (k <= deg) inv[k] = sk;
  }
  for (int k = 1; k <= deg; ++k) V[k] = V[k - 1] * inv[k];
}

// I_k = int_0^L v^k e^{-b v} dv, k <= deg, b >= 0, L >= 0 (L = inf needs b > 0). With y = b L, the
// top moment K = deg first: y < 2(K+1): the series L^{K+1} e^{-y} sum_n y^n / ((K+1)(K+2)...(K+1+n))
// (positive terms; exact as b -> 0, where it is L^{K+1}/(K+1)); otherwise K!/b^{K+1} (1 - e^{-y}
// sum_{j<=K} y^j/j!), whose bracket is >= 1 - e^{-2} there (no cancellation). The lower ones by
// integration by parts run downwards, I_{k-1} = (b I_k + L^k e^{-y})/k: two non-negative terms, so
// no cancellation either (a few eps in total), and one series per call instead of one per k.
template <class T>
inline void exp_moments(T L, T b, int deg, T* I, T ey) {  // ey = e^{-b L}
  const T y = b * L;
  const int K = deg;
  if (y < T(2 * (K + 1))) {
    T term = recip<T>(K + 1), sum = term;
    for (int n = 1; n < 200; ++n) {
      term *= y * recip<T>(K + 1 + n);
      sum += term;
      if (term <= std::numeric_limits<T>::epsilon() * T(0.25) * sum) break;
    }
    T LK1 = L;  // L^{K+1}
    for (int k = 0; k < K; ++k) LK1 *= L;
    I[K] = LK1 * ey * sum;
  } else {
    T kfact = T(1), bk1 = b;  // K!, b^{K+1}
    for (int k = 1; k <= K; ++k) {
      kfact *= T(k);
      bk1 *= b;
    }
    if (ey == T(0)) {  // y beyond exp's range (also y = inf): the bracket is 1
      I[K] = kfact / bk1;
    } else {
      T term = T(1), sum = T(1);
      for (int j = 1; j <= K; ++j) {
        term *= y * recip<T>(j);
        sum += term;
      }
      I[K] = kfact / bk1 * (T(1) - ey * sum);
    }
  }
  if (K == 0) return;
  // L^k e^{-y} for k = K..1, from L^K down (ey = 0: the boundary term vanishes, also for L = inf).
  T Lk[kMaxCoef + 1];
  Lk[0] = T(1);
  for (int k = 1; k <= K; ++k) Lk[k] = Lk[k - 1] * L;
  for (int k = K; k >= 1; --k) {
    const T boundary = ey == T(0) ? T(0) : Lk[k] * ey;
    I[k - 1] = (b * I[k] + boundary) * recip<T>(k);
  }
}

template <class T>
inline void exp_moments(T L, T b, int deg, T* I) {
  using std::exp;
  exp_moments(L, b, deg, I, exp(-(b * L)));
}

// e^{pre} s / d without overflowing where the product is finite (pre large, d large).
template <class T>
inline T exp_scaled(T pre, T s, T d) {
  using std::exp;
  using std::log;
  if (pre < T(30)) return exp(pre) * s / d;
  return exp(pre - log(d)) * s;
}

// sum_k g_k dir^k int_0^len v^k (G + sw v) e^{-b v} dv (G = 1, sw = 0 for the box).
// ey = e^{-b len}.
template <class T>
inline T exp_side(const T* c, int deg, T s0, T dir, T len, T b, T G, T sw, T ey) {
  T g[kMaxCoef], I[kMaxCoef + 1];
  taylor_shift(c, deg, s0, g);
  exp_moments(len, b, sw != T(0) ? deg + 1 : deg, I, ey);
  T sum = T(0), dk = T(1);
  for (int k = 0; k <= deg; ++k) {
    if (g[k] != T(0)) sum += g[k] * dk * (sw != T(0) ? G * I[k] + sw * I[k + 1] : I[k]);
    dk *= dir;
  }
  return sum;
}

// Value of the terms at x (sigma = 0): the terms whose [lo, hi) contains x.
template <class T, int N>
inline T ept_eval(T x, const ExpTerm<T> (&p)[N]) {
  using std::exp;
  T s = T(0);
  for (int i = 0; i < N; ++i)
    if (p[i].lo <= x && x < p[i].hi) {
      const T u = x - p[i].ref;
      const T e = exp(p[i].a * u);
      if (e != T(0)) s += poly(p[i].c, u) * e;  // an underflowed e^{a u} at huge u: 0, not inf * 0
    }
  return s;
}

// Gaussian of one term. Completing the square, e^{a s} phi_sigma(t - x) = e^{a (x - ref) + a^2
// sigma^2/2} phi_sigma(t - mu), mu = x + a sigma^2: the polynomial's truncated-normal moments about
// the shifted centre mu. Three regimes by alpha = (lo - mu)/sigma, beta = (hi - mu)/sigma:
//  * narrow piece near mu (width <= 2 sigma): 20-point Gauss-Legendre on the integrand with its
//    exponent a s - (t - x)^2/(2 sigma^2) formed as one number;
//  * mu inside or within 2 sigma of the piece: Taylor of q about mu against the moments, full
//    moments and tails scaled by e^{a (x - ref) + a^2 sigma^2/2} inside their exponentials
//    (upper_moments_scaled), so nothing overflows when the true value is finite;
//  * the piece >= 2 sigma beyond mu (large sigma, or far from the piece): Taylor of q about each
//    finite end E against V_k(|E - mu|/sigma) (tail_laplace), with the factor e^{a (E - ref) - (E -
//    x)^2/(2 sigma^2)}: the value of the integrand at E. Expanding about mu here would cancel by
//    ~alpha^(2 deg) (the ramp x e^{-x} at sigma = 1e4 in float).
template <class T>
inline T gauss_exp_term(T x, T sigma, const ExpTerm<T>& p) {
  using std::exp;
  if (!(p.hi > p.lo)) return T(0);
  const int deg = degree(p.c);
  const T a = p.a;
  const T el = p.lo - x, eh = p.hi - x;
  const T as2 = a * sigma * sigma;
  const T fl = el - as2, fh = eh - as2;  // ends relative to mu
  auto lw_at = [&](T E, T e) {           // a (E - ref) - (E - x)^2 / (2 sigma^2)
    const T z = e / sigma;
    return a * (E - p.ref) - T(0.5) * z * z;
  };
  const T two_sigma = T(2) * sigma;
  if (fl >= two_sigma || fh <= -two_sigma) {
    const bool right = fl >= two_sigma;
    auto end = [&](T E, T e, T f) {
      const T al = (right ? f : -f) / sigma;
      T g[kMaxCoef], V[kMaxCoef];
      taylor_shift(p.c, deg, E - p.ref, g);
      tail_laplace(al, deg, V);
      T s = T(0), sk = T(1);
      const T step = right ? sigma : -sigma;
      for (int k = 0; k <= deg; ++k) {
        if (g[k] != T(0)) s += g[k] * sk * V[k];
        sk *= step;
      }
      return k_inv_sqrt_2pi<T>() * exp(lw_at(E, e)) * s;
    };
    if (right) return end(p.lo, el, fl) - (p.hi < inf<T>() ? end(p.hi, eh, fh) : T(0));
    return end(p.hi, eh, fh) - (p.lo > -inf<T>() ? end(p.lo, el, fl) : T(0));
  }
  const T width = p.hi - p.lo;
  if (width < inf<T>()) {
    const T hw = width / two_sigma, cz = (fl + fh) / two_sigma;
    if (hw <= T(1) && abs_of(cz) * hw <= T(10)) {
      using GL = GaussLegendre<T>;
      const T half = width / T(2);
      const T sm = ((p.lo - p.ref) + (p.hi - p.ref)) / T(2), em = (el + eh) / T(2);
      auto f = [&](T xi) {
        const T z = (em + half * xi) / sigma;
        return poly(p.c, sm + half * xi) * exp(a * (sm + half * xi) - T(0.5) * z * z);
      };
      T s = T(0);
      for (int i = 0; i < GL::kHalf; ++i) s += GL::w(i) * (f(GL::x(i)) + f(-GL::x(i)));
      return hw * k_inv_sqrt_2pi<T>() * s;
    }
  }
  T g[kMaxCoef];
  taylor_shift(p.c, deg, (x - p.ref) + as2, g);
  const T L = a * (x - p.ref) + T(0.5) * a * as2;  // log of the completed-square factor
  const T al = fl / sigma, be = fh / sigma;
  T Ua[kMaxCoef], Ub[kMaxCoef];
  T sum = T(0), sk = T(1);
  if (al < T(0) && be > T(0)) {
    upper_moments_scaled(-al, p.lo > -inf<T>() ? lw_at(p.lo, el) : T(0), deg, Ua);
    upper_moments_scaled(be, p.hi < inf<T>() ? lw_at(p.hi, eh) : T(0), deg, Ub);
    const T eL = exp(L);
    T mk[kMaxCoef];  // full moments: m_0 = 1, m_1 = 0, m_k = (k-1) m_{k-2}
    for (int k = 0; k <= deg; ++k) {
      mk[k] = k == 0 ? T(1) : (k == 1 ? T(0) : T(k - 1) * mk[k - 2]);
      const T Ik = eL * mk[k] - ((k & 1) ? -Ua[k] : Ua[k]) - Ub[k];
      if (g[k] != T(0)) sum += g[k] * sk * Ik;
      if (k < deg) sk *= sigma;
    }
    return sum;
  }
  if (al >= T(0)) {
    upper_moments_scaled(al, lw_at(p.lo, el), deg, Ua);
    upper_moments_scaled(be, p.hi < inf<T>() ? lw_at(p.hi, eh) : T(0), deg, Ub);
    for (int k = 0; k <= deg; ++k) {
      if (g[k] != T(0)) sum += g[k] * sk * (Ua[k] - Ub[k]);
      if (k < deg) sk *= sigma;
    }
    return sum;
  }
  upper_moments_scaled(-be, lw_at(p.hi, eh), deg, Ub);
  upper_moments_scaled(-al, p.lo > -inf<T>() ? lw_at(p.lo, el) : T(0), deg, Ua);
  for (int k = 0; k <= deg; ++k) {
    const T Ik = Ub[k] - Ua[k];
    if (g[k] != T(0)) sum += g[k] * sk * ((k & 1) ? -Ik : Ik);
    if (k < deg) sk *= sigma;
  }
  return sum;
}

// Box of one term: (1/2h) int over [lo, hi) cap [x - h, x + h] of f, expanded about the end of the
// covered interval where e^{a s} is largest (a <= 0: the left end, else the right end), so the
// exponential seen from there decays, e^{-|a| v}, and exp_moments integrates it without cancelling
// (tiny h: its series is exact to rounding). The covered length comes from offsets, as in box_core.
template <class T>
inline T box_exp_term(T x, T h, const ExpTerm<T>& p) {
  const T el = p.lo - x, eh = p.hi - x;
  if (!(el < h) || !(eh > -h) || !(p.hi > p.lo)) return T(0);
  const bool cl = el > -h, cr = eh < h;
  const T len = cl ? (cr ? p.hi - p.lo : h - el) : (cr ? eh + h : T(2) * h);
  const int deg = degree(p.c);
  const bool left = !(p.a > T(0));
  const T s0 = left ? (cl ? p.lo - p.ref : (x - p.ref) - h) : (cr ? p.hi - p.ref : (x - p.ref) + h);
  const T b = abs_of(p.a);
  const T sum = exp_side(p.c, deg, s0, left ? T(1) : T(-1), len, b, T(1), T(0), T(exp(-(b * len))));
  return exp_scaled(p.a * s0, sum, T(2) * h);
}

// Tent of one term: split at the kernel centre; each half is int of f times the linear weight
// (w - |t - x|)/w^2, expanded about the end where e^{a s} is largest, as for the box; the weight
// there is G + sw v with G >= 0 and, for sw = -1, G >= the length (the integrand stays >= 0 where f
// does: G I_k - I_{k+1} loses at most a factor k + 2).
template <class T>
inline T tent_exp_term(T x, T w, const ExpTerm<T>& p) {
  using std::exp;
  const T el = p.lo - x, eh = p.hi - x;
  if (!(el < w) || !(eh > -w) || !(p.hi > p.lo)) return T(0);
  const int deg = degree(p.c);
  const bool left_anchor = !(p.a > T(0));
  const T b = abs_of(p.a), dir = left_anchor ? T(1) : T(-1);
  const T xr = x - p.ref;
  // One half [o0, o1] (offsets from x); e0/e1: whether o0/o1 is an end of the piece.
  struct Half {
    bool on;
    T len, s0, G, sw;
  };
  auto half = [&](T o0, bool e0, T o1, bool e1, bool right) {
    Half h{false, (e0 && e1) ? p.hi - p.lo : o1 - o0, T(0), T(0), T(0)};
    if (!(h.len > T(0))) return h;
    h.on = true;
    const T o = left_anchor ? o0 : o1;
    const bool e = left_anchor ? e0 : e1;
    h.s0 = e ? (left_anchor ? p.lo - p.ref : p.hi - p.ref) : xr + o;
    h.G = right ? w - o : w + o;
    h.sw = (right == left_anchor) ? T(-1) : T(1);
    return h;
  };
  Half hr{false, T(0), T(0), T(0), T(0)}, hl = hr;
  const bool inner_r = !(el > T(0)) && !(eh < w), inner_l = !(el > -w) && !(eh < T(0));
  if (eh > T(0)) hr = half(el > T(0) ? el : T(0), el > T(0), eh < w ? eh : w, eh < w, true);
  if (el < T(0)) hl = half(el > -w ? el : -w, el > -w, eh < T(0) ? eh : T(0), eh < T(0), false);
  if (inner_r && inner_l) {
    // The kernel inside the piece (both halves of length w, anchored at x and at x -+ w): one
    // e^{-b w} serves both moment sets, and e^{a s} at x is e^{a s} at the far anchor times it
    // (2 exps instead of 4; the far anchor is where e^{a s} is largest, so nothing overflows that
    // the direct form would not, and an underflowed product means the near half is < e^{-b w}
    // relative to the far one).
    const T ey = exp(-(b * w));
    const T sr = exp_side(p.c, deg, hr.s0, dir, w, b, hr.G, hr.sw, ey);
    const T sl = exp_side(p.c, deg, hl.s0, dir, w, b, hl.G, hl.sw, ey);
    const T pre_far = p.a * (left_anchor ? hl.s0 : hr.s0);
    if (pre_far < T(30)) {
      const T e_far = exp(pre_far), e_near = e_far * ey;
      const T iw = T(1) / w;
      return (left_anchor ? e_far * sl + e_near * sr : e_far * sr + e_near * sl) * iw * iw;
    }
    return exp_scaled(p.a * hr.s0, sr / w, w) + exp_scaled(p.a * hl.s0, sl / w, w);
  }
  T r = T(0);
  const Half* hs[2] = {&hr, &hl};
  for (const Half* h : hs) {
    if (!h->on) continue;
    const T sum = exp_side(p.c, deg, h->s0, dir, h->len, b, h->G, h->sw, T(exp(-(b * h->len))));
    r += exp_scaled(p.a * h->s0, sum / w, w);
  }
  return r;
}

// Float at huge arguments: the terms' intermediates (u^7 for a tent of f^2 past |u| ~ 3.7e5, a
// sigma^2 past sigma ~ 1e19, u^n times an underflowed e^{a u}) leave float's range where the value
// does not, so beyond |x| or sigma = 1e4 a float call computes the same sums in double and rounds
// once (the table's float coefficients are exact in double; tests/extreme_inputs_test.cpp).
template <class T>
inline bool ept_widen(T x, T sigma) {
  return abs_of(x) > T(1e4) || sigma > T(1e4);
}
template <class T, int N>
inline void ept_to_double(const ExpTerm<T> (&p)[N], ExpTerm<double> (&q)[N]) {
  for (int i = 0; i < N; ++i) {
    q[i].lo = p[i].lo;
    q[i].hi = p[i].hi;
    q[i].a = p[i].a;
    q[i].ref = p[i].ref;
    for (int k = 0; k < kMaxCoef; ++k) q[i].c[k] = p[i].c[k];
  }
}

template <class T, int N>
inline T gauss_ept(T x, T sigma, const ExpTerm<T> (&p)[N]) {
  if constexpr (std::is_same<T, float>::value) {
    if (ept_widen(x, sigma)) {
      ExpTerm<double> q[N];
      ept_to_double(p, q);
      return static_cast<T>(gauss_ept(static_cast<double>(x), static_cast<double>(sigma), q));
    }
  }
  if (sigma == T(0)) return ept_eval(x, p);
  T s = T(0);
  for (int i = 0; i < N; ++i) s += gauss_exp_term(x, sigma, p[i]);
  return s;
}
template <class T, int N>
inline T box_ept(T x, T sigma, const ExpTerm<T> (&p)[N]) {
  if constexpr (std::is_same<T, float>::value) {
    if (ept_widen(x, sigma)) {
      ExpTerm<double> q[N];
      ept_to_double(p, q);
      return static_cast<T>(box_ept(static_cast<double>(x), static_cast<double>(sigma), q));
    }
  }
  if (sigma == T(0)) return ept_eval(x, p);
  const T h = k_sqrt3<T>() * sigma;
  T s = T(0);
  for (int i = 0; i < N; ++i) s += box_exp_term(x, h, p[i]);
  return s;
}
template <class T, int N>
inline T tent_ept(T x, T sigma, const ExpTerm<T> (&p)[N]) {
  if constexpr (std::is_same<T, float>::value) {
    if (ept_widen(x, sigma)) {
      ExpTerm<double> q[N];
      ept_to_double(p, q);
      return static_cast<T>(tent_ept(static_cast<double>(x), static_cast<double>(sigma), q));
    }
  }
  if (sigma == T(0)) return ept_eval(x, p);
  const T w = k_sqrt6<T>() * sigma;
  T s = T(0);
  for (int i = 0; i < N; ++i) s += tent_exp_term(x, w, p[i]);
  return s;
}

// ---------------------------------------------------------------------------------------------
// Periodic functions given by one period: pieces cover [0, period).

// r in [0, period) and the integer n (held in T) with y = n period + r. fmod is exact in IEEE
// arithmetic, so r is the true remainder of the given y and period even for |y| >> period (a
// computed y - period floor(y/period) can be off by several periods when y/period rounds). n is
// recovered from the exact r, so (n, r) always describe the same y.
template <class T>
inline T reduce_period(T y, T period, T& n) {
  using std::floor;
  using std::fmod;
  T r = fmod(y, period);
  if (r < T(0)) r += period;
  if (!(r < period)) r = T(0);  // r + period rounded up to period: y is a multiple within rounding
  n = floor((y - r) / period + T(0.5));
  return r;
}

// Signed remainder r = fmod(y, period) in (-period, period): exact, with no "+ period" that would
// round a tiny negative r (x just below a period boundary) to a multiple of eps * period, which a
// tiny kernel width would then magnify. Used where the kernel is narrow.
template <class T>
inline T reduce_signed(T y, T period) {
  using std::fmod;
  return fmod(y, period);
}

// fmod(y, period) for a power-of-two period, without the libm call: |y| - P floor(|y|/P) is exact
// for |y| >= 0 there (every operand is a multiple of ulp(|y|) or of P), and the sign is y's.
template <class T>
inline T reduce_signed_pow2(T y, T period) {
  using std::copysign;
  using std::fabs;
  using std::floor;
  const T a = fabs(y);
  return copysign(a - period * floor(a / period), y);
}

// reduce_period for a power-of-two period, without the libm fmod: y/period and q period are exact,
// and so is y - q period once |y| >= period (Sterbenz); only for -period < y < 0 is r = y + period
// rounded (by eps period), which the callers (the wide-kernel F-differences, divided by a width
// above a period) do not see. r in [0, period), n = q with y ~ n period + r.
template <class T>
inline T reduce_period_pow2(T y, T period, T& n) {
  using std::floor;
  n = floor(y / period);
  T r = y - n * period;
  if (!(r < period)) {  // y + period rounded up to period
    r = T(0);
    n += T(1);
  }
  return r;
}

template <class T, int N>
inline T periodic_piece_eval(T r, const Piece<T> (&p)[N]) {  // r in [0, period)
  for (int i = 0; i < N - 1; ++i)
    if (r < p[i].hi) return poly(p[i].c, r);
  return poly(p[N - 1].c, r);
}

// f(x - period floor(x/period)). The piece is chosen on the exact signed remainder r = fmod(x, T):
// for r < 0 the position is T + r, whose rounding may land on T itself, so the piece is found by
// comparing r with hi - T instead (a jump just below a period boundary stays on the correct side).
// The polynomial is evaluated at r or T + r (up to one rounding, in [0, period]), so the result
// stays in the range of f for any |x|.
template <class T, int N>
inline T periodic_eval(T x, T period, const Piece<T> (&p)[N]) {
  const T r = reduce_signed(x, period);
  if (!(r < T(0))) return periodic_piece_eval(r, p);
  for (int i = 0; i < N - 1; ++i)
    if (r < p[i].hi - period) return poly(p[i].c, r + period);
  return poly(p[N - 1].c, r + period);
}

// Gaussian tail multiple z with P(|Z| > z) <= tol/fmax. Mills: Phic(z) <= phi(z)/z <= phi(z) for
// z >= 1, so 2 phi(z) <= tol/fmax suffices: z = sqrt(2 log(sqrt(2/pi) fmax/tol)), at least 1.
template <class T>
inline T image_z(T fmax, T tol) {
  using std::log;
  using std::sqrt;
  const T arg = T(0.7978845608028654) * fmax / tol;
  if (!(arg > T(1.6487212707001282))) return T(1);  // e^{1/2}: z would be < 1
  return sqrt(T(2) * log(arg));
}

// The window multiple z = image_z(4 fmax, series_tol) + 1 of gauss_periodic_breaks, formed by its
// callers (small, inlined: a literal fmax folds the log and sqrt at compile time).
template <class T>
inline T breaks_z(T fmax) {
  return image_z(T(4) * fmax, series_tol<T>()) + T(1);
}

// Break decomposition of a periodic f (one period of pieces on [0, period)), or with half = true
// of f(y) 1{y >= 0}: the polynomial of the piece containing x plus one far-side tail per break
// within z sigma of x (gauss_pw_breaks, repeated every period; the jump polynomial of each break
// type is the same in every period). z = breaks_z(fmax) (passed in): dropping the breaks beyond it
// replaces f there by a polynomial continuation of degree <= 7 whose weight sigma^k z^k Phic(z)
// stays below tol for sigma <= period. Valid for sigma at most the narrowest piece (/4 when the
// degree exceeds 3), like gauss_pw_breaks; one erfc and one exp per break in the window instead
// of a Gauss-Legendre rule per piece. x is the exact signed remainder (full period) or x itself
// (half line, |x| a few sigma).
template <class T, int N>
inline T gauss_periodic_breaks(T x, T sigma, T period, const Piece<T> (&p)[N], T z, bool half) {
  using std::floor;
  // Jump polynomials, about the break, of each break type: i = 0 the period boundary (last piece
  // of the previous period to the first), i > 0 between pieces i-1 and i; e0: from 0 to p[0] at
  // the half line's start. Formed on first use (at small sigma most calls meet no break) and only
  // up to the degree of the two pieces.
  T e[N][kMaxCoef], e0[kMaxCoef];
  int deg[N], deg0 = -1;
  for (int i = 0; i < N; ++i) deg[i] = -1;
  auto jump = [&](int i) {
    const Piece<T>& prev = p[i == 0 ? N - 1 : i - 1];
    const int da = degree(p[i].c), db = degree(prev.c), dm = da > db ? da : db;
    T a[kMaxCoef], b[kMaxCoef];
    taylor_shift(p[i].c, da, p[i].lo, a);
    taylor_shift(prev.c, db, i == 0 ? period : p[i].lo, b);
    for (int k = da + 1; k <= dm; ++k) a[k] = T(0);
    for (int k = db + 1; k <= dm; ++k) b[k] = T(0);
    for (int k = 0; k <= dm; ++k) e[i][k] = a[k] - b[k];
    int d = dm;
    while (d > 0 && e[i][d] == T(0)) --d;
    deg[i] = d;
    if (i == 0) {
      for (int k = 0; k <= da; ++k) e0[k] = a[k];
      deg0 = da;
    }
  };
  // Base piece j of period m0 containing x (right-continuous; for x < 0 the piece is found on the
  // signed remainder as periodic_eval does), or none (0) left of a half line.
  T s = T(0);
  if (!(half && x < T(0))) {
    const T m0 = half ? floor(x / period) : (x < T(0) ? T(-1) : T(0));
    const T r = x - m0 * period;
    int j = N - 1;
    for (int i = 0; i < N - 1; ++i)
      if (half || !(x < T(0)) ? r < p[i].hi : x < p[i].hi - period) {
        j = i;
        break;
      }
    T g[kMaxCoef];
    const int dj = degree(p[j].c);
    taylor_shift(p[j].c, dj, r, g);
    s = g[0];
    T s2k = T(1), mk = T(1);
    for (int k = 2; k <= dj; k += 2) {
      s2k *= sigma * sigma;
      mk *= T(k - 1);
      if (g[k] != T(0)) s += g[k] * s2k * mk;
    }
  }
  const T R = z * sigma;
  T m1 = floor((x - R) / period);
  if (half && m1 < T(0)) m1 = T(0);
  const T m2 = floor((x + R) / period);
  for (T m = m1; m <= m2; m += T(1)) {
    const T shift = m * period;
    for (int i = 0; i < N; ++i) {
      const bool start = half && m == T(0) && i == 0;
      const T d = (p[i].lo + shift) - x;  // break minus x
      if (!(d < R) || !(d > -R)) continue;
      if (start ? deg0 < 0 : deg[i] < 0) jump(i);
      const T* ei = start ? e0 : e[i];
      const int di = start ? deg0 : deg[i];
      if (di == 0 && ei[0] == T(0)) continue;
      if (d > T(0)) {
        s += break_tail(ei, di, d / sigma, sigma);
      } else {
        T ne[kMaxCoef];
        for (int k = 0; k <= di; ++k) ne[k] = -ei[k];
        s += break_tail(ne, di, -d / sigma, -sigma);
      }
    }
  }
  return s;
}

// sigma small enough for gauss_periodic_breaks (see there).
template <class T, int N>
inline bool periodic_breaks_ok(T sigma, const Piece<T> (&p)[N]) {
  T wmin = inf<T>();
  int maxdeg = 0;
  for (int i = 0; i < N; ++i) {
    wmin = min_of(wmin, p[i].hi - p[i].lo);
    maxdeg = degree(p[i].c) > maxdeg ? degree(p[i].c) : maxdeg;
  }
  return sigma <= (maxdeg <= 3 ? wmin : T(0.25) * wmin);
}

// Image sum: f smoothed = sum over periods m of the pieces shifted by m period. Only pieces that
// meet [x_r - z sigma, x_r + z sigma] are summed, z = image_z(fmax, series_tol): the neglected
// ones carry at most fmax P(|Z| > z) <= series_tol in total. x_r is the exact signed remainder
// and shifted ends are formed as (lo + m period) - x_r (see the header note).
template <class T, int N>
inline T gauss_periodic_image(T x, T sigma, T period, const Piece<T> (&p)[N], T fmax) {
  using std::floor;
  if (sigma == T(0)) return periodic_eval(x, period, p);
  const T xr = reduce_signed(x, period);
  if (periodic_breaks_ok(sigma, p)) return gauss_periodic_breaks(xr, sigma, period, p, breaks_z(fmax), false);
  const T R = image_z(fmax, series_tol<T>()) * sigma;
  const T m0 = floor((xr - R) / period), m1 = floor((xr + R) / period);
  T s = T(0);
  for (T m = m0; m <= m1; m += T(1)) {
    const T shift = m * period;
    for (int i = 0; i < N; ++i) {
      const T dl = (p[i].lo + shift) - xr, dh = (p[i].hi + shift) - xr;
      if (!(dh > -R) || !(dl < R)) continue;
      s += gauss_core(xr - shift, sigma, dl, dh, p[i].lo, p[i].hi, p[i].c);
    }
  }
  return s;
}

// Number of Fourier terms K for the Gaussian-smoothed series: the tail sum_{k>K} B e^{-a k^2},
// a = 2 pi^2 s^2, is bounded by the geometric majorant (u = K + 1)
//   sum_{k>K} e^{-a k^2} <= e^{-a u^2} sum_{j>=0} e^{-2 a u j} = e^{-a u^2} / (1 - e^{-2 a u})
// (since (u + j)^2 >= u^2 + 2 u j). Returns the smallest K >= 0 for which B times the
// majorant is <= tol (so the true tail is certified; K is at most one above the true minimum).
// The start value solves (K+1)^2 = log(B/tol)/a refined by a few fixed-point steps for the
// geometric factor; a tiny s (K beyond 2^30) returns 2^30.
template <class T>
inline int fourier_terms(T s, T coef_bound, T tol) {
  using std::ceil;
  using std::exp;
  using std::expm1;
  using std::log;
  using std::sqrt;
  constexpr int kBig = 1 << 30;
  if (!(coef_bound > T(0))) return 0;
  const T a = T(2) * k_pi<T>() * k_pi<T>() * s * s;
  if (!(a > T(0))) return kBig;
  auto bound = [&](int K) {
    const T u = T(K) + T(1);
    return coef_bound * exp(-a * u * u) / (-expm1(T(-2) * a * u));
  };
  const T L = log(coef_bound / tol);
  T u = sqrt((L > T(0) ? L : T(0)) / a);
  for (int it = 0; it < 4; ++it) {
    const T uu = u > T(1) ? u : T(1);
    const T Lg = L - log(-expm1(T(-2) * a * uu));
    u = sqrt((Lg > T(0) ? Lg : T(0)) / a);
  }
  if (!(u < T(kBig))) return kBig;
  int K = static_cast<int>(ceil(u)) - 1;
  if (K < 0) K = 0;
  while (K > 0 && bound(K - 1) <= tol) --K;
  while (!(bound(K) <= tol) && K < kBig) ++K;
  return K;
}

// Periods the image sum visits in the worst case over x_r in [0, period): the window
// [x_r - z sigma, x_r + z sigma] (z = image_z(fmax, tol)) meets at most ceil(2 z s) + 1 periods.
template <class T>
inline int image_periods(T s, T fmax, T tol) {
  using std::ceil;
  const T v = ceil(T(2) * image_z(fmax, tol) * s) + T(1);
  if (!(v < T(1 << 30))) return 1 << 30;
  return static_cast<int>(v);
}

// The number of Fourier terms K when the Fourier series is the cheaper of the two dual series,
// else -1 (callers then use the image sum); one evaluation of fourier_terms serves both the choice
// and the loop. Cost model (measured with bench_table): a Fourier term is an exp, a cos and a sin
// (~3 units); an image piece is an erfc and an exp (~4) when wider than 2 sigma, else a 20-point
// Gauss-Legendre rule (~20 exps).
template <class T>
inline int fourier_terms_if_preferred(T s, int npieces, T coef_bound, T fmax) {
  const int K = fourier_terms(s, coef_bound, series_tol<T>());
  const int P = image_periods(s, fmax, series_tol<T>());
  const double per_piece = double(s) * double(npieces) > 0.5 ? 20.0 : 4.0;
  return 3.0 * double(K) < double(P) * double(npieces) * per_piece ? K : -1;
}

template <class T>
inline bool prefer_fourier(T s, int npieces, T coef_bound, T fmax) {
  return fourier_terms_if_preferred(s, npieces, coef_bound, fmax) >= 0;
}

// Box over a periodic f. (a) Support 2h <= 4 periods: integrate the pieces of the (at most 6)
// periods it meets directly (box_core on exact shifted offsets around the exact signed remainder);
// no difference of F is formed, so tiny h is exact. (b) Wider: Appendix C, F(y) = n F_p(T) + F_p(y
// - nT), with the difference F(x_r + h) - F(x_r - h) = (n2 - n1) F_p(T) + F_p(r2) - F_p(r1) taken
// on the reduced argument and with the integer parts subtracted as integers: nothing of size |x| is
// formed, and the rounding of x_r +- h (eps h) is divided by 2h.
template <class T, int N>
inline T box_periodic(T x, T sigma, T period, const Piece<T> (&p)[N], const Piece<T> (&P1)[N]) {
  using std::floor;
  if (sigma == T(0)) return periodic_eval(x, period, p);
  const T h = k_sqrt3<T>() * sigma;
  if (h <= T(2) * period) {
    const T xr = reduce_signed(x, period);
    const T m0 = floor((xr - h) / period), m1 = floor((xr + h) / period);
    T s = T(0);
    for (T m = m0; m <= m1; m += T(1)) {
      const T shift = m * period;
      for (int i = 0; i < N; ++i) {
        const T dl = (p[i].lo + shift) - xr, dh = (p[i].hi + shift) - xr;
        if (!(dh > -h) || !(dl < h)) continue;
        s += box_core(xr - shift, h, dl, dh, p[i].lo, p[i].hi, p[i].c);
      }
    }
    return s;
  }
  T n, n1, n2;
  const T xr = reduce_period(x, period, n);
  const T r1 = reduce_period(xr - h, period, n1);
  const T r2 = reduce_period(xr + h, period, n2);
  const T FT = poly(P1[N - 1].c, period);
  return ((n2 - n1) * FT + (periodic_piece_eval(r2, P1) - periodic_piece_eval(r1, P1))) /
         (T(2) * h);
}

// Tent over a periodic f. (a) Support 2w <= 4 periods: direct tent_core over the shifted pieces.
// (b) Appendix C second integral F_2(y) = A (T q(q-1)/2 + r q) + B q + F_p2(r), y = qT + r,
// A = F_p(T), B = F_p2(T), at y = x_r - w, x_r, x_r + w with x_r in [0, T) (so q0 = 0, r0 = x_r):
//   F_2(x_r+w) - 2F_2(x_r) + F_2(x_r-w)
//     = A (g(q2) + g(q1) + r2 q2 + r1 q1) + B (q2 + q1) + F_p2(r2) - 2 F_p2(x_r) + F_p2(r1),
// g(q) = T q (q-1)/2. Every term is O(w^2 A / T) or bounded, so the w^2 division loses nothing.
template <class T, int N>
inline T tent_periodic(T x, T sigma, T period, const Piece<T> (&p)[N], const Piece<T> (&P1)[N],
                       const Piece<T> (&P2)[N]) {
  using std::floor;
  if (sigma == T(0)) return periodic_eval(x, period, p);
  const T w = k_sqrt6<T>() * sigma;
  if (w <= T(2) * period) {
    const T xr = reduce_signed(x, period);
    const T m0 = floor((xr - w) / period), m1 = floor((xr + w) / period);
    T s = T(0);
    for (T m = m0; m <= m1; m += T(1)) {
      const T shift = m * period;
      for (int i = 0; i < N; ++i) {
        const T dl = (p[i].lo + shift) - xr, dh = (p[i].hi + shift) - xr;
        if (!(dh > -w) || !(dl < w)) continue;
        s += tent_core(xr - shift, w, dl, dh, p[i].lo, p[i].hi, p[i].c);
      }
    }
    return s;
  }
  T n, q1, q2;
  const T xr = reduce_period(x, period, n);
  const T r1 = reduce_period(xr - w, period, q1);
  const T r2 = reduce_period(xr + w, period, q2);
  const T A = poly(P1[N - 1].c, period);
  const T B = poly(P2[N - 1].c, period);
  // Every term is divided by w^2 as it is formed (q/w ~ 1/period): q^2 and w^2 overflow float
  // once w exceeds ~1e19, and inf/inf would be NaN.
  const T iw = T(1) / w;
  const T s1 = q1 * iw, s2 = q2 * iw;
  const T g1 = period * s1 * ((q1 - T(1)) * iw) * T(0.5);
  const T g2 = period * s2 * ((q2 - T(1)) * iw) * T(0.5);
  return A * ((g2 + g1) + (r2 * iw * s2 + r1 * iw * s1)) + B * iw * (s2 + s1) +
         ((periodic_piece_eval(r2, P2) + periodic_piece_eval(r1, P2)) - T(2) * periodic_piece_eval(xr, P2)) *
             iw * iw;
}

// ---------------------------------------------------------------------------------------------
// Half-line restrictions of periodic functions: f_right(x) = E[f(x+U) 1{x+U >= 0}] for f given by
// one period of pieces (products f * B with B piecewise constant, such as trunc^2's fract * step,
// are sums of these at the breaks of B). The generated companion <kernel>_<f>_right returns 0 when
// the kernel lies left of 0 and the plain periodic entry when it lies right of 0; the routines below
// are called only when the kernel straddles 0, so |x| is at most a few kernel widths and the
// absolute coordinate needs no reduction.

// Gaussian. (a) Boundary series (repeated integration by parts at t = 0 with the periodic, mean-free
// antiderivatives S_j of f - a0; the engine derives S_j(0) exactly):
//   f_right = a0 Phi(z) + rho phi(z) sum_m cs[m] rho^m He_m(z),  z = x/sigma, rho = T/(2 pi sigma),
// cs[m] = (-1)^(m+1) S_{m+2}(0) (2 pi/T)^(m+1). Stopping after term m leaves the remainder
// +-int_0^inf S_{m+2}(t) d^(m+1)/dt^(m+1) phi_sigma(t - x) dt, bounded by
//   max|S_{m+2}| int |phi_sigma^(m+1)| <= coef_bound zeta(m+1) (T/2pi)^(m+1) sigma^-(m+1) sqrt((m+1)!)
// (|S_n| from the Fourier coefficients, |c_k| <= coef_bound/2; int |He_n| phi <= sqrt(n!) by
// Cauchy-Schwarz), i.e. 1.65 coef_bound rho^(m+1) sqrt((m+1)!) for m >= 1. The series is asymptotic
// (the bound has a minimum over m): it is used when that bound reaches series_tol within the M
// coefficients (sigma >~ 1.5 T in double, >~ 1.1 T in float). rho^m He_m(z) is formed by the
// recurrence G_{m+1} = rho z G_m - m rho^2 G_{m-1} (no powers of sigma, no overflow).
// (b) Otherwise the image sum over the periods m >= 0 within image_z(fmax, tol) sigma of x.
template <class T, int N, int M>
inline T gauss_periodic_right(T x, T sigma, T period, const Piece<T> (&p)[N], T fmax, T coef_bound, T a0,
                              const T (&cs)[M]) {
  using std::floor;
  using std::sqrt;
  const T tol = series_tol<T>();
  const T rho = period / (T(2) * k_pi<T>() * sigma);
  if (rho < T(0.5)) {
    T b = T(1.65) * coef_bound;
    int last = -1;
    for (int m = 0; m < M; ++m) {
      b *= rho * sqrt(T(m + 1));
      if (m >= 1 && b <= tol) {
        last = m;
        break;
      }
    }
    if (last >= 0) {
      const T z = x / sigma;
      T Gm1 = T(0), G = T(1), acc = T(0);
      for (int m = 0; m <= last; ++m) {
        acc += cs[m] * G;
        const T Gn = rho * z * G - T(m) * rho * rho * Gm1;
        Gm1 = G;
        G = Gn;
      }
      return a0 * Phi(z) + rho * phi(z) * acc;
    }
  }
  if (periodic_breaks_ok(sigma, p)) return gauss_periodic_breaks(x, sigma, period, p, breaks_z(fmax), true);
  const T R = image_z(fmax, tol) * sigma;
  T m0 = floor((x - R) / period);
  if (m0 < T(0)) m0 = T(0);
  const T m1 = floor((x + R) / period);
  T s = T(0);
  for (T m = m0; m <= m1; m += T(1)) {
    const T shift = m * period;
    for (int i = 0; i < N; ++i) {
      const T dl = (p[i].lo + shift) - x, dh = (p[i].hi + shift) - x;
      if (!(dh > -R) || !(dl < R)) continue;
      s += gauss_core(x - shift, sigma, dl, dh, p[i].lo, p[i].hi, p[i].c);
    }
  }
  return s;
}

// Box, half-width h, -h < x < h: (1/2h) int_0^(x+h) f. h <= 2 periods: the pieces of the periods
// m >= 0 it meets, directly (box_core; exact for tiny h). Wider: F(y) = q F_p(T) + F_p(r), y = x + h
// = qT + r, divided by 2h >= y (no cancellation).
template <class T, int N>
inline T box_periodic_right(T x, T h, T period, const Piece<T> (&p)[N], const Piece<T> (&P1)[N]) {
  using std::floor;
  if (h <= T(2) * period) {
    const T m1 = floor((x + h) / period);
    T s = T(0);
    for (T m = T(0); m <= m1; m += T(1)) {
      const T shift = m * period;
      for (int i = 0; i < N; ++i) {
        const T dl = (p[i].lo + shift) - x, dh = (p[i].hi + shift) - x;
        if (!(dh > -h) || !(dl < h)) continue;
        s += box_core(x - shift, h, dl, dh, p[i].lo, p[i].hi, p[i].c);
      }
    }
    return s;
  }
  T q;
  const T r = reduce_period(x + h, period, q);
  return (q * poly(P1[N - 1].c, period) + periodic_piece_eval(r, P1)) / (T(2) * h);
}

// Tent, half-width w, -w < x < w: int_0^(x+w) f(t) (w - |t - x|)/w^2 dt. w <= 2 periods: tent_core
// over the pieces of the periods m >= 0. Wider: the second difference of F2(max(y, 0)),
// (F2(x + w) - 2 F2(max(x, 0)))/w^2, F2(y) = A (T q(q-1)/2 + r q) + B q + F_p2(r) (Appendix C);
// for 0 <= x < w the difference is at least half of F2(x + w) (F2 grows like y^2 a0/2), so it
// cancels by at most a small factor.
template <class T, int N>
inline T tent_periodic_right(T x, T w, T period, const Piece<T> (&p)[N], const Piece<T> (&P1)[N],
                             const Piece<T> (&P2)[N]) {
  using std::floor;
  if (w <= T(2) * period) {
    const T m1 = floor((x + w) / period);
    T s = T(0);
    for (T m = T(0); m <= m1; m += T(1)) {
      const T shift = m * period;
      for (int i = 0; i < N; ++i) {
        const T dl = (p[i].lo + shift) - x, dh = (p[i].hi + shift) - x;
        if (!(dh > -w) || !(dl < w)) continue;
        s += tent_core(x - shift, w, dl, dh, p[i].lo, p[i].hi, p[i].c);
      }
    }
    return s;
  }
  const T A = poly(P1[N - 1].c, period);
  const T B = poly(P2[N - 1].c, period);
  auto F2 = [&](T y) {
    T q;
    const T r = reduce_period(y, period, q);
    return A * (period * q * (q - T(1)) * T(0.5) + r * q) + B * q + periodic_piece_eval(r, P2);
  };
  const T x0 = x > T(0) ? x : T(0);
  return (F2(x + w) - T(2) * F2(x0)) / (w * w);
}

}  // namespace detail
}  // namespace bl

// ---- first kernel moment of periodic functions ----
namespace bl {
namespace detail {

// M_K(x, sigma) = E[U g(x + U)] for a periodic g given by one period of polynomial pieces (the same
// Piece<T> input as the periodic routines above: absolute coordinate t in [0, period), degree <= 6
// here, since the integrand (t - x) q(t) gains one degree; a piece of degree 7 gives NaN). With it
// the engine forms E[(x+U) g(x+U)] = x E[g(x+U)] + M_K (floor^2 = x^2 - 2 x fract + fract^2, ceil^2).
// sigma == 0: U = 0, so 0. sigma < 0, NaN or +inf, or x not finite: NaN.
//
// Conventions of this section (c.f. the header note):
//  * M depends on x only through x_r = x mod period (exact fmod; the signed remainder
//    reduce_signed where the kernel is narrow, as above, so x just below a period boundary is not
//    rounded onto it; [0, period) in the wide branches): with d_m = m period - x_r the
//    integrand on period m in the piece's own coordinate s is (s + d_m) q(s) w(s + d_m); t g(t) is
//    never formed in absolute coordinates, so nothing of size |x| appears anywhere.
//  * Mean removal: g is replaced by g - gbar (gbar = I0/period, computed from the pieces). E[U c] = 0
//    for every constant c and symmetric kernel, so M is unchanged exactly (whatever the rounding of
//    gbar), but the terms become mean-free: sums over many periods no longer carry O(sigma) or
//    O(w/period) parts that cancel (sawtooth: every period's term is small; tent: the d^2 I0 sums
//    of the two sides no longer cancel from O(w/period)).
//  * Per piece, the polynomial is re-expanded about o = the kernel centre clamped into the piece
//    (o = lo, o = hi or o = the centre), in v = t - o, as (v + e) q(o + v) with e = o - centre taken
//    from the exact offsets (dl, dh or 0). Coefficients stay local to the piece (no powers of a far
//    centre), and when the centre lies inside the piece the constant term is exactly 0, so a tiny
//    kernel gives M ~ sigma^2 q'(x) to relative accuracy instead of an absolute eps |x_r q|. The
//    result is handed to gauss_core/box_core/tent_core with centre -e and ends lo - o, hi - o.

// Pieces minus the period mean, their degrees, and the period moments I_j = int_0^T s^j (g - gbar).
template <class T, int N>
struct UPeriodData {
  Piece<T> p[N];
  int deg[N];
  T I0 = T(0), I1 = T(0), I2 = T(0);
  bool ok = true;
};

// int_a^b s^j q(s) ds for 0 <= a <= b, by box_core's divided differences S_n = sum_i a^i b^(n-i)
// (all terms >= 0: no cancellation; (b - a) is the only difference formed).
template <class T>
inline T u_piece_moment(const T* c, int deg, int j, T a, T b) {
  T S = T(1), an = T(1), sum = T(0);
  for (int n = 0; n <= deg + j; ++n) {
    if (n > 0) {
      an *= a;
      S = b * S + an;
    }
    if (n >= j && c[n - j] != T(0)) sum += c[n - j] * S / T(n + 1);
  }
  return (b - a) * sum;
}

template <class T, int N>
inline UPeriodData<T, N> u_period_data(T period, const Piece<T> (&p)[N]) {
  UPeriodData<T, N> d;
  T I0 = T(0);
  for (int i = 0; i < N; ++i) {
    d.p[i] = p[i];
    d.deg[i] = degree(p[i].c);
    if (d.deg[i] > kMaxCoef - 2) d.ok = false;
    if (p[i].hi > p[i].lo) I0 += u_piece_moment(p[i].c, d.deg[i], 0, p[i].lo, p[i].hi);
  }
  const T gbar = I0 / period;
  for (int i = 0; i < N; ++i) {
    d.p[i].c[0] -= gbar;
    if (!(p[i].hi > p[i].lo)) continue;
    d.I0 += u_piece_moment(d.p[i].c, d.deg[i], 0, p[i].lo, p[i].hi);
    d.I1 += u_piece_moment(d.p[i].c, d.deg[i], 1, p[i].lo, p[i].hi);
    d.I2 += u_piece_moment(d.p[i].c, d.deg[i], 2, p[i].lo, p[i].hi);
  }
  return d;
}

// Coefficients in v of (v + e) q(o + v) (degree deg + 1 <= 7).
template <class T>
inline void u_coefs(const T* q, int deg, T o, T e, T* out) {
  T g[kMaxCoef];
  for (int k = 0; k < kMaxCoef; ++k) g[k] = out[k] = T(0);
  taylor_shift(q, deg, o, g);
  out[0] = e * g[0];
  for (int k = 1; k <= deg; ++k) out[k] = g[k - 1] + e * g[k];
  out[deg + 1] = g[deg];
}

// Tent with its centre inside the piece, c in v = t - centre: both halves term by term,
// sum_k c_k (A_k(Lr) + (-1)^k A_k(Ll)), A_k(L) = int_0^L v^k (w - v) dv / w^2
// = L^k (L/w) (1/(k+1) - (L/w)/(k+2)) (tent_side's terms with G = w). For odd k and Lr == Ll (the
// support inside the piece) the bracket is exactly 0, so the odd part of the integrand, of size
// w |q|, cancels before any rounding: a tiny tent keeps relative accuracy (M = sigma^2 q' + ...),
// where summing the two tent_side halves would leave eps w |q| against sigma^2 |q'|.
template <class T>
inline T u_tent_centre(const T* c, int deg, T Lr, T Ll, T w) {
  const T lr = Lr / w, ll = Ll / w;
  T sum = T(0), Lrk = T(1), Llk = T(1);
  for (int k = 0; k <= deg; ++k) {
    if (c[k] != T(0)) {
      const T ar = Lrk * lr * (recip<T>(k + 1) - lr * recip<T>(k + 2));
      const T al = Llk * ll * (recip<T>(k + 1) - ll * recip<T>(k + 2));
      sum += c[k] * ((k & 1) ? ar - al : ar + al);
    }
    if (k < deg) {
      Lrk *= Lr;
      Llk *= Ll;
    }
  }
  return sum;
}

// One piece against one kernel, centre xq in the piece's coordinate, exact offsets dl, dh of the
// piece ends from the centre. Kernel: 0 Gaussian (s = sigma), 1 box (s = h), 2 tent (s = w).
template <class T>
inline T u_piece(int kernel, T xq, T s, T dl, T dh, T lo, T hi, const T* q, int deg) {
  T o = xq, e = T(0), lo2 = dl, hi2 = dh;  // centre inside the piece: about the centre, e = 0
  if (!(dl < T(0))) {  // centre at or left of the piece: about lo
    o = lo;
    e = dl;
    lo2 = T(0);
    hi2 = hi - lo;
  } else if (!(dh > T(0))) {  // right of it: about hi
    o = hi;
    e = dh;
    lo2 = lo - hi;
    hi2 = T(0);
  }
  T c[kMaxCoef];
  u_coefs(q, deg, o, e, c);
  if (kernel == 2 && dl < T(0) && dh > T(0))
    return u_tent_centre(c, deg + 1, min_of(dh, s), min_of(-dl, s), s);
  if (kernel == 0) return gauss_core(-e, s, dl, dh, lo2, hi2, c);
  if (kernel == 1) return box_core(-e, s, dl, dh, lo2, hi2, c);
  return tent_core(-e, s, dl, dh, lo2, hi2, c);
}

// Sum of u_piece over the periods m0..m1 and the pieces meeting (x_r - R, x_r + R), shifted ends
// formed as (lo + m T) - x_r (header note).
template <class T, int N>
inline T u_periods(int kernel, T xr, T s, T R, T period, T m0, T m1, const UPeriodData<T, N>& g) {
  T sum = T(0);
  // Counted in integers: with a float m beyond 2^24, m += 1 would not move and the loop would never
  // end. Box/tent pass spans of a few periods, the Gaussian image sum ~2 z sigma / period (its
  // caller switches to the Fourier form long before 1e7).
  const T span = m1 - m0;
  if (!(span >= T(0) && span < T(1e7))) return span < T(0) ? sum : std::numeric_limits<T>::quiet_NaN();
  const long count = static_cast<long>(span) + 1;
  for (long k = 0; k < count; ++k) {
    const T m = m0 + T(k);
    const T shift = m * period;
    for (int i = 0; i < N; ++i) {
      const Piece<T>& P = g.p[i];
      if (!(P.hi > P.lo)) continue;
      const T dl = (P.lo + shift) - xr, dh = (P.hi + shift) - xr;
      if (!(dh > -R) || !(dl < R)) continue;
      sum += u_piece(kernel, xr - shift, s, dl, dh, P.lo, P.hi, P.c, g.deg[i]);
    }
  }
  return sum;
}

// int_0^L c(v) dv for either sign of L (Horner in L).
template <class T>
inline T u_integral0(const T* c, int deg, T L) {
  T r = T(0);
  for (int k = deg; k >= 0; --k) r = r * L + c[k] / T(k + 1);
  return r * L;
}

template <class T>
inline bool u_bad_args(T x, T sigma) {
  return !(x - x == T(0)) || !(sigma >= T(0)) || !(sigma < inf<T>());
}

// Gaussian, image sum over periods: sum_m sum_i int (s + d_m)(q_i(s) - gbar) phi((s + d_m)/sigma)
// /sigma ds over the pieces meeting [x_r - R, x_r + R]. Truncation: the neglected part is at most
// max|g - gbar| E[|U|; |U| > R] <= 2 fmax * 2 sigma phi(z), R = z sigma, and z = image_z(2 fmax
// max(1, sigma), series_tol) makes that <= series_tol * min(sigma, 1): relative series_tol for small
// sigma (M ~ sigma fmax), absolute series_tol beyond. Error: each piece term is computed to a few
// eps of its size; the terms are O(sigma fmax width/period) at most, and after the mean removal a
// single-piece period (sawtooth, fract^2) is mean-free within its piece, so the sum does not grow
// with sigma; with several pieces per period (square wave) adjacent pieces still cancel from
// ~0.4 sigma fmax in total, an absolute error ~ eps sigma fmax (the caller's Fourier form takes
// over long before that matters: cost ~ 2 z sigma / period periods).
template <class T, int N>
inline T gauss_periodic_u_image(T x, T sigma, T period, const Piece<T> (&p)[N], T fmax) {
  using std::floor;
  if (u_bad_args(x, sigma)) return std::numeric_limits<T>::quiet_NaN();
  if (sigma == T(0)) return T(0);
  const UPeriodData<T, N> g = u_period_data(period, p);
  if (!g.ok) return std::numeric_limits<T>::quiet_NaN();
  const T xr = reduce_signed(x, period);  // exact, in (-T, T): no "+ T" rounding near 0
  const T big = sigma > T(1) ? sigma : T(1);
  const T R = image_z(T(2) * fmax * big, series_tol<T>()) * sigma;
  const T m0 = floor((xr - R) / period), m1 = floor((xr + R) / period);
  return u_periods(0, xr, sigma, R, period, m0, m1, g);
}

// sqrt(3) sigma as hh + hl with |hl| <~ eps hh (fma for the rounding error of the product, then the
// low part of sqrt(3)). Multiprecision: hl = 0 (not needed).
template <class T>
inline T u_sqrt3_lo_times(T sigma, T hh) {
  if constexpr (kWide<T>) {
    (void)sigma;
    (void)hh;
    return T(0);
  } else {
    using std::fma;
    const T lo = sizeof(T) >= 8 ? T(1.0035084221806902653e-16) : T(3.1087248875558696342e-8);
    return fma(k_sqrt3<T>(), sigma, -hh) + lo * sigma;
  }
}

// Box. (a) 2h <= 4 periods: every piece of the (at most 6) periods met, u_piece on exact offsets
// (box_core clips to [x - h, x + h]; relative accuracy for tiny h, see the section note).
// (b) Wider: [x_r - h, x_r + h] = [q1 T + r1, q2 T + r2] is the left end [r1, T) of period q1, the
// full periods q1+1..q2-1 and the right end [0, r2) of period q2. A full period contributes
// int_0^T (s + d_m) g~(s) ds = I1 + d_m I0; summed in closed form with sum_m d_m = -n (r1 + r2)/2
// (from (q1 + q2) T = 2 x_r - r1 - r2), so the full part is n (I1 - I0 (r1 + r2)/2) with n =
// q2 - q1 - 1: no term of size h is formed. The ends are int (s + d) g~ over [lo, min(hi, r2)) and
// [max(lo, r1), hi), in v = s - lo / v = s - hi (local coefficients, |d| ~ h only as the factor e).
// All terms are O(h T max|g~|) before the division by 2h: error ~ eps T max|g|.
// Conditioning: dM/dh = (g(x+h) - g(x-h))/2 = O(1), so the rounding of h = sqrt(3) sigma itself
// (eps h) would cost eps h absolute (float, sigma = 1e4: 1e-3). Hence h is carried as hh + hl and
// the ends as hh mod T (exact fmod) + x_r + hl: r1, r2 are right to eps T.
// The period data depend only on the table: the emitted entry builds them once (a static) and
// calls the overload taking them; the overload taking the pieces builds them per call.
template <class T, int N>
inline T box_periodic_u(T x, T sigma, T period, const UPeriodData<T, N>& g) {
  using std::floor;
  if (u_bad_args(x, sigma)) return std::numeric_limits<T>::quiet_NaN();
  if (sigma == T(0)) return T(0);
  if (!g.ok) return std::numeric_limits<T>::quiet_NaN();
  const T h = k_sqrt3<T>() * sigma;
  if (h <= T(2) * period) {
    const T xs = reduce_signed(x, period);  // exact, in (-T, T)
    const T m0 = floor((xs - h) / period), m1 = floor((xs + h) / period);
    return u_periods(1, xs, h, h, period, m0, m1, g);
  }
  T n;
  const T xr = reduce_period(x, period, n);  // in [0, T)
  const T hl = u_sqrt3_lo_times(sigma, h);
  T nh;
  const T rh = reduce_period(h, period, nh);
  T q2 = nh, r2 = (rh + xr) + hl;  // x_r + h = q2 T + r2
  if (!(r2 < period)) {
    r2 -= period;
    q2 += T(1);
  } else if (r2 < T(0)) {
    r2 += period;
    q2 -= T(1);
    if (!(r2 < period)) {
      r2 = T(0);
      q2 += T(1);
    }
  }
  T q1 = -nh, r1 = (xr - rh) - hl;  // x_r - h = q1 T + r1
  if (r1 < T(0)) {
    r1 += period;
    q1 -= T(1);
    if (!(r1 < period)) {
      r1 = T(0);
      q1 += T(1);
    }
  } else if (!(r1 < period)) {
    r1 -= period;
    q1 += T(1);
  }
  const T nfull = q2 - q1 - T(1);
  T s = nfull * (g.I1 - g.I0 * (r1 + r2) * T(0.5));
  const T s1 = q1 * period, s2 = q2 * period;
  for (int i = 0; i < N; ++i) {
    const Piece<T>& P = g.p[i];
    if (!(P.hi > P.lo)) continue;
    T c[kMaxCoef];
    if (P.lo < r2) {  // right end: [lo, min(hi, r2)) of period q2
      const T b = P.hi < r2 ? P.hi : r2;
      u_coefs(P.c, g.deg[i], P.lo, (P.lo + s2) - xr, c);
      s += u_integral0(c, g.deg[i] + 1, b - P.lo);
    }
    if (P.hi > r1) {  // left end: [max(lo, r1), hi) of period q1
      const T a = P.lo > r1 ? P.lo : r1;
      u_coefs(P.c, g.deg[i], P.hi, (P.hi + s1) - xr, c);
      s -= u_integral0(c, g.deg[i] + 1, a - P.hi);
    }
  }
  return s / (T(2) * h);
}

// Tent. (a) 2w <= 4 periods: u_piece over the periods met (tent_core splits at the kink).
// (b) Wider: periods q1 (left edge), 0 (the kink, x_r is in it) and q2 (right edge) by u_piece; the
// full periods right of the kink, m = 1..n_r (n_r = q2 - 1, d = m T - x_r), weight (w - s - d)/w^2,
// contribute (w - 2d) I1 + d (w - d) I0 - I2; those left of it, m = -1..-n_l (n_l = -q1 - 1,
// e = -d = |m| T + x_r), weight (w + s + d)/w^2, contribute (w - 2e) I1 - e (w - e) I0 + I2. Summed
// in closed form with the arithmetic and square sums:
//   sum_r (w - 2d) = n_r (w - q2 T + 2 x_r) = n_r (x_r + r2),  sum_l (w - 2e) = -n_l (x_r + r1),
//   (x_r + w = q2 T + r2, x_r - w = q1 T + r1), so the I1 part is O(w) before the division by w^2
// instead of a difference of two O(w^2/T) sums; the I0 part (I0 ~ eps after the mean removal) is
// w sum d - sum d^2 per side; the I2 part is (n_l - n_r) I2. Every term is O(T max|g|) or smaller,
// error ~ eps T max|g|. The tent's weight vanishes at the support edges, so dM/dw = O(T/w): the
// rounding of w and of x_r +- w costs only eps T (no extra precision needed, unlike the box).
template <class T, int N>
inline T tent_periodic_u(T x, T sigma, T period, const UPeriodData<T, N>& g) {
  using std::floor;
  if (u_bad_args(x, sigma)) return std::numeric_limits<T>::quiet_NaN();
  if (sigma == T(0)) return T(0);
  if (!g.ok) return std::numeric_limits<T>::quiet_NaN();
  const T w = k_sqrt6<T>() * sigma;
  if (w <= T(2) * period) {
    const T xs = reduce_signed(x, period);  // exact, in (-T, T)
    const T m0 = floor((xs - w) / period), m1 = floor((xs + w) / period);
    return u_periods(2, xs, w, w, period, m0, m1, g);
  }
  T n;
  const T xr = reduce_period(x, period, n);  // in [0, T)
  T q1, q2;
  const T r1 = reduce_period(xr - w, period, q1);
  const T r2 = reduce_period(xr + w, period, q2);
  T local = u_periods(2, xr, w, w, period, q1, q1, g) + u_periods(2, xr, w, w, period, T(0), T(0), g) +
            u_periods(2, xr, w, w, period, q2, q2, g);
  const T nr = q2 - T(1), nl = -q1 - T(1);
  const T S1r = nr * (nr + T(1)) * T(0.5), S2r = S1r * (T(2) * nr + T(1)) / T(3);
  const T S1l = nl * (nl + T(1)) * T(0.5), S2l = S1l * (T(2) * nl + T(1)) / T(3);
  const T sd = period * S1r - nr * xr;
  const T sd2 = period * period * S2r - T(2) * period * xr * S1r + nr * xr * xr;
  const T se = period * S1l + nl * xr;
  const T se2 = period * period * S2l + T(2) * period * xr * S1l + nl * xr * xr;
  const T full = g.I1 * (nr * (xr + r2) - nl * (xr + r1)) +
                 g.I0 * ((w * sd - sd2) - (w * se - se2)) + g.I2 * (nl - nr);
  return local + full / (w * w);
}

template <class T, int N>
inline T box_periodic_u(T x, T sigma, T period, const Piece<T> (&p)[N]) {
  return box_periodic_u(x, sigma, period, u_period_data(period, p));
}
template <class T, int N>
inline T tent_periodic_u(T x, T sigma, T period, const Piece<T> (&p)[N]) {
  return tent_periodic_u(x, sigma, period, u_period_data(period, p));
}

}  // namespace detail
}  // namespace bl
