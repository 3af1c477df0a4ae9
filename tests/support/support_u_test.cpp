// Tests of the first kernel moment of periodic functions, M_K(x, sigma) = E[U g(x + U)]
// (rulegen/templates/support.hpp and support.glsl, section "first kernel moment of periodic
// functions"): gauss_periodic_u_image, box_periodic_u, tent_periodic_u and their GLSL versions.
//
// References never call the code under test:
//  * quadrature (Boost.Math Gauss-Kronrod, long double) of u (g(x_r + u) - g(x_r)) k(u) du in the
//    kernel's own variable, split at every break of g and at the kernel's kink (and on a unit grid
//    of the Gaussian); subtracting the constant g(x_r) changes nothing (E[U] = 0) but keeps the
//    reference relatively accurate for tiny sigma;
//  * Stein's identity for the Gaussian, E[U g(x+U)] = sigma^2 E[g'(x+U)] with the jumps of g as
//    deltas: closed forms in phi/Phi sums (small sigma) or their Poisson/Fourier series (large);
//  * for tiny kernels inside a piece or centred on a jump: exact closed forms.
// Error: |got - ref| / max(1, |x| |E g|, |ref|) (the caller adds x E[g]) <= 1e-9 in double,
// 2e-5 in float with the reference at the float-rounded inputs. The worst errors are printed.
//
// Like support_test.cpp, this file is compiled a second time (GCC only) as an object that
// includes support.glsl as C++ float code, so the GLSL versions run through the float checks.

#include <cmath>

struct GlslUPieces {  // the GLSL BlPiece[4] layout, free of GLSL types
  int n;
  float lo[4];
  float hi[4];
  float c[4][8];
};

#ifdef BL_SUPPORT_GLSL_AS_CPP
// ---------------------------------------------------------------------------------------------
// GLSL compiled as C++ float code (shims for the GLSL built-ins it uses).
#include <algorithm>

namespace bl_glsl_u_cpp {
using std::abs;
using std::ceil;
using std::exp;
using std::floor;
using std::fma;
using std::log;
using std::sin;
using std::sinh;
using std::sqrt;
using std::trunc;
inline float min(float a, float b) { return b < a ? b : a; }
inline float max(float a, float b) { return a < b ? b : a; }
inline int min(int a, int b) { return b < a ? b : a; }
inline int max(int a, int b) { return a < b ? b : a; }
inline float clamp(float x, float a, float b) { return min(max(x, a), b); }
inline float mod(float a, float b) { return a - b * floor(a / b); }
inline float sign(float a) { return a > 0 ? 1.0f : (a < 0 ? -1.0f : 0.0f); }
struct vec2 {
  float x, y;
  vec2(float a, float b) : x(a), y(b) {}
};
#define out
#define inout
#include "support.glsl"
#undef out
#undef inout

inline void to_glsl(const GlslUPieces& g, BlPiece* p) {
  for (int i = 0; i < 4; ++i) {
    p[i].lo = i < g.n ? g.lo[i] : 0.0;
    p[i].hi = i < g.n ? g.hi[i] : 0.0;
    for (int k = 0; k < 8; ++k) p[i].c[k] = i < g.n ? g.c[i][k] : 0.0;
  }
}
}  // namespace bl_glsl_u_cpp

namespace glsl_u {
using namespace bl_glsl_u_cpp;
float moment(int kernel, float x, float s, float period, const GlslUPieces& g, float fmax) {
  BlPiece p[4];
  to_glsl(g, p);
  if (kernel == 0) return bl_gauss_periodic_u_image(x, s, period, g.n, p, fmax);
  if (kernel == 1) return bl_box_periodic_u(x, s, period, g.n, p);
  return bl_tent_periodic_u(x, s, period, g.n, p);
}
}  // namespace glsl_u

#else
// ---------------------------------------------------------------------------------------------
// The test executable.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "support.hpp"

#ifdef BL_HAVE_GLSL_AS_CPP
namespace glsl_u {
float moment(int kernel, float x, float s, float period, const GlslUPieces& g, float fmax);
}
#endif

namespace {

namespace bd = bl::detail;
using bd::Piece;
using ld = long double;
using mp50 = boost::multiprecision::cpp_bin_float_50;

constexpr double kTolDouble = 1e-9;
constexpr double kTolFloat = 2e-5;
const ld kPiL = 3.14159265358979323846264338327950288L;
const ld kInvSqrt2PiL = 0.398942280401432677939946059934381868L;

enum Kernel { kGauss = 0, kBox = 1, kTent = 2 };
const char* kname(int k) {
  static const char* n[] = {"gauss", "box", "tent"};
  return n[k];
}
ld kernel_scale(int k) {  // support half-width per unit sigma (Gaussian: the quadrature reach)
  return k == kGauss ? 38.0L : (k == kBox ? std::sqrt(3.0L) : std::sqrt(6.0L));
}
// E[U^-] / sigma = E[max(-U, 0)] / sigma: 1/sqrt(2 pi), sqrt(3)/4, sqrt(6)/6.
ld half_abs_moment(int k) {
  return k == kGauss ? kInvSqrt2PiL : (k == kBox ? std::sqrt(3.0L) / 4 : std::sqrt(6.0L) / 6);
}

// ---------------------------------------------------------------------------------------------
// Test functions. Reference side: one period as plain pieces (lo, hi, polynomial lambda in the
// coordinate within the period). Code side: Piece<T>[] with the same polynomials as coefficients.
struct RefPiece {
  ld lo, hi;
  ld (*f)(ld);
};
struct TestFn {
  const char* name;
  ld period;
  std::vector<RefPiece> pieces;
  ld mean;
  double fmax;
};
enum FnId { kSaw, kSawSq, kSquare, kTri, kNumFn };
const TestFn& fn(int id) {
  static const TestFn f[] = {
      {"fract", 1, {{0, 1, [](ld t) { return t; }}}, 0.5L, 1.0},
      {"fract^2", 1, {{0, 1, [](ld t) { return t * t; }}}, 1.0L / 3, 1.0},
      {"square", 1, {{0, 0.5L, [](ld) { return ld(1); }}, {0.5L, 1, [](ld) { return ld(0); }}},
       0.5L, 1.0},
      {"triangle", 2, {{0, 1, [](ld t) { return t; }}, {1, 2, [](ld t) { return 2 - t; }}}, 0.5L,
       1.0}};
  return f[id];
}

template <class T>
Piece<T> mk(T lo, T hi, std::initializer_list<T> c) {
  Piece<T> p{lo, hi, {}};
  for (int k = 0; k < bd::kMaxCoef; ++k) p.c[k] = T(0);
  int k = 0;
  for (const T& v : c) p.c[k++] = v;
  return p;
}
template <class T>
struct Fns {
  Piece<T> saw[1], sawsq[1], sq[2], tri[2];
  Fns() {
    const T Z = T(0), O = T(1), H = T(1) / T(2);
    saw[0] = mk<T>(Z, O, {Z, O});
    sawsq[0] = mk<T>(Z, O, {Z, Z, O});
    sq[0] = mk<T>(Z, H, {O});
    sq[1] = mk<T>(H, O, {Z});
    tri[0] = mk<T>(Z, O, {Z, O});
    tri[1] = mk<T>(O, T(2), {T(2), -O});
  }
};
template <class T>
const Fns<T>& fns() {
  static const Fns<T> f;
  return f;
}

template <class T>
T u_call(int id, int kernel, T x, T s) {
  const Fns<T>& F = fns<T>();
  auto go = [&](const auto& p, T period) -> T {
    switch (kernel) {
      case kGauss: return bd::gauss_periodic_u_image(x, s, period, p, T(1));
      case kBox: return bd::box_periodic_u(x, s, period, p);
      default: return bd::tent_periodic_u(x, s, period, p);
    }
  };
  switch (id) {
    case kSaw: return go(F.saw, T(1));
    case kSawSq: return go(F.sawsq, T(1));
    case kSquare: return go(F.sq, T(1));
    default: return go(F.tri, T(2));
  }
}

#ifdef BL_HAVE_GLSL_AS_CPP
template <int N>
GlslUPieces to_g(const Piece<float> (&p)[N]) {
  GlslUPieces g{};
  g.n = N;
  for (int i = 0; i < N; ++i) {
    g.lo[i] = p[i].lo;
    g.hi[i] = p[i].hi;
    for (int k = 0; k < 8; ++k) g.c[i][k] = p[i].c[k];
  }
  return g;
}
float glsl_u_call(int id, int kernel, float x, float s) {
  const Fns<float>& F = fns<float>();
  switch (id) {
    case kSaw: return glsl_u::moment(kernel, x, s, 1.0f, to_g(F.saw), 1.0f);
    case kSawSq: return glsl_u::moment(kernel, x, s, 1.0f, to_g(F.sawsq), 1.0f);
    case kSquare: return glsl_u::moment(kernel, x, s, 1.0f, to_g(F.sq), 1.0f);
    default: return glsl_u::moment(kernel, x, s, 2.0f, to_g(F.tri), 1.0f);
  }
}
#endif

// ---------------------------------------------------------------------------------------------
// Quadrature reference.
using GKL = boost::math::quadrature::gauss_kronrod<ld, 31>;
using GL7 = boost::math::quadrature::gauss<ld, 7>;

// Exact reduction x = q P + r for the test periods 1 and 2 (fmod is exact).
ld reduce_exact(double x, double period) {
  double r = std::fmod(x, period);
  if (r < 0) r += period;
  if (r >= period) r = 0;
  return r;
}

ld eval_fn(const TestFn& F, ld t) {  // right-continuous, t any
  const ld m = std::floor(t / F.period);
  const ld r = t - m * F.period;
  for (const RefPiece& p : F.pieces)
    if (r < p.hi) return p.f(r);
  return F.pieces.back().f(r);
}

ld density(int k, ld u, ld s) {
  if (k == kGauss) return kInvSqrt2PiL * std::exp(-0.5L * (u / s) * (u / s)) / s;
  if (k == kBox) return 1 / (2 * std::sqrt(3.0L) * s);
  const ld w = std::sqrt(6.0L) * s;
  return std::max(ld(0), w - std::fabs(u)) / (w * w);
}

// E[U^j (g(x_r + U) - c)] with c = g(x_r) (j = 1, the moment) or c = 0 (j = 0, E g): quadrature in
// u over the kernel's support, split at every break b + m P - x_r, at 0 (the tent's kink), and on
// a grid of one sigma for the Gaussian. In each segment the period m and the piece are fixed (from
// the segment midpoint) and the piece polynomial is evaluated at (x_r - m P) + u.
struct RefOut {
  ld m1, eg;
};
RefOut ref_quad(const TestFn& F, int k, ld xr, ld s) {
  const ld R = kernel_scale(k) * s;
  std::vector<ld> cuts = {-R, 0, R};
  if (k == kGauss)
    for (int j = -37; j <= 37; ++j) cuts.push_back(j * s);
  const ld m0 = std::floor((xr - R) / F.period) - 1, m1 = std::floor((xr + R) / F.period) + 1;
  for (ld m = m0; m <= m1; m += 1)
    for (const RefPiece& p : F.pieces) {
      const ld u = (p.lo + m * F.period) - xr;
      if (u > -R && u < R) cuts.push_back(u);
    }
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  const ld c = eval_fn(F, xr);
  ld m1sum = 0, egsum = 0;
  for (size_t i = 0; i + 1 < cuts.size(); ++i) {
    const ld a = cuts[i], b = cuts[i + 1];
    if (!(b > a)) continue;
    const ld um = 0.5L * (a + b);
    const ld mm = std::floor((xr + um) / F.period);
    const ld base = xr - mm * F.period;  // exact: m P is an integer (times 2)
    const ld rm = base + um;
    const RefPiece* pc = &F.pieces.back();
    for (const RefPiece& p : F.pieces)
      if (rm < p.hi) {
        pc = &p;
        break;
      }
    auto f1 = [&](ld u) { return u * (pc->f(base + u) - c) * density(k, u, s); };
    auto f0 = [&](ld u) { return pc->f(base + u) * density(k, u, s); };
    if (k == kGauss) {
      m1sum += GKL::integrate(f1, a, b, 4, 1e-17L);
      egsum += GKL::integrate(f0, a, b, 4, 1e-17L);
    } else {  // polynomial integrands of degree <= 8: the 7-point Gauss rule is exact
      m1sum += GL7::integrate(f1, a, b);
      egsum += GL7::integrate(f0, a, b);
    }
  }
  return {m1sum, egsum};
}

// Stein: E[U g(x+U)] = sigma^2 (E[g_reg'(x+U)] + sum_jumps J phi_sigma(x - t_J)) for the Gaussian.
// Sums over the jump lattice: direct for sigma < 0.3, Poisson (Fourier) beyond.
ld lattice_phi(ld x, ld a, ld P, ld s) {  // sum_m phi_sigma(x - a - m P)
  ld sum = 0;
  if (s < 0.3L * P) {
    const ld c = std::floor((x - a) / P);
    for (ld m = c - 40; m <= c + 41; m += 1) {
      const ld z = (x - a - m * P) / s;
      sum += kInvSqrt2PiL * std::exp(-0.5L * z * z) / s;
    }
    return sum;
  }
  sum = 1 / P;
  for (int k = 1; k < 100; ++k) {
    const ld e = std::exp(-2 * kPiL * kPiL * k * k * s * s / (P * P));
    if (e < 1e-40L) break;
    sum += 2 / P * std::cos(2 * kPiL * k * (x - a) / P) * e;
  }
  return sum;
}
// P(x + U in [a, b) mod P), Gaussian (E of the indicator of one interval per period).
ld lattice_prob(ld x, ld a, ld b, ld P, ld s) {
  if (s < 0.3L * P) {
    ld sum = 0;
    const ld c = std::floor((x - a) / P);
    for (ld m = c - 40; m <= c + 41; m += 1) {
      const ld za = (a + m * P - x) / s, zb = (b + m * P - x) / s;
      sum += 0.5L * (std::erfc(-zb / std::sqrt(2.0L)) - std::erfc(-za / std::sqrt(2.0L)));
    }
    return sum;
  }
  // Fourier: indicator of [a, b) = (b - a)/P + sum_k (sin(2pi k (t - a)/P) - sin(2pi k (t - b)/P))/(pi k)
  ld sum = (b - a) / P;
  for (int k = 1; k < 100; ++k) {
    const ld e = std::exp(-2 * kPiL * kPiL * k * k * s * s / (P * P));
    if (e < 1e-40L) break;
    sum += (std::sin(2 * kPiL * k * (x - a) / P) - std::sin(2 * kPiL * k * (x - b) / P)) / (kPiL * k) * e;
  }
  return sum;
}
// E[fract(x + U)], Gaussian: 1/2 - sum sin(2 pi k x) e^{-2 pi^2 k^2 s^2}/(pi k) (s >= 0.3), else
// sum over periods of (x - m)(Phi(b) - Phi(a)) + s (phi(a) - phi(b)).
ld gauss_fract_mean(ld x, ld s) {
  if (s >= 0.3L) {
    ld sum = 0.5L;
    for (int k = 1; k < 100; ++k) {
      const ld e = std::exp(-2 * kPiL * kPiL * k * k * s * s);
      if (e < 1e-40L) break;
      sum -= std::sin(2 * kPiL * k * x) * e / (kPiL * k);
    }
    return sum;
  }
  ld sum = 0;
  const ld c = std::floor(x);
  for (ld m = c - 40; m <= c + 40; m += 1) {
    const ld za = (m - x) / s, zb = (m + 1 - x) / s;
    const ld pr = 0.5L * (std::erfc(-zb / std::sqrt(2.0L)) - std::erfc(-za / std::sqrt(2.0L)));
    sum += (x - m) * pr + s * kInvSqrt2PiL * (std::exp(-0.5L * za * za) - std::exp(-0.5L * zb * zb));
  }
  return sum;
}
ld ref_stein(int id, ld xr, ld s) {
  const ld s2 = s * s;
  switch (id) {
    case kSaw: return s2 * (1 - lattice_phi(xr, 0, 1, s));  // g' = 1 - sum delta(t - m)
    case kSawSq: return s2 * (2 * gauss_fract_mean(xr, s) - lattice_phi(xr, 0, 1, s));
    case kSquare: return s2 * (lattice_phi(xr, 0, 1, s) - lattice_phi(xr, 0.5L, 1, s));
    default:  // triangle: g' = +1 on [0,1), -1 on [1,2) (period 2)
      return s2 * (2 * lattice_prob(xr, 0, 1, 2, s) - 1);
  }
}

// ---------------------------------------------------------------------------------------------
struct Worst {
  std::map<std::string, double> w;
  std::map<std::string, std::string> where;
  void add(const std::string& label, double e, const std::string& at) {
    if (!w.count(label) || e > w[label] || std::isnan(e)) {
      w[label] = e;
      where[label] = at;
    }
  }
  void print(const char* title) const {
    for (const auto& kv : w)
      std::printf("[worst] %-22s %-26s %.3g  at %s\n", title, kv.first.c_str(), kv.second,
                  where.at(kv.first).c_str());
  }
};
std::string at_str(int id, int k, double x, double s) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "%s/%s x=%.17g sigma=%.3g", fn(id).name, kname(k), x, s);
  return buf;
}
double err_scaled(double got, ld ref, double x, ld eg) {
  if (std::isnan(got)) return std::numeric_limits<double>::infinity();
  const ld scale = std::max({ld(1), std::fabs(ld(x)) * std::fabs(eg), std::fabs(ref)});
  return double(std::fabs(ld(got) - ref) / scale);
}

const std::vector<double>& xs_double() {
  static const std::vector<double> v = {0.0, 1e-9, 1 - 1e-9, 0.37, -2.6, 1e6 + 0.3};
  return v;
}
const std::vector<double>& xs_float() {
  static const std::vector<double> v = {0.0, 1e-9, 1 - 1e-9, 0.37, -2.6, 1e4 + 0.3};
  return v;
}
const std::vector<double>& sigmas() {
  static const std::vector<double> v = {1e-12, 1e-6, 0.01, 0.3, 2, 50, 1e4};
  return v;
}

// Reference cache (the wide box/tent quadratures take ~10^5 segments).
RefOut ref_cached(int id, int k, ld xr, ld s) {
  static std::map<std::tuple<int, int, ld, ld>, RefOut> cache;
  const auto key = std::make_tuple(id, k, xr, s);
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  return cache[key] = ref_quad(fn(id), k, xr, s);
}

// ---------------------------------------------------------------------------------------------
TEST(SupportU, ReferencesAgree) {
  // Quadrature and Stein agree for the Gaussian (where the quadrature is affordable).
  Worst W;
  for (int id = 0; id < kNumFn; ++id)
    for (double x : xs_double())
      for (double s : sigmas()) {
        if (s > 50) continue;
        const ld xr = reduce_exact(x, double(fn(id).period));
        const RefOut q = ref_cached(id, kGauss, xr, s);
        const ld st = ref_stein(id, xr, s);
        const double e = double(std::fabs(q.m1 - st) / std::max(ld(s) * s, std::fabs(st)));
        W.add("quad vs stein rel", e, at_str(id, kGauss, x, s));
        // the quadrature evaluates g at (x_r - m P) + u in long double: relative accuracy
        // ~ eps_ld x_r / sigma for tiny sigma (Stein is exact there)
        const double tol = 1e-12 + 64 * double(std::numeric_limits<ld>::epsilon()) / s;
        EXPECT_LE(e, tol) << at_str(id, kGauss, x, s) << " quad " << double(q.m1) << " stein "
                            << double(st);
      }
  W.print("ReferencesAgree");
}

TEST(SupportU, DoubleAgainstQuadratureAndStein) {
  Worst W;
  for (int id = 0; id < kNumFn; ++id)
    for (int k = 0; k < 3; ++k)
      for (double x : xs_double())
        for (double s : sigmas()) {
          const ld xr = reduce_exact(x, double(fn(id).period));
          const double got = u_call<double>(id, k, x, s);
          const bool quad_ok = !(k == kGauss && s > 50);
          const RefOut q = quad_ok ? ref_cached(id, k, xr, s) : RefOut{0, fn(id).mean};
          std::vector<std::pair<const char*, ld>> refs;
          if (quad_ok) refs.push_back({"quad", q.m1});
          if (k == kGauss) refs.push_back({"stein", ref_stein(id, xr, s)});
          for (const auto& r : refs) {
            const double e = err_scaled(got, r.second, x, q.eg);
            W.add(std::string("double ") + kname(k) + " vs " + r.first, e, at_str(id, k, x, s));
            EXPECT_LE(e, kTolDouble) << at_str(id, k, x, s) << " got " << got << " ref "
                                     << double(r.second) << " (" << r.first << ")";
          }
        }
  W.print("Double");
}

TEST(SupportU, FloatAgainstQuadratureAndStein) {
  Worst W;
  for (int id = 0; id < kNumFn; ++id)
    for (int k = 0; k < 3; ++k)
      for (double xd : xs_float())
        for (double sd : sigmas()) {
          const float x = float(xd), s = float(sd);
          if (k == kGauss && s > 50) continue;  // see FloatGaussianWide
          const ld xr = reduce_exact(x, double(fn(id).period));
          const RefOut q = ref_cached(id, k, xr, s);
          const ld ref = k == kGauss ? ref_stein(id, xr, s) : q.m1;
          const double e = err_scaled(u_call<float>(id, k, x, s), ref, x, q.eg);
          W.add(std::string("float ") + kname(k), e, at_str(id, k, x, s));
          EXPECT_LE(e, kTolFloat) << "float " << at_str(id, k, x, s) << " got "
                                  << u_call<float>(id, k, x, s) << " ref " << double(ref);
#ifdef BL_HAVE_GLSL_AS_CPP
          const double eg = err_scaled(glsl_u_call(id, k, x, s), ref, x, q.eg);
          W.add(std::string("glsl ") + kname(k), eg, at_str(id, k, x, s));
          EXPECT_LE(eg, kTolFloat) << "glsl " << at_str(id, k, x, s) << " got "
                                   << glsl_u_call(id, k, x, s) << " ref " << double(ref);
#endif
        }
  W.print("Float");
}

// The image sum in float at sigma >> period: terms of adjacent pieces cancel from ~sigma fmax, so
// the error grows like eps sigma (the caller's Fourier form is used there). Measured, bounded
// loosely: 2e-5 of max(1, |x E g|, |ref|, sigma/100).
TEST(SupportU, FloatGaussianWide) {
  Worst W;
  for (int id = 0; id < kNumFn; ++id)
    for (double xd : xs_float()) {
      const float x = float(xd), s = 1e4f;
      const ld xr = reduce_exact(x, double(fn(id).period));
      const ld ref = ref_stein(id, xr, s);
      const float got = u_call<float>(id, kGauss, x, s);
      const double e = err_scaled(got, ref, x, fn(id).mean);
      W.add("float gauss sigma=1e4", e, at_str(id, kGauss, x, s));
      EXPECT_LE(e, kTolFloat * std::max(1.0, double(s) / 100)) << at_str(id, kGauss, x, s);
    }
  W.print("FloatGaussianWide");
}

// Tiny kernels: relative accuracy against exact closed forms. Inside a piece (degree <= 2):
// E[U q(x + U)] = q'(x) sigma^2. Centred on the jump at 0: fract sigma^2 - c sigma, fract^2
// sigma^2 - c sigma, square c sigma, triangle (kink) 0, c = E[U^-]/sigma.
TEST(SupportU, TinyKernelsRelative) {
  Worst W;
  for (int id = 0; id < kNumFn; ++id)
    for (int k = 0; k < 3; ++k)
      for (double s : {1e-12, 1e-9, 1e-6, 1e-4}) {
        struct Case {
          double x;
          ld ref;
        };
        const ld s2 = ld(s) * s, c = half_abs_moment(k) * s;
        std::vector<Case> cases;
        for (double x : {0.37, 1e-3, 1 - 1e-3, -2.6, 1e6 + 0.3}) {
          const ld xr = reduce_exact(x, double(fn(id).period));
          ld d = 0;  // q'(x_r)
          if (id == kSaw) d = 1;
          if (id == kSawSq) d = 2 * xr;
          if (id == kTri) d = xr < 1 ? 1 : -1;
          cases.push_back({x, d * s2});
        }
        const ld at0[] = {s2 - c, s2 - c, c, 0};
        cases.push_back({0.0, at0[id]});
        for (const Case& cs : cases) {
          const double got = u_call<double>(id, k, cs.x, s);
          const double e = double(std::fabs(got - cs.ref) / std::max(s2, std::fabs(cs.ref)));
          W.add(std::string("double ") + kname(k) + " rel", e, at_str(id, k, cs.x, s));
          EXPECT_LE(e, 1e-13) << at_str(id, k, cs.x, s) << " got " << got << " ref "
                              << double(cs.ref);
          if (std::fabs(cs.x) < 1e4 && s >= 1e-9) {
            const float xf = float(cs.x), sf = float(s);
            // the float inputs: recompute the closed form at them
            const ld xr = reduce_exact(xf, double(fn(id).period)), s2f = ld(sf) * sf;
            const ld cf = half_abs_moment(k) * sf;
            ld ref = 0;
            if (cs.x == 0.0) {
              const ld a0[] = {s2f - cf, s2f - cf, cf, 0};
              ref = a0[id];
            } else {
              const ld d = id == kSaw ? 1 : id == kSawSq ? 2 * xr : id == kTri ? (xr < 1 ? 1 : -1) : 0;
              ref = d * s2f;
            }
            const float gf = u_call<float>(id, k, xf, sf);
            const double ef = double(std::fabs(gf - ref) / std::max(s2f, std::fabs(ref)));
            W.add(std::string("float ") + kname(k) + " rel", ef, at_str(id, k, xf, sf));
            EXPECT_LE(ef, 2e-6) << "float " << at_str(id, k, xf, sf) << " got " << gf << " ref "
                                << double(ref);
#ifdef BL_HAVE_GLSL_AS_CPP
            const float gg = glsl_u_call(id, k, xf, sf);
            const double eg = double(std::fabs(gg - ref) / std::max(s2f, std::fabs(ref)));
            W.add(std::string("glsl ") + kname(k) + " rel", eg, at_str(id, k, xf, sf));
            EXPECT_LE(eg, 2e-6) << "glsl " << at_str(id, k, xf, sf) << " got " << gg << " ref "
                                << double(ref);
#endif
          }
        }
      }
  // x just below a period boundary (|x| below eps period): the kernel sits left of the jump at 0,
  // M = q'(T^-) sigma^2, not the value at the jump (x reduced onto 0 would give ~ c sigma).
  const double dleft[] = {1, 2, 0, -1};  // q' at the end of the period
  for (int id = 0; id < kNumFn; ++id)
    for (int k = 0; k < 3; ++k) {
      const double s = 1e-22, ref = dleft[id] * s * s;
      const double got = u_call<double>(id, k, -1e-20, s);
      const double e = std::fabs(got - ref) / (s * s);
      W.add(std::string("double ") + kname(k) + " rel", e, at_str(id, k, -1e-20, s));
      EXPECT_LE(e, 1e-13) << at_str(id, k, -1e-20, s) << " got " << got;
      const float sf = 1e-18f, xf = -1e-16f;
      const double reff = dleft[id] * double(sf) * double(sf);
      const double ef = std::fabs(u_call<float>(id, k, xf, sf) - reff) / (double(sf) * sf);
      W.add(std::string("float ") + kname(k) + " rel", ef, at_str(id, k, xf, sf));
      EXPECT_LE(ef, 2e-6) << "float " << at_str(id, k, xf, sf);
#ifdef BL_HAVE_GLSL_AS_CPP
      const double eg = std::fabs(glsl_u_call(id, k, xf, sf) - reff) / (double(sf) * sf);
      W.add(std::string("glsl ") + kname(k) + " rel", eg, at_str(id, k, xf, sf));
      EXPECT_LE(eg, 2e-6) << "glsl " << at_str(id, k, xf, sf);
#endif
    }
  W.print("TinyKernelsRelative");
}

// Random x and sigma (log-uniform, across the few-/many-period switch h, w = 2 period), plus sigma
// at the switch itself and sigma that puts x_r +- h (box) exactly on a break, against quadrature.
TEST(SupportU, RandomizedAgainstQuadrature) {
  Worst W;
  unsigned long long st = 0x9E3779B97F4A7C15ull;
  auto uni = [&]() {  // xorshift, [0, 1)
    st ^= st << 13;
    st ^= st >> 7;
    st ^= st << 17;
    return double(st >> 11) * (1.0 / 9007199254740992.0);
  };
  struct Case {
    int id, k;
    double x, s;
  };
  std::vector<Case> cases;
  for (int i = 0; i < 240; ++i) {
    const int id = i % kNumFn, k = (i / kNumFn) % 3;
    const double x = 20 * uni() - 10;
    const double s = std::pow(10.0, (k == kGauss ? 4.5 : 6.0) * uni() - 3.0);
    cases.push_back({id, k, x, s});
  }
  for (int id = 0; id < kNumFn; ++id) {
    const double P = double(fn(id).period);
    for (double f : {1 - 1e-15, 1.0, 1 + 1e-15}) {
      cases.push_back({id, kBox, 0.37, f * 2 * P / std::sqrt(3.0)});
      cases.push_back({id, kTent, 0.37, f * 2 * P / std::sqrt(6.0)});
    }
    // x_r + h on a break: h = 3.5 - 0.25 (x = 0.25, h = 3.25: x + h = 3.5, x - h = -3)
    cases.push_back({id, kBox, 0.25, 3.25 / std::sqrt(3.0)});
    cases.push_back({id, kTent, 0.25, 3.25 / std::sqrt(6.0)});
  }
  for (const Case& c : cases) {
    const ld xr = reduce_exact(c.x, double(fn(c.id).period));
    const RefOut q = ref_quad(fn(c.id), c.k, xr, c.s);
    const double got = u_call<double>(c.id, c.k, c.x, c.s);
    const double e = err_scaled(got, q.m1, c.x, q.eg);
    W.add(std::string("double ") + kname(c.k), e, at_str(c.id, c.k, c.x, c.s));
    EXPECT_LE(e, kTolDouble) << at_str(c.id, c.k, c.x, c.s) << " got " << got << " ref "
                             << double(q.m1);
    const float xf = float(c.x), sf = float(c.s);
    const ld xrf = reduce_exact(xf, double(fn(c.id).period));
    const RefOut qf = ref_quad(fn(c.id), c.k, xrf, sf);
    const double ef = err_scaled(u_call<float>(c.id, c.k, xf, sf), qf.m1, xf, qf.eg);
    W.add(std::string("float ") + kname(c.k), ef, at_str(c.id, c.k, xf, sf));
    EXPECT_LE(ef, kTolFloat) << "float " << at_str(c.id, c.k, xf, sf);
#ifdef BL_HAVE_GLSL_AS_CPP
    const double eg = err_scaled(glsl_u_call(c.id, c.k, xf, sf), qf.m1, xf, qf.eg);
    W.add(std::string("glsl ") + kname(c.k), eg, at_str(c.id, c.k, xf, sf));
    EXPECT_LE(eg, kTolFloat) << "glsl " << at_str(c.id, c.k, xf, sf);
#endif
  }
  W.print("Randomized");
}

TEST(SupportU, SpecialArguments) {
  const Fns<double>& F = fns<double>();
  for (double x : {0.0, 0.37, -1e6}) {
    EXPECT_EQ(bd::gauss_periodic_u_image(x, 0.0, 1.0, F.saw, 1.0), 0.0);
    EXPECT_EQ(bd::box_periodic_u(x, 0.0, 1.0, F.sq), 0.0);
    EXPECT_EQ(bd::tent_periodic_u(x, 0.0, 2.0, F.tri), 0.0);
    for (double s : {-1.0, -1e-300, std::nan(""), std::numeric_limits<double>::infinity()}) {
      EXPECT_TRUE(std::isnan(bd::gauss_periodic_u_image(x, s, 1.0, F.saw, 1.0))) << s;
      EXPECT_TRUE(std::isnan(bd::box_periodic_u(x, s, 1.0, F.saw))) << s;
      EXPECT_TRUE(std::isnan(bd::tent_periodic_u(x, s, 1.0, F.saw))) << s;
    }
  }
  EXPECT_TRUE(std::isnan(bd::box_periodic_u(std::nan(""), 1.0, 1.0, F.saw)));
  EXPECT_TRUE(std::isnan(bd::tent_periodic_u(std::numeric_limits<double>::infinity(), 1.0, 1.0, F.saw)));
  Piece<double> deg7[1] = {mk<double>(0, 1, {0, 0, 0, 0, 0, 0, 0, 1})};
  EXPECT_TRUE(std::isnan(bd::box_periodic_u(0.3, 0.1, 1.0, deg7)));
  EXPECT_EQ(bd::box_periodic_u(0.0f, 0.0f, 1.0f, fns<float>().saw), 0.0f);
  EXPECT_TRUE(std::isnan(bd::tent_periodic_u(0.0f, -1.0f, 1.0f, fns<float>().saw)));
#ifdef BL_HAVE_GLSL_AS_CPP
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(glsl_u_call(kSaw, k, 0.37f, 0.0f), 0.0f);
    EXPECT_TRUE(std::isnan(glsl_u_call(kSaw, k, 0.37f, -1.0f)));
  }
#endif
}

// Degree 6 input (smoothstep^2 made periodic: (3t^2 - 2t^3)^2 on [0, 1), period 1) and a period
// that is not a power of two (0.3, pieces scaled): against quadrature in double.
TEST(SupportU, HighDegreeAndOddPeriod) {
  Worst W;
  const TestFn ss2{"ss2", 1, {{0, 1, [](ld t) { const ld u = t * t * (3 - 2 * t); return u * u; }}}, 0.5L, 1.0};
  const Piece<double> p6[1] = {mk<double>(0, 1, {0, 0, 0, 0, 9, -12, 4})};
  const TestFn saw03{"saw03", 0.3L, {{0, 0.3L, [](ld t) { return t; }}}, 0.15L, 0.3};
  const double P = 0.3;
  const Piece<double> p03[1] = {mk<double>(0, P, {0, 1})};
  for (int k = 0; k < 3; ++k)
    for (double x : {0.0, 0.37, -2.6, 1e3 + 0.1})
      for (double s : {1e-6, 0.01, 0.3, 2.0, 50.0}) {
        const ld xr = reduce_exact(x, 1.0);
        const RefOut q = ref_quad(ss2, k, xr, s);
        const double got = k == 0 ? bd::gauss_periodic_u_image(x, s, 1.0, p6, 1.0)
                                  : (k == 1 ? bd::box_periodic_u(x, s, 1.0, p6)
                                            : bd::tent_periodic_u(x, s, 1.0, p6));
        const double e = err_scaled(got, q.m1, x, q.eg);
        W.add(std::string("deg6 ") + kname(k), e, at_str(0, k, x, s));
        EXPECT_LE(e, kTolDouble) << "deg6 " << kname(k) << " " << x << " " << s;
        // period 0.3 (fmod exact in double; reference reduction in long double of the same x)
        const ld xr3 = std::fmod(ld(x), ld(P)) + (x < 0 ? ld(P) : 0);
        const RefOut q3 = ref_quad(saw03, k, xr3 >= ld(P) ? 0 : xr3, s);
        const double g3 = k == 0 ? bd::gauss_periodic_u_image(x, s, P, p03, P)
                                 : (k == 1 ? bd::box_periodic_u(x, s, P, p03)
                                           : bd::tent_periodic_u(x, s, P, p03));
        const double e3 = err_scaled(g3, q3.m1, x, q3.eg);
        W.add(std::string("period 0.3 ") + kname(k), e3, at_str(0, k, x, s));
        EXPECT_LE(e3, kTolDouble) << "period 0.3 " << kname(k) << " " << x << " " << s;
      }
  W.print("HighDegreeAndOddPeriod");
}

// The engine's use: Var(floor(X)), X = x + U, as E[floor^2] - E[floor]^2 with E[floor^2] =
// (x^2 + sigma^2) - 2 (x E fract + M) + E fract^2 and E floor = x - E fract, against
// Var(X - fract X) = sigma^2 - 2 Cov(U, fract(x+U)) + Var(fract) from the quadratures
// (Cov(U, fract(x+U)) = E[U (fract(x+U) - c)] for any constant c). Scale max(1, x^2): the
// formula itself cancels x^2.
TEST(SupportU, FloorVarianceIdentity) {
  Worst W;
  for (int k = 0; k < 3; ++k)
    for (double x : {0.0, 0.37, -2.6, 1e3 + 0.3})
      for (double s : {0.01, 0.3, 2.0}) {
        const ld xr = reduce_exact(x, 1.0);
        const RefOut qf = ref_quad(fn(kSaw), k, xr, s), qf2 = ref_quad(fn(kSawSq), k, xr, s);
        const double Ef = double(qf.eg), Ef2 = double(qf2.eg);
        const double M = u_call<double>(kSaw, k, x, s);
        const double var = (x * x + s * s) - 2 * (x * Ef + M) + Ef2 - (x - Ef) * (x - Ef);
        const ld vref = ld(s) * s - 2 * qf.m1 + (qf2.eg - qf.eg * qf.eg);
        const double e = double(std::fabs(var - vref)) / std::max(1.0, x * x);
        W.add(std::string("var floor ") + kname(k), e, at_str(kSaw, k, x, s));
        EXPECT_LE(e, 1e-9) << kname(k) << " " << x << " " << s << " var " << var << " ref "
                           << double(vref);
      }
  W.print("FloorVarianceIdentity");
}

// Multiprecision instantiation agrees (and the image sum keeps its accuracy there).
TEST(SupportU, Multiprecision) {
  Worst W;
  for (int id = 0; id < kNumFn; ++id)
    for (int k = 0; k < 3; ++k)
      for (double x : {0.37, 1 - 1e-9})
        for (double s : {1e-6, 0.3, 2.0}) {
          const ld xr = reduce_exact(x, double(fn(id).period));
          const RefOut q = ref_cached(id, k, xr, s);
          const double got = static_cast<double>(u_call<mp50>(id, k, mp50(x), mp50(s)));
          const double e = err_scaled(got, q.m1, x, q.eg);
          W.add("mp50", e, at_str(id, k, x, s));
          EXPECT_LE(e, 1e-14) << at_str(id, k, x, s);
        }
  W.print("Multiprecision");
}

// Cost of the image sum at sigma/period ~ 1 stays small (a handful of periods).
TEST(SupportU, ImageSumCost) {
  const Fns<double>& F = fns<double>();
  const auto t0 = std::chrono::steady_clock::now();
  double acc = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) acc += bd::gauss_periodic_u_image(0.37 + 1e-5 * i, 1.0, 1.0, F.sq, 1.0);
  const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() / n;
  std::printf("[cost] gauss_periodic_u_image square wave, sigma = period: %.2f us per call (%g)\n", us, acc);
  EXPECT_LT(us, 200.0);
}

// The GLSL file (with this section) compiles as a fragment shader in both dialects, calling the
// three new entry points.
TEST(SupportU, GlslValidates) {
#ifndef BL_GLSLANG_VALIDATOR
  GTEST_SKIP() << "glslangValidator was not found at configure time; GLSL not validated";
#else
  std::ifstream in(BL_SUPPORT_GLSL);
  ASSERT_TRUE(in.good()) << BL_SUPPORT_GLSL;
  std::stringstream body;
  body << in.rdbuf();
  const char* main_src = R"(
layout(location = 0) out vec4 bl_frag;
void main() {
  BlPiece p[4];
  for (int i = 0; i < 4; ++i) {
    p[i].lo = 0.25 * float(i); p[i].hi = 0.25 * float(i + 1);
    for (int k = 0; k < 8; ++k) p[i].c[k] = 0.0;
  }
  float x = gl_FragCoord.x;
  float r = bl_gauss_periodic_u_image(x, 0.1, 1.0, 4, p, 1.0) + bl_box_periodic_u(x, 0.1, 1.0, 4, p)
      + bl_box_periodic_u(x, 10.0, 1.0, 4, p) + bl_tent_periodic_u(x, 0.1, 1.0, 4, p)
      + bl_tent_periodic_u(x, 10.0, 1.0, 4, p);
  bl_frag = vec4(r);
}
)";
  const std::string headers[2] = {"#version 450\n",
                                  "#version 320 es\nprecision highp float;\nprecision highp int;\n"};
  const char* tags[2] = {"450", "320es"};
  for (int v = 0; v < 2; ++v) {
    const std::string base = ::testing::TempDir() + "bl_support_u_" + tags[v] + "_" +
                             std::to_string(::getpid());
    const std::string src = base + ".frag", log = base + ".log";
    {
      std::ofstream o(src);
      o << headers[v] << body.str() << main_src;
    }
    const std::string cmd = std::string("\"") + BL_GLSLANG_VALIDATOR + "\" -S frag \"" + src +
                            "\" > \"" + log + "\" 2>&1";
    const int rc = std::system(cmd.c_str());
    std::ifstream lg(log);
    std::stringstream ls;
    ls << lg.rdbuf();
    EXPECT_EQ(rc, 0) << "glslangValidator failed for " << tags[v] << ":\n" << ls.str();
    std::remove(src.c_str());
    std::remove(log.c_str());
  }
#endif
}

}  // namespace
#endif  // BL_SUPPORT_GLSL_AS_CPP
