// Tests of the runtime support library: rulegen/templates/support.hpp (float, double,
// cpp_bin_float_50) and rulegen/templates/support.glsl (validated with glslangValidator as
// `#version 450` and `#version 320 es`, and executed as C++ float code, see below).
//
// Error measure: |got - ref| / max(1, |ref|); bounds 1e-9 in double, 2e-5 in float (the float
// reference is the double reference at the float-rounded inputs). References never call the code
// under test: Boost.Math Gauss-Kronrod quadrature split at every break (Gaussian in z =
// (t-x)/sigma, box/tent in u = (t-x)/h), Fourier series from the literature, the smoothing paper's
// Appendix C closed form evaluated naively in 50 digits, or elementary closed forms.
//
// This file is compiled twice. Normally it is the gtest executable. With BL_SUPPORT_GLSL_AS_CPP it
// is a separate object, built with -fsingle-precision-constant (GCC), that includes support.glsl
// as C++ (shims for the few GLSL built-ins it uses) and exports float wrappers, so the GLSL code
// runs through the same float checks as the C++ header.

#include <cmath>

struct GlslPieces {  // the GLSL BlPiece[4] layout, free of GLSL types
  int n;
  float lo[4];
  float hi[4];
  float c[4][8];
};

#ifdef BL_SUPPORT_GLSL_AS_CPP
// ---------------------------------------------------------------------------------------------
// GLSL compiled as C++ float code.
#include <algorithm>

namespace bl_glsl_cpp {
using std::abs;
using std::ceil;
using std::exp;
using std::floor;
using std::log;
using std::sin;
using std::sinh;
using std::sqrt;
using std::trunc;
inline float min(float a, float b) { return b < a ? b : a; }
inline float max(float a, float b) { return a < b ? b : a; }
inline int max(int a, int b) { return a < b ? b : a; }
inline float clamp(float x, float a, float b) { return min(max(x, a), b); }
struct vec2 {
  float x, y;
  vec2(float a, float b) : x(a), y(b) {}
};
// GLSL `out` is only used on array parameters, which C++ passes as pointers.
#define out
#include "support.glsl"
#undef out

inline void to_glsl(const GlslPieces& g, BlPiece* p) {
  for (int i = 0; i < 4; ++i) {
    p[i].lo = i < g.n ? g.lo[i] : 0.0;
    p[i].hi = i < g.n ? g.hi[i] : 0.0;
    for (int k = 0; k < 8; ++k) p[i].c[k] = i < g.n ? g.c[i][k] : 0.0;
  }
}
}  // namespace bl_glsl_cpp

namespace glsl {
using namespace bl_glsl_cpp;
float Phi(float z) { return bl_Phi(z); }
float Phic(float z) { return bl_Phic(z); }
float phi(float z) { return bl_phi(z); }
float sinc(float t) { return bl_sinc(t); }
float sinhc(float t) { return bl_sinhc(t); }
float exp_sinhc(float u, float v) { return bl_exp_sinhc(u, v); }
float exp_sinhc2(float u, float v) { return bl_exp_sinhc2(u, v); }
float logcosh(float x) { return bl_logcosh(x); }
float pw(int kernel, float x, float s, const GlslPieces& g) {
  BlPiece p[4];
  to_glsl(g, p);
  if (kernel == 0) return bl_gauss_pw(x, s, g.n, p);
  if (kernel == 1) return bl_box_pw(x, s, g.n, p);
  if (kernel == 2) return bl_tent_pw(x, s, g.n, p);
  return bl_pw_eval(x, g.n, p);
}
float periodic(int kernel, float x, float s, float period, const GlslPieces& g,
               const GlslPieces& g1, const GlslPieces& g2, float fmax) {
  BlPiece p[4], p1[4], p2[4];
  to_glsl(g, p);
  to_glsl(g1, p1);
  to_glsl(g2, p2);
  if (kernel == 0) return bl_gauss_periodic_image(x, s, period, g.n, p, fmax);
  if (kernel == 1) return bl_box_periodic(x, s, period, g.n, p, p1);
  if (kernel == 2) return bl_tent_periodic(x, s, period, g.n, p, p1, p2);
  return bl_periodic_eval(x, period, g.n, p);
}
int fourier_terms(float s, float b, float tol) { return bl_fourier_terms(s, b, tol); }
int image_periods(float s, float fmax, float tol) { return bl_image_periods(s, fmax, tol); }
bool prefer_fourier(float s, int np, float b, float fmax) {
  return bl_prefer_fourier(s, np, b, fmax);
}
}  // namespace glsl

#else
// ---------------------------------------------------------------------------------------------
// The test executable.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/special_functions/erf.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "support.hpp"

#ifdef BL_HAVE_GLSL_AS_CPP
namespace glsl {
float Phi(float z);
float Phic(float z);
float phi(float z);
float sinc(float t);
float sinhc(float t);
float exp_sinhc(float u, float v);
float exp_sinhc2(float u, float v);
float logcosh(float x);
float pw(int kernel, float x, float s, const GlslPieces& g);
float periodic(int kernel, float x, float s, float period, const GlslPieces& g,
               const GlslPieces& g1, const GlslPieces& g2, float fmax);
int fourier_terms(float s, float b, float tol);
int image_periods(float s, float fmax, float tol);
bool prefer_fourier(float s, int np, float b, float fmax);
}  // namespace glsl
#endif

namespace {

namespace bd = bl::detail;
using bd::Piece;
using mp50 = boost::multiprecision::cpp_bin_float_50;

constexpr double kTolDouble = 1e-9;
constexpr float kTolFloat = 2e-5f;
const double kInf = std::numeric_limits<double>::infinity();
const double kPi = 3.141592653589793238462643;

double err_of(double got, double ref) {
  if (std::isnan(got)) return kInf;
  return std::fabs(got - ref) / std::max(1.0, std::fabs(ref));
}

// Worst error per label, printed by the tests that fill it (numbers for the report).
struct Worst {
  std::map<std::string, double> w;
  std::map<std::string, std::string> where;
  void add(const std::string& label, double e, const std::string& at) {
    if (!w.count(label) || e > w[label]) {
      w[label] = e;
      where[label] = at;
    }
  }
  void print(const char* title) const {
    for (const auto& kv : w)
      std::printf("[worst] %-40s %-28s %.3g  at %s\n", title, kv.first.c_str(), kv.second,
                  where.at(kv.first).c_str());
  }
};

std::string at_str(const char* fn, const char* kern, double x, double s) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "%s/%s x=%.17g sigma=%.3g", fn, kern, x, s);
  return buf;
}

// ---------------------------------------------------------------------------------------------
// Test functions: independent plain definitions (reference side). f(t, tm) evaluates at t the
// piece that contains tm (a point inside the same quadrature segment), so a quadrature node that
// rounds onto a break (x + h u == break in floating point) still gets its own piece's formula.
// f(t, t) is the plain right-continuous function.
using RefF = double (*)(double t, double tm);
double f_ss2(double t, double tm) {  // smoothstep^2, the degree-6 piece (3t^2 - 2t^3)^2 on [0, 1)
  if (tm < 0) return 0;
  if (tm < 1) {
    double u = t * t * (3 - 2 * t);
    return u * u;
  }
  return 1;
}
double f_abs(double t, double tm) { return tm < 0 ? -t : t; }
double f_step(double, double tm) { return tm >= 0 ? 1.0 : 0.0; }
double f_sat(double t, double tm) { return tm < 0 ? 0.0 : (tm < 1 ? t : 1.0); }
double f_saw(double t, double tm) { return t - std::floor(tm); }  // fract, period 1
double f_tri(double t, double tm) {  // period 2: t on [0,1), 2-t on [1,2)
  const double m = 2 * std::floor(tm / 2);
  return tm - m < 1 ? t - m : 2 - (t - m);
}
double f_sq(double, double tm) {  // period 1: 1 on [0, 0.5), 0 on [0.5, 1)
  return tm - std::floor(tm) < 0.5 ? 1.0 : 0.0;
}
double q_eval(const double* c, double t) {  // plain power sum (reference side)
  double s = 0, tk = 1;
  for (int k = 0; k < 8; ++k, tk *= t) s += c[k] * tk;
  return s;
}

// ... and the same functions as pieces (input of the code under test), with the first and second
// integrals over one period for the periodic ones (checked against quadrature below).
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
  Piece<T> ss2[3], abs_[2], step[2], sat[3];
  Piece<T> saw[1], saw1[1], saw2[1];
  Piece<T> tri[2], tri1[2], tri2[2];
  Piece<T> sq[2], sq1[2], sq2[2];
  Fns() {
    const T I = bd::inf<T>(), Z = T(0), O = T(1), H = T(1) / T(2);
    ss2[0] = mk<T>(-I, Z, {Z});
    ss2[1] = mk<T>(Z, O, {Z, Z, Z, Z, T(9), T(-12), T(4)});
    ss2[2] = mk<T>(O, I, {O});
    abs_[0] = mk<T>(-I, Z, {Z, -O});
    abs_[1] = mk<T>(Z, I, {Z, O});
    step[0] = mk<T>(-I, Z, {Z});
    step[1] = mk<T>(Z, I, {O});
    sat[0] = mk<T>(-I, Z, {Z});
    sat[1] = mk<T>(Z, O, {Z, O});
    sat[2] = mk<T>(O, I, {O});
    saw[0] = mk<T>(Z, O, {Z, O});
    saw1[0] = mk<T>(Z, O, {Z, Z, H});
    saw2[0] = mk<T>(Z, O, {Z, Z, Z, O / T(6)});
    tri[0] = mk<T>(Z, O, {Z, O});
    tri[1] = mk<T>(O, T(2), {T(2), -O});
    tri1[0] = mk<T>(Z, O, {Z, Z, H});
    tri1[1] = mk<T>(O, T(2), {-O, T(2), -H});
    tri2[0] = mk<T>(Z, O, {Z, Z, Z, O / T(6)});
    tri2[1] = mk<T>(O, T(2), {O / T(3), -O, O, -O / T(6)});
    sq[0] = mk<T>(Z, H, {O});
    sq[1] = mk<T>(H, O, {Z});
    sq1[0] = mk<T>(Z, H, {Z, O});
    sq1[1] = mk<T>(H, O, {H});
    sq2[0] = mk<T>(Z, H, {Z, Z, H});
    sq2[1] = mk<T>(H, O, {-O / T(8), H});
  }
};
template <class T>
const Fns<T>& fns() {
  static const Fns<T> f;
  return f;
}

enum Kernel { kGauss = 0, kBox = 1, kTent = 2, kEval = 3 };
const char* kname(int k) {
  static const char* n[] = {"gauss", "box", "tent", "eval"};
  return n[k];
}

// Whole-line test functions.
enum PwId { kSs2, kAbs, kStep, kSat, kNumPw };
struct PwInfo {
  const char* name;
  RefF f;
  std::vector<double> breaks;
};
const PwInfo& pw_info(int id) {
  static const PwInfo info[] = {{"smoothstep2", f_ss2, {0.0, 1.0}},
                                {"abs", f_abs, {0.0}},
                                {"step", f_step, {0.0}},
                                {"saturate", f_sat, {0.0, 1.0}}};
  return info[id];
}

template <class T>
T pw_call(int id, int kernel, T x, T s) {
  const Fns<T>& F = fns<T>();
  auto go = [&](const auto& p) -> T {
    switch (kernel) {
      case kGauss:
        return bd::gauss_pw(x, s, p);
      case kBox:
        return bd::box_pw(x, s, p);
      case kTent:
        return bd::tent_pw(x, s, p);
      default:
        return bd::pw_eval(x, p);
    }
  };
  switch (id) {
    case kSs2:
      return go(F.ss2);
    case kAbs:
      return go(F.abs_);
    case kStep:
      return go(F.step);
    default:
      return go(F.sat);
  }
}

// Periodic test functions.
enum PerId { kSaw, kTri, kSq, kNumPer };
struct PerInfo {
  const char* name;
  RefF f;
  double period;
  std::vector<double> breaks;  // in [0, period)
  double mean;
  // first and second integral over one period, plain formulas (for the Appendix C reference)
  mp50 (*Fp)(const mp50&);
  mp50 (*Fp2)(const mp50&);
};
mp50 saw_F1(const mp50& t) { return t * t / 2; }
mp50 saw_F2(const mp50& t) { return t * t * t / 6; }
mp50 tri_F1(const mp50& t) { return t < 1 ? mp50(t * t / 2) : mp50(-1 + 2 * t - t * t / 2); }
mp50 tri_F2(const mp50& t) {
  return t < 1 ? mp50(t * t * t / 6) : mp50(mp50(1) / 3 - t + t * t - t * t * t / 6);
}
mp50 sq_F1(const mp50& t) { return t < mp50(0.5) ? t : mp50(0.5); }
mp50 sq_F2(const mp50& t) { return t < mp50(0.5) ? mp50(t * t / 2) : mp50(t / 2 - mp50(0.125)); }
const PerInfo& per_info(int id) {
  static const PerInfo info[] = {{"sawtooth", f_saw, 1.0, {0.0}, 0.5, saw_F1, saw_F2},
                                 {"triangle", f_tri, 2.0, {0.0, 1.0}, 0.5, tri_F1, tri_F2},
                                 {"square", f_sq, 1.0, {0.0, 0.5}, 0.5, sq_F1, sq_F2}};
  return info[id];
}

template <class T>
T per_call(int id, int kernel, T x, T s) {
  const Fns<T>& F = fns<T>();
  auto go = [&](const auto& p, const auto& p1, const auto& p2, T period) -> T {
    switch (kernel) {
      case kGauss:
        return bd::gauss_periodic_image(x, s, period, p, T(1));
      case kBox:
        return bd::box_periodic(x, s, period, p, p1);
      case kTent:
        return bd::tent_periodic(x, s, period, p, p1, p2);
      default:
        return bd::periodic_eval(x, period, p);
    }
  };
  switch (id) {
    case kSaw:
      return go(F.saw, F.saw1, F.saw2, T(1));
    case kTri:
      return go(F.tri, F.tri1, F.tri2, T(2));
    default:
      return go(F.sq, F.sq1, F.sq2, T(1));
  }
}

#ifdef BL_HAVE_GLSL_AS_CPP
template <int N>
GlslPieces to_g(const Piece<float> (&p)[N]) {
  GlslPieces g{};
  g.n = N;
  for (int i = 0; i < N; ++i) {
    g.lo[i] = std::isinf(p[i].lo) ? (p[i].lo < 0 ? -1e30f : 1e30f) : p[i].lo;
    g.hi[i] = std::isinf(p[i].hi) ? (p[i].hi < 0 ? -1e30f : 1e30f) : p[i].hi;
    for (int k = 0; k < 8; ++k) g.c[i][k] = p[i].c[k];
  }
  return g;
}
float glsl_pw_call(int id, int kernel, float x, float s) {
  const Fns<float>& F = fns<float>();
  switch (id) {
    case kSs2:
      return glsl::pw(kernel, x, s, to_g(F.ss2));
    case kAbs:
      return glsl::pw(kernel, x, s, to_g(F.abs_));
    case kStep:
      return glsl::pw(kernel, x, s, to_g(F.step));
    default:
      return glsl::pw(kernel, x, s, to_g(F.sat));
  }
}
float glsl_per_call(int id, int kernel, float x, float s) {
  const Fns<float>& F = fns<float>();
  switch (id) {
    case kSaw:
      return glsl::periodic(kernel, x, s, 1.0f, to_g(F.saw), to_g(F.saw1), to_g(F.saw2), 1.0f);
    case kTri:
      return glsl::periodic(kernel, x, s, 2.0f, to_g(F.tri), to_g(F.tri1), to_g(F.tri2), 1.0f);
    default:
      return glsl::periodic(kernel, x, s, 1.0f, to_g(F.sq), to_g(F.sq1), to_g(F.sq2), 1.0f);
  }
}
#endif

// ---------------------------------------------------------------------------------------------
// References.
using GK = boost::math::quadrature::gauss_kronrod<double, 31>;

template <class F>
double gk(F f, double a, double b) {
  if (!(b > a)) return 0.0;
  return GK::integrate(f, a, b, 8, 1e-12);  // |G15 - K31| is pessimistic: K31 is far better
}

// Integral of g over [lo, hi] split at the grid lo + k*step and at the points `cuts`.
template <class G>
double split_integral(G g, double lo, double hi, double step, std::vector<double> cuts) {
  std::vector<double> pts;
  for (double z = lo; z < hi; z += step) pts.push_back(z);
  pts.push_back(hi);
  for (double c : cuts)
    if (c > lo && c < hi) pts.push_back(c);
  std::sort(pts.begin(), pts.end());
  double s = 0;
  for (size_t i = 0; i + 1 < pts.size(); ++i) {
    const double mid = 0.5 * (pts[i] + pts[i + 1]);
    s += gk([&](double u) { return g(u, mid); }, pts[i], pts[i + 1]);
  }
  return s;
}

// Break points of f near x: the whole-line breaks, or all shifted periodic breaks within
// [x - R, x + R].
std::vector<double> breaks_near(const std::vector<double>& brk, double period, double x, double R) {
  if (period == 0) return brk;
  std::vector<double> out;
  double m0 = std::floor((x - R) / period) - 1, m1 = std::floor((x + R) / period) + 1;
  for (double m = m0; m <= m1; m += 1)
    for (double b : brk) out.push_back(b + m * period);
  return out;
}

constexpr double kZ = 38.0;  // phi(38) ~ 1e-314: nothing beyond matters

// E f(x + sigma Z), Z ~ N(0,1): quadrature in z over [-38, 38], unit grid plus every break.
double ref_gauss(RefF f, const std::vector<double>& brk, double period, double x, double s) {
  if (s == 0) return f(x, x);
  std::vector<double> cuts;
  for (double b : breaks_near(brk, period, x, kZ * s)) cuts.push_back((b - x) / s);
  auto g = [&](double z, double zm) {
    return f(x + s * z, x + s * zm) * std::exp(-0.5 * z * z) * 0.3989422804014327;
  };
  return split_integral(g, -kZ, kZ, 1.0, cuts);
}
// Box: (1/2) int_{-1}^{1} f(x + h u) du; tent: int_{-1}^{1} f(x + w u)(1 - |u|) du.
double ref_box(RefF f, const std::vector<double>& brk, double period, double x, double s) {
  if (s == 0) return f(x, x);
  const double h = std::sqrt(3.0) * s;
  std::vector<double> cuts;
  for (double b : breaks_near(brk, period, x, h)) cuts.push_back((b - x) / h);
  auto g = [&](double u, double um) { return 0.5 * f(x + h * u, x + h * um); };
  return split_integral(g, -1.0, 1.0, 0.125, cuts);
}
double ref_tent(RefF f, const std::vector<double>& brk, double period, double x, double s) {
  if (s == 0) return f(x, x);
  const double w = std::sqrt(6.0) * s;
  std::vector<double> cuts;
  for (double b : breaks_near(brk, period, x, w)) cuts.push_back((b - x) / w);
  auto g = [&](double u, double um) { return f(x + w * u, x + w * um) * (1 - std::fabs(u)); };
  return split_integral(g, -1.0, 1.0, 0.125, cuts);
}
double ref_kernel(int kernel, RefF f, const std::vector<double>& brk, double period, double x,
                  double s) {
  switch (kernel) {
    case kGauss:
      return ref_gauss(f, brk, period, x, s);
    case kBox:
      return ref_box(f, brk, period, x, s);
    case kTent:
      return ref_tent(f, brk, period, x, s);
    default:
      return f(x, x);
  }
}

// Exact reduction of x for the periodic references: the signed remainder fmod(x, period) is
// exact, so E f(x + U) = E f(x_r + U) holds exactly (x_r may be negative: f is periodic; adding
// the period would round).
double reduce_exact(double x, double period) { return std::fmod(x, period); }

// Gaussian-smoothed Fourier series (literature closed forms).
double fourier_gauss(int id, double x, double s) {
  double sum = 0.5;
  if (id == kSaw) {  // fract: 1/2 - sum sin(2 pi n x) e^{-2 pi^2 n^2 s^2} / (pi n)
    for (int n = 1; n < 100000; ++n) {
      double e = std::exp(-2 * kPi * kPi * double(n) * n * s * s);
      if (e < 1e-22) break;
      sum -= std::sin(2 * kPi * n * reduce_exact(x, 1.0)) * e / (kPi * n);
    }
  } else if (id == kSq) {  // 1/2 + sum_{n odd} 2 sin(2 pi n x) / (pi n) e^{-2 pi^2 n^2 s^2}
    for (int n = 1; n < 100000; n += 2) {
      double e = std::exp(-2 * kPi * kPi * double(n) * n * s * s);
      if (e < 1e-22) break;
      sum += 2 * std::sin(2 * kPi * n * reduce_exact(x, 1.0)) * e / (kPi * n);
    }
  } else {  // triangle, period 2: 1/2 - (4/pi^2) sum_{n odd} cos(n pi x)/n^2 e^{-n^2 pi^2 s^2/2}
    for (int n = 1; n < 100000; n += 2) {
      double e = std::exp(-0.5 * kPi * kPi * double(n) * n * s * s);
      if (e < 1e-22) break;
      sum -= 4 / (kPi * kPi) * std::cos(kPi * n * reduce_exact(x, 2.0)) * e / (double(n) * n);
    }
  }
  return sum;
}

// Smoothing paper, Appendix C (C.2)-(C.5), evaluated as printed, on the unreduced x, in 50 digits.
double appendix_c(int id, int kernel, double xd, double sd) {
  const PerInfo& P = per_info(id);
  const mp50 T = P.period, x = xd, s = sd;
  auto F = [&](const mp50& y) {
    mp50 q = floor(y / T);
    return q * P.Fp(T) + P.Fp(y - T * q);
  };
  auto F2 = [&](const mp50& y) {
    mp50 q = floor(y / T);
    return P.Fp(T) * (T * (q - 1) * q / 2 + (y - q * T) * q) + P.Fp2(T) * q + P.Fp2(y - q * T);
  };
  if (kernel == kBox) {
    mp50 h = sqrt(mp50(3)) * s;
    return static_cast<double>((F(x + h) - F(x - h)) / (2 * h));
  }
  mp50 w = sqrt(mp50(6)) * s;
  return static_cast<double>((F2(x + w) - 2 * F2(x) + F2(x - w)) / (w * w));
}

// ---------------------------------------------------------------------------------------------
// Scalar helpers.

TEST(SupportScalar, PolyIsHorner) {
  const double c[8] = {0.5, -1.25, 3, 0.125, -2, 1.5, 0.75, -0.0625};
  for (double t : {-3.0, -0.4, 0.0, 0.7, 2.5}) {
    mp50 ref = 0, tk = 1;
    for (int k = 0; k < 8; ++k, tk *= t) ref += mp50(c[k]) * tk;
    EXPECT_LE(err_of(bd::poly(c, t), static_cast<double>(ref)), 1e-14) << t;
  }
}

TEST(SupportScalar, NormalCdfPdfTails) {
  Worst W;
  for (double z = -37; z <= 37; z += 0.37) {
    mp50 zz = z;
    mp50 phic = boost::math::erfc(zz / sqrt(mp50(2))) / 2;
    mp50 phiv = exp(-zz * zz / 2) / sqrt(2 * boost::math::constants::pi<mp50>());
    double rc = static_cast<double>(phic);
    double rl = static_cast<double>(boost::math::erfc(-zz / sqrt(mp50(2))) / 2);
    double rp = static_cast<double>(phiv);
    // relative accuracy in both tails (the point of using erfc)
    double e1 = std::fabs(bd::Phic(z) - rc) / rc, e2 = std::fabs(bd::Phi(z) - rl) / rl;
    double e3 = std::fabs(bd::phi(z) - rp) / rp;
    W.add("double Phic/Phi/phi rel", std::max({e1, e2, e3}), std::to_string(z));
    EXPECT_LE(std::max({e1, e2, e3}), 2e-13) << z;  // z/sqrt2 rounding costs ~z^2 eps
    if (std::fabs(z) < 12) {
      const float zf = float(z);
      mp50 zr = zf;
      double rcf = static_cast<double>(boost::math::erfc(zr / sqrt(mp50(2))) / 2);
      double rlf = static_cast<double>(boost::math::erfc(-zr / sqrt(mp50(2))) / 2);
      double rpf =
          static_cast<double>(exp(-zr * zr / 2) / sqrt(2 * boost::math::constants::pi<mp50>()));
      double f1 = std::fabs(bd::Phic(zf) - rcf) / rcf, f2 = std::fabs(bd::Phi(zf) - rlf) / rlf;
      double f3 = std::fabs(bd::phi(zf) - rpf) / rpf;
      W.add("float Phic/Phi/phi rel", std::max({f1, f2, f3}), std::to_string(z));
      EXPECT_LE(std::max({f1, f2, f3}), 2e-5) << z;
#ifdef BL_HAVE_GLSL_AS_CPP
      double g1 = std::fabs(glsl::Phic(zf) - rcf) / rcf, g2 = std::fabs(glsl::Phi(zf) - rlf) / rlf;
      double g3 = std::fabs(glsl::phi(zf) - rpf) / rpf;
      W.add("glsl Phic/Phi/phi rel", std::max({g1, g2, g3}), std::to_string(z));
      EXPECT_LE(std::max({g1, g2, g3}), 2e-5) << z;
#endif
    }
  }
  W.print("NormalCdfPdfTails");
}

// The float erfcx/erfc (support.hpp: erfcx_f, stated bound 4e-7 relative; erfc_f 6e-7) against
// long double erfc on a dense grid and at hard points (0, tiny, the fit's worst point, where erfc
// underflows, up to 1e37 where the result is still normal, inf); phi_Phic against 50-digit Phic.
TEST(SupportScalar, FastFloatErfcx) {
  auto ref = [](long double t) {  // e^{t^2} erfc(t): product below 50, continued fraction beyond
    if (t < 50) return std::exp(t * t) * std::erfc(t);
    long double f = t;
    for (int k = 200; k >= 1; --k) f = t + k * 0.5L / f;
    return 0.564189583547756286948L / f;
  };
  Worst W;
  double worst = 0, worst_c = 0;
  std::vector<float> ts = {0.0f,  1e-30f,      1e-7f, 0.0294f, 1.0f,  2.0f, 9.5f,
                           10.0f, 10.0546875f, 26.5f, 1e4f,    1e19f, 1e37f};
  for (int i = 0; i <= 200000; ++i) ts.push_back(float(i * 1e-4));
  for (int i = 0; i <= 4000; ++i) ts.push_back(float(std::pow(10.0, -8 + i * 0.01)));
  for (float t : ts) {
    const long double r = ref(t);
    const double e = double(std::fabs((bd::erfcx_f(t) - r) / r));
    worst = std::max(worst, e);
    EXPECT_LE(e, 4e-7) << "erfcx_f(" << t << ")";
    const long double rc = std::erfc((long double)t);
    if (rc > 1e-37L) {  // normal float range
      const double ec = double(std::fabs((bd::erfc_f(t) - rc) / rc));
      const double en = double(std::fabs((bd::erfc_f(-t) - (2 - rc)) / (2 - rc)));
      worst_c = std::max({worst_c, ec, en});
      EXPECT_LE(ec, 6e-7) << "erfc_f(" << t << ")";
      EXPECT_LE(en, 6e-7) << "erfc_f(" << -t << ")";
    }
  }
  EXPECT_EQ(bd::erfcx_f(std::numeric_limits<float>::infinity()), 0.0f);
  EXPECT_GE(bd::erfcx_f(3e38f), 0.0f);  // true value 1.9e-39 (subnormal): 2t + 1 overflows to inf
  EXPECT_EQ(bd::erfc_f(std::numeric_limits<float>::infinity()), 0.0f);
  EXPECT_EQ(bd::erfc_f(-std::numeric_limits<float>::infinity()), 2.0f);
  EXPECT_TRUE(std::isnan(bd::erfcx_f(std::numeric_limits<float>::quiet_NaN())));
  W.add("erfcx_f rel", worst, "grid");
  W.add("erfc_f rel", worst_c, "grid");
  for (double t = 0; t < 12; t += 0.12) {  // phi_Phic: float pair and the double pair
    float ph, pc;
    bd::phi_Phic(float(t), ph, pc);
    const mp50 z = mp50(float(t));
    const double rc = static_cast<double>(boost::math::erfc(z / sqrt(mp50(2))) / 2);
    const double rp = static_cast<double>(exp(-z * z / 2) / sqrt(2 * boost::math::constants::pi<mp50>()));
    EXPECT_LE(std::fabs(pc - rc) / rc, 1e-5) << t;  // t^2/2 rounding in phi: <= 72 ulp at t = 12
    EXPECT_LE(std::fabs(ph - rp) / rp, 1e-5) << t;
    double phd, pcd;
    bd::phi_Phic(t, phd, pcd);
    EXPECT_EQ(pcd, bd::Phic(t));
    EXPECT_EQ(phd, bd::phi(t));
  }
  W.print("FastFloatErfcx");
}

// tail_laplace's V_k(al) = int_0^inf u^k e^{-al u - u^2/2} du (Miller levels by al and deg, the
// double upward range) against Gauss-Kronrod, and the double erfcx (product with the exact t^2
// split, then the short fractions) against long double erfc.
TEST(SupportScalar, TailLaplaceAndDoubleErfcx) {
  Worst W;
  for (double al : {0.5, 1.9, 2.0, 2.5, 3.0, 3.5, 4.0, 4.9, 5.0, 5.5, 6.0, 7.0, 8.0, 10.0, 12.0,
                    15.0, 20.0, 25.0, 30.0, 50.0, 200.0, 1e4}) {
    double Vd[8];
    float Vf[8];
    for (int deg = 1; deg <= 7; ++deg) {
      bd::tail_laplace(al, deg, Vd);
      bd::tail_laplace(float(al), deg, Vf);
      for (int k = 0; k <= deg; ++k) {
        const double hi = std::min(40.0, 50.0 / al);
        auto g = [&](double u) { return std::pow(u, k) * std::exp(-al * u - 0.5 * u * u); };
        double ref = 0;
        for (int j = 0; j < 40; ++j) ref += gk(g, hi * j / 40, hi * (j + 1) / 40);
        const double ed = std::fabs(Vd[k] - ref) / ref, ef = std::fabs(Vf[k] - ref) / ref;
        W.add("double V_k rel", ed, std::to_string(al));
        W.add("float V_k rel", ef, std::to_string(al));
        EXPECT_LE(ed, 1e-12) << "al " << al << " deg " << deg << " k " << k;
        // float below al = 2 runs upwards: V_7(1.9) loses ~70x of V_0's 3e-7 (measured 2.1e-5)
        EXPECT_LE(ef, al < 2 ? 5e-5 : 2e-6) << "al " << al << " deg " << deg << " k " << k;
      }
    }
  }
  double worst = 0;
  for (double t = 0; t < 300; t += (t < 50 ? 0.01 : 0.37)) {
    const long double tl = t;
    long double r;
    if (t < 100) {
      r = std::exp(tl * tl) * std::erfc(tl);
    } else {
      long double f = tl;
      for (int k = 400; k >= 1; --k) f = tl + k * 0.5L / f;
      r = 0.564189583547756286948L / f;
    }
    const double e = double(std::fabs((bd::erfcx(t) - r) / r));
    worst = std::max(worst, e);
    EXPECT_LE(e, 2e-15) << "erfcx(" << t << ")";
  }
  W.add("double erfcx rel", worst, "grid");
  W.print("TailLaplaceAndDoubleErfcx");
}

// sinc, sinhc, logcosh against 50-digit evaluations of the definitions (relative errors).
TEST(SupportScalar, SincSinhcLogcosh) {
  Worst W;
  EXPECT_EQ(bd::sinc(0.0), 1.0);
  EXPECT_EQ(bd::sinc(0.0f), 1.0f);
  EXPECT_EQ(bd::sinhc(0.0), 1.0);
  EXPECT_EQ(bd::logcosh(0.0), 0.0);
  auto rel = [](double got, const mp50& ref) {
    double r = static_cast<double>(ref);
    return std::fabs(got - r) / std::fabs(r);
  };
  for (double t : {1e-300, 1e-9, 1e-5, 0.05, 0.0999, 0.1001, 0.3,  0.4999, 0.5001, 0.9999, 1.0001,
                   3.0,    19.9, 20.1, 30.0, 39.9,   40.1,   80.0, 700.0,  705.0,  711.0}) {
    for (double sg : {1.0, -1.0}) {
      const double x = sg * t;
      const mp50 X = x;
      const float xf = float(x);
      const mp50 XF = xf;
      const bool fok = t > 1e-30;  // representable in float
      // sinc
      const double e1 = rel(bd::sinc(x), sin(X) / X);
      W.add("double sinc rel", e1, std::to_string(x));
      EXPECT_LE(e1, 4e-16) << x;
      if (fok) {
        const double e1f = rel(bd::sinc(xf), sin(XF) / XF);
        W.add("float sinc rel", e1f, std::to_string(x));
        EXPECT_LE(e1f, 4e-7) << x;
#ifdef BL_HAVE_GLSL_AS_CPP
        if (t < 100) {
          const double e1g = rel(glsl::sinc(xf), sin(XF) / XF);
          W.add("glsl sinc rel", e1g, std::to_string(x));
          EXPECT_LE(e1g, 1e-6) << x;
        }
#endif
      }
      // sinhc: relative error may grow like t eps (conditioning of sinh at large t)
      const double e2 = rel(bd::sinhc(x), sinh(X) / X);
      W.add("double sinhc rel/max(1,t)", e2 / std::max(1.0, t), std::to_string(x));
      EXPECT_LE(e2, 4e-16 * std::max(1.0, t)) << x;
      EXPECT_TRUE(std::isfinite(bd::sinhc(x))) << x;  // 711: sinh overflows, sinhc does not
      if (fok && t < 80) {
        const double e2f = rel(bd::sinhc(xf), sinh(XF) / XF);
        W.add("float sinhc rel/max(1,t)", e2f / std::max(1.0, t), std::to_string(x));
        EXPECT_LE(e2f, 4e-7 * std::max(1.0, t)) << x;
#ifdef BL_HAVE_GLSL_AS_CPP
        const double e2g = rel(glsl::sinhc(xf), sinh(XF) / XF);
        W.add("glsl sinhc rel/max(1,t)", e2g / std::max(1.0, t), std::to_string(x));
        EXPECT_LE(e2g, 1e-6 * std::max(1.0, t)) << x;
#endif
      }
      // logcosh, relative (x^2/2 near 0: the form that avoids cancellation)
      if (t > 1e-150) {  // log cosh(1e-300) = 5e-601 underflows
        const double e3 = rel(bd::logcosh(x), log(cosh(X)));
        W.add("double logcosh rel", e3, std::to_string(x));
        EXPECT_LE(e3, 1e-15) << x;
      }
      if (fok) {
        const double e3f = rel(bd::logcosh(xf), log(cosh(XF)));
        W.add("float logcosh rel", e3f, std::to_string(x));
        EXPECT_LE(e3f, 4e-7) << x;
#ifdef BL_HAVE_GLSL_AS_CPP
        const double e3g = rel(glsl::logcosh(xf), log(cosh(XF)));
        W.add("glsl logcosh rel", e3g, std::to_string(x));
        EXPECT_LE(e3g, 1e-6) << x;
#endif
      }
    }
  }
  EXPECT_EQ(bd::sinhc(720.0), kInf);  // true value e^720/1440 overflows
  EXPECT_EQ(bd::sinhc(100.0f), std::numeric_limits<float>::infinity());
  W.print("SincSinhcLogcosh");
}

TEST(SupportScalar, ExpSinhcNoOverflow) {
  Worst W;
  // exp(u) sinhc(v) and exp(u) sinhc(v)^2 where exp(u) underflows and sinhc(v) overflows.
  const double r1 = 1.0 / 1600.0;  // u = -800, v = 800: e^0 (1 - e^{-1600}) / 1600
  EXPECT_LE(std::fabs(bd::exp_sinhc(-800.0, 800.0) - r1) / r1, 1e-15);
  EXPECT_LE(std::fabs(bd::exp_sinhc2(-1600.0, 800.0) - r1 * r1) / (r1 * r1), 1e-15);
  const float r1f = 1.0f / 160.0f;  // float: u = -80, v = 80
  EXPECT_LE(std::fabs(bd::exp_sinhc(-80.0f, 80.0f) - r1f) / r1f, 1e-6);
  EXPECT_LE(std::fabs(bd::exp_sinhc2(-160.0f, 80.0f) - r1f * r1f) / (r1f * r1f), 1e-6);
#ifdef BL_HAVE_GLSL_AS_CPP
  EXPECT_LE(std::fabs(glsl::exp_sinhc(-80.0f, 80.0f) - r1f) / r1f, 1e-6);
  EXPECT_LE(std::fabs(glsl::exp_sinhc2(-160.0f, 80.0f) - r1f * r1f) / (r1f * r1f), 1e-6);
#endif
  for (double u : {-2000.0, -800.0, -50.0, -1.0, 0.0, 2.0, 50.0})
    for (double v : {0.0, 1e-8, 0.5, 1.0, 1.5, 10.0, 100.0, 799.0, 800.0, 1000.0}) {
      mp50 U = u, V = v;
      mp50 s = V == 0 ? mp50(1) : mp50(sinh(V) / V);
      mp50 r = exp(U) * s, r2 = exp(U) * s * s;
      const double g = bd::exp_sinhc(u, v), g2 = bd::exp_sinhc2(u, v);
      EXPECT_FALSE(std::isnan(g) || std::isnan(g2)) << u << " " << v;
      const double rd = static_cast<double>(r), rd2 = static_cast<double>(r2);
      // relative error bounded by the conditioning (|u| + 2v) eps of the exponent
      const double cond = (std::fabs(u) + 2 * v + 1) * 2.3e-16;
      if (std::isfinite(rd) && rd > 1e-300) {
        W.add("double exp_sinhc rel/cond", std::fabs(g - rd) / rd / cond, "");
        EXPECT_LE(std::fabs(g - rd) / rd, 4 * cond) << u << " " << v;
      } else if (std::isinf(rd)) {
        EXPECT_EQ(g, kInf) << u << " " << v;
      }
      if (std::isfinite(rd2) && rd2 > 1e-300) {
        W.add("double exp_sinhc2 rel/cond", std::fabs(g2 - rd2) / rd2 / cond, "");
        EXPECT_LE(std::fabs(g2 - rd2) / rd2, 4 * cond) << u << " " << v;
      }
      const float uf = float(u / 10), vf = float(v / 10);  // the same shapes in float range
      mp50 UF = uf, VF = vf;
      mp50 sf = VF == 0 ? mp50(1) : mp50(sinh(VF) / VF);
      const double rf = static_cast<double>(exp(UF) * sf),
                   rf2 = static_cast<double>(exp(UF) * sf * sf);
      const double condf = (std::fabs(uf) + 2 * vf + 1) * 1.2e-7;
      const float gf = bd::exp_sinhc(uf, vf), gf2 = bd::exp_sinhc2(uf, vf);
      EXPECT_FALSE(std::isnan(gf) || std::isnan(gf2));
      if (rf > 1e-37 && rf < 1e38) {
        EXPECT_LE(std::fabs(gf - rf) / rf, 4 * condf) << uf << " " << vf;
      }
      if (rf2 > 1e-37 && rf2 < 1e38) {
        EXPECT_LE(std::fabs(gf2 - rf2) / rf2, 4 * condf) << uf << " " << vf;
      }
#ifdef BL_HAVE_GLSL_AS_CPP
      const float hg = glsl::exp_sinhc(uf, vf), hg2 = glsl::exp_sinhc2(uf, vf);
      if (rf > 1e-37 && rf < 1e38) {
        EXPECT_LE(std::fabs(hg - rf) / rf, 8 * condf) << uf << " " << vf;
      }
      if (rf2 > 1e-37 && rf2 < 1e38) {
        EXPECT_LE(std::fabs(hg2 - rf2) / rf2, 8 * condf) << uf << " " << vf;
      }
#endif
    }
  W.print("ExpSinhcNoOverflow");
}

// ---------------------------------------------------------------------------------------------
// Per-piece primitives on hard inputs, with *relative* error against quadrature of the single
// piece (stronger than the max(1, |ref|) measure: tails and narrow pieces must not cancel).

double ref_gauss_piece(const double* c, double mu, double s, double lo, double hi) {
  // z-coordinates, clipped to mu +- 38 sigma, unit grid.
  double a = std::max((lo - mu) / s, -kZ), b = std::min((hi - mu) / s, kZ);
  if (!(b > a)) return 0;
  auto g = [&](double z, double) {
    return q_eval(c, mu + s * z) * std::exp(-0.5 * z * z) * 0.3989422804014327;
  };
  if (b - a < 1e-3) {  // narrow piece: integrate in t for an exact polynomial rule
    auto gt = [&](double t) {
      double z = (t - mu) / s;
      return q_eval(c, t) * std::exp(-0.5 * z * z) * 0.3989422804014327 / s;
    };
    return gk(gt, lo, hi);
  }
  return split_integral(g, a, b, std::min(1.0, (b - a) / 4), {});
}

TEST(SupportPiece, GaussPieceNarrowAndTails) {
  Worst W;
  const double ss[8] = {0, 0, 0, 0, 9, -12, 4, 0};  // degree 6 on [0, 1]
  const double one[8] = {1, 0, 0, 0, 0, 0, 0, 0};
  const double lin[8] = {0, 1, 0, 0, 0, 0, 0, 0};
  struct C {
    const double* c;
    double mu, s, lo, hi;
    double tol, tolf;  // relative bounds, double and float (tolf 0: float value underflows)
  };
  const C cases[] = {
      {ss, 0.3, 1e3, 0, 1, 1e-13, 2e-6},       // narrow: width 1e-3 sd
      {ss, 0.3, 1e6, 0, 1, 1e-13, 2e-6},       // width 1e-6 sd (moments would lose everything)
      {ss, -2e6, 1e6, 0, 1, 1e-13, 2e-6},      // narrow and 2 sd away
      {ss, 0.5, 0.5, 0, 1, 1e-13, 2e-6},       // exactly 2 sd wide
      {ss, 0.5, 0.49, 0, 1, 1e-13, 2e-6},      // just over: moments path
      {ss, 0.5, 0.02, 0, 1, 1e-13, 2e-6},      // wide
      {ss, 1.2, 0.1, 0, 1, 1e-12, 2e-5},       // 2 sd beyond the end, wide
      {ss, 6.0, 0.5, 0, 1, 1e-9, 0},           // 10..12 sd into the tail (value 1e-23)
      {ss, -1.0, 0.1, 0, 1, 1e-6, 0},          // 10 sd into the other tail (value 1e-29)
      {one, 0.0, 1.0, 5, 6, 1e-13, 2e-6},      // Phi(6) - Phi(5)
      {one, 0.0, 1.0, 9, 11, 1e-13, 2e-6},     // corner of the quadrature rule: |cz| hw = 10
      {ss, -5.0, 1.0, 0, 1, 1e-13, 2e-6},      // 5..6 sd away, degree 6
      {one, 0.0, 1.0, -30, -29, 1e-11, 0},     // deep lower tail
      {lin, -5.0, 1.0, 0, kInf, 1e-10, 1e-4},  // infinite piece, mu 5 sd to the left
      {lin, 1e15, 1.0, 0, kInf, 1e-15, 0},     // infinite piece, mu huge
      {lin, 1e15, 1e-12, 0, kInf, 1e-15, 0},
      {lin, 1e6, 1e3, 0, kInf, 1e-15, 2e-7},
      {ss, 1.0, 1e-12, 0, 1, 1e-15, 2e-7},  // at the end of the piece, tiny sigma: q(1)/2
      {ss, 1.0 - 1e-9, 1e-8, 0, 1, 1e-13, 2e-6},
  };
  for (const C& k : cases) {
    const double ref = ref_gauss_piece(k.c, k.mu, k.s, k.lo, k.hi);
    const double got = bd::gauss_piece(k.mu, k.s, k.lo, k.hi, k.c);
    const double e = std::fabs(got - ref) / std::fabs(ref);
    W.add("double rel", e, at_str("piece", "gauss", k.mu, k.s));
    EXPECT_LE(e, k.tol) << "mu=" << k.mu << " s=" << k.s << " [" << k.lo << "," << k.hi << ") got "
                        << got << " ref " << ref;
    // float: inputs rounded to float, reference at those inputs
    float cf[8];
    for (int i = 0; i < 8; ++i) cf[i] = float(k.c[i]);
    const float muf = float(k.mu), sf = float(k.s), lof = float(k.lo), hif = float(k.hi);
    if (std::fabs(k.mu) < 1e10) {
      const double reff = ref_gauss_piece(k.c, muf, sf, lof, hif);
      const float gotf = bd::gauss_piece(muf, sf, lof, hif, cf);
      if (k.tolf > 0) {
        const double ef = std::fabs(gotf - reff) / std::fabs(reff);
        W.add("float rel", ef, at_str("piece", "gauss", k.mu, k.s));
        EXPECT_LE(ef, k.tolf) << "float mu=" << k.mu << " s=" << k.s;
      }
      EXPECT_LE(err_of(gotf, reff), kTolFloat) << "float mu=" << k.mu << " s=" << k.s;
    }
  }
  W.print("GaussPieceNarrowAndTails");
}

// Box and tent of t^2 and t^3 around a large x with a tiny kernel: closed forms
// E(x+U)^2 = x^2 + Var, E(x+U)^3 = x^3 + 3x Var (Var = h^2/3 box, w^2/6 tent, sigma^2 Gaussian).
TEST(SupportPiece, MomentsAtLargeXTinyKernel) {
  Worst W;
  const double c2[8] = {0, 0, 1}, c3[8] = {0, 0, 0, 1};
  for (double x : {1e6, -1e6, 3.0, 1e3}) {
    for (double s : {1e-12, 1e-8, 1e-3, 0.2}) {
      const double lo = x - 1, hi = x + 1;
      const double h = std::sqrt(3.0) * s, w = std::sqrt(6.0) * s;
      const mp50 X = x, V = mp50(s) * s;
      const double r2 = static_cast<double>(X * X + V),
                   r3 = static_cast<double>(X * X * X + 3 * X * V);
      const double e[6] = {
          err_of(bd::box_piece(x, h, lo, hi, c2), r2) * std::max(1.0, r2) / r2,
          err_of(bd::box_piece(x, h, lo, hi, c3), r3) * std::max(1.0, std::fabs(r3)) /
              std::fabs(r3),
          err_of(bd::tent_piece(x, w, lo, hi, c2), r2) * std::max(1.0, r2) / r2,
          err_of(bd::tent_piece(x, w, lo, hi, c3), r3) * std::max(1.0, std::fabs(r3)) /
              std::fabs(r3),
          err_of(bd::gauss_piece(x, s, -kInf, kInf, c2), r2) * std::max(1.0, r2) / r2,
          err_of(bd::gauss_piece(x, s, -kInf, kInf, c3), r3) * std::max(1.0, std::fabs(r3)) /
              std::fabs(r3)};
      for (int i = 0; i < 6; ++i) {
        W.add("double rel", e[i], at_str("t^k", "box/tent/gauss", x, s));
        EXPECT_LE(e[i], 1e-14) << i << " x=" << x << " s=" << s;
      }
    }
  }
  W.print("MomentsAtLargeXTinyKernel");
}

// ---------------------------------------------------------------------------------------------
// Whole-line piecewise functions: every kernel, hard x and sigma, double, float (C++ and GLSL).

const std::vector<double>& pw_xs() {
  static const std::vector<double> xs = {0.0,  1.0, 1e-9, -1e-9, 1 + 1e-9, 1 - 1e-9, 0.3,  0.5,
                                         -0.7, 1.5, 2.0,  1e6,   -1e6,     1e15,     -1e15};
  return xs;
}
const std::vector<double>& pw_sigmas() {
  static const std::vector<double> ss = {0.0, 1e-12, 1e-8, 1e-5, 1e-3, 0.1,
                                         0.5, 1.0,   10.0, 1e3,  1e6};
  return ss;
}

TEST(SupportPw, SigmaZeroIsPlainEvaluationRightContinuous) {
  for (int id = 0; id < kNumPw; ++id)
    for (double x : pw_xs()) {
      const double v = pw_call<double>(id, kEval, x, 0.0);
      for (int k = 0; k < 3; ++k) EXPECT_EQ(pw_call<double>(id, k, x, 0.0), v);
      EXPECT_LE(err_of(v, pw_info(id).f(x, x)), 1e-15) << pw_info(id).name << " " << x;
      EXPECT_EQ(pw_call<float>(id, kGauss, float(x), 0.0f),
                pw_call<float>(id, kEval, float(x), 0.0f));
    }
  // right-continuous at jumps
  EXPECT_EQ(pw_call<double>(kStep, kEval, 0.0, 0.0), 1.0);
  EXPECT_EQ(pw_call<double>(kStep, kEval, -1e-300, 0.0), 0.0);
  EXPECT_EQ(pw_call<double>(kSat, kEval, 1.0, 0.0), 1.0);
}

TEST(SupportPw, AllKernelsAgainstQuadrature) {
  Worst W;
  for (int id = 0; id < kNumPw; ++id) {
    const PwInfo& I = pw_info(id);
    for (int k = 0; k < 3; ++k)
      for (double x : pw_xs())
        for (double s : pw_sigmas()) {
          const double ref = ref_kernel(k, I.f, I.breaks, 0, x, s);
          const double got = pw_call<double>(id, k, x, s);
          const double e = err_of(got, ref);
          W.add(std::string("double ") + kname(k), e, at_str(I.name, kname(k), x, s));
          EXPECT_LE(e, kTolDouble)
              << at_str(I.name, kname(k), x, s) << " got " << got << " ref " << ref;
          const float xf = float(x), sf = float(s);
          if (std::fabs(x) > 1e7) continue;  // float: x up to 1e6
          const double reff = ref_kernel(k, I.f, I.breaks, 0, xf, sf);
          const double ef = err_of(pw_call<float>(id, k, xf, sf), reff);
          W.add(std::string("float ") + kname(k), ef, at_str(I.name, kname(k), xf, sf));
          EXPECT_LE(ef, kTolFloat) << "float " << at_str(I.name, kname(k), xf, sf);
#ifdef BL_HAVE_GLSL_AS_CPP
          const double eg = err_of(glsl_pw_call(id, k, xf, sf), reff);
          W.add(std::string("glsl ") + kname(k), eg, at_str(I.name, kname(k), xf, sf));
          EXPECT_LE(eg, kTolFloat) << "glsl " << at_str(I.name, kname(k), xf, sf);
#endif
        }
  }
  W.print("AllKernelsAgainstQuadrature");
}

// Fixed-seed random sweep over x and sigma spanning many decades, near and away from breaks
// (BL_SUPPORT_SWEEP=n sets the samples per function and kernel; default 150).
int sweep_count() {
  const char* e = std::getenv("BL_SUPPORT_SWEEP");
  return e ? std::atoi(e) : 150;
}
struct Rng {  // splitmix64: deterministic across platforms
  uint64_t s;
  double uni() {
    uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  }
  double logu(double lo, double hi) { return std::pow(10.0, lo + (hi - lo) * uni()); }
  double sgn() { return uni() < 0.5 ? -1.0 : 1.0; }
};
// x: near a break (offset 1e-12..1), or anywhere up to 1e6; sigma 1e-12..1e6.
void sample(Rng& g, const std::vector<double>& brk, double period, double& x, double& s) {
  const double u = g.uni();
  if (u < 0.6) {
    const double b = brk[size_t(g.uni() * brk.size()) % brk.size()];
    const double m = period > 0 ? std::floor(g.logu(0, 6) * g.sgn()) * period : 0;
    x = (b + m) + g.sgn() * g.logu(-12, 0);
  } else {
    x = g.sgn() * g.logu(-3, 6);
  }
  s = g.logu(-12, period > 0 ? 3 : 6);
}

TEST(SupportPw, RandomSweep) {
  Worst W;
  Rng g{12345};
  const int n = sweep_count();
  for (int id = 0; id < kNumPw; ++id) {
    const PwInfo& I = pw_info(id);
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < n; ++i) {
        double x, s;
        sample(g, I.breaks, 0, x, s);
        const double ref = ref_kernel(k, I.f, I.breaks, 0, x, s);
        const double e = err_of(pw_call<double>(id, k, x, s), ref);
        W.add(std::string("double ") + kname(k), e, at_str(I.name, kname(k), x, s));
        EXPECT_LE(e, kTolDouble) << at_str(I.name, kname(k), x, s);
        const float xf = float(x), sf = float(s);
        const double reff = ref_kernel(k, I.f, I.breaks, 0, xf, sf);
        const double ef = err_of(pw_call<float>(id, k, xf, sf), reff);
        W.add(std::string("float ") + kname(k), ef, at_str(I.name, kname(k), xf, sf));
        EXPECT_LE(ef, kTolFloat) << "float " << at_str(I.name, kname(k), xf, sf);
#ifdef BL_HAVE_GLSL_AS_CPP
        const double eg = err_of(glsl_pw_call(id, k, xf, sf), reff);
        W.add(std::string("glsl ") + kname(k), eg, at_str(I.name, kname(k), xf, sf));
        EXPECT_LE(eg, kTolFloat) << "glsl " << at_str(I.name, kname(k), xf, sf);
#endif
      }
  }
  W.print("PwRandomSweep");
}

// E|X| for X ~ N(mu, sigma^2) = sigma sqrt(2/pi) e^{-mu^2/2sigma^2} + mu erf(mu/(sigma sqrt 2)),
// and the box/tent closed forms of |x| (|x| when the support misses 0; (x^2 + h^2)/2h for the box
// when it does), for huge |x| including 1e15.
TEST(SupportPw, AbsClosedForms) {
  Worst W;
  for (double x : {0.0, 0.3, -2.0, 1e3, -1e6, 1e15, -1e15, 12345.678})
    for (double s : {1e-12, 1e-8, 0.01, 1.0, 1e3, 1e6, 1e9}) {
      mp50 X = x, S = s;
      mp50 r = S * sqrt(2 / boost::math::constants::pi<mp50>()) * exp(-X * X / (2 * S * S)) +
               X * boost::math::erf(X / (S * sqrt(mp50(2))));
      const double eg = err_of(pw_call<double>(kAbs, kGauss, x, s), static_cast<double>(r));
      W.add("double gauss", eg, at_str("abs", "gauss", x, s));
      EXPECT_LE(eg, kTolDouble) << x << " " << s;
      mp50 H = sqrt(mp50(3)) * S;
      mp50 rb = abs(X) >= H ? mp50(abs(X)) : mp50((X * X + H * H) / (2 * H));
      const double eb = err_of(pw_call<double>(kAbs, kBox, x, s), static_cast<double>(rb));
      W.add("double box", eb, at_str("abs", "box", x, s));
      EXPECT_LE(eb, kTolDouble) << x << " " << s;
      const float xf = float(x), sf = float(s);
      if (std::fabs(xf) < 1e7f && sf < 1e7f) {
        mp50 XF = xf, SF = sf;
        mp50 rf =
            SF * sqrt(2 / boost::math::constants::pi<mp50>()) * exp(-XF * XF / (2 * SF * SF)) +
            XF * boost::math::erf(XF / (SF * sqrt(mp50(2))));
        const double ef = err_of(pw_call<float>(kAbs, kGauss, xf, sf), static_cast<double>(rf));
        W.add("float gauss", ef, at_str("abs", "gauss", xf, sf));
        EXPECT_LE(ef, kTolFloat) << xf << " " << sf;
      }
    }
  W.print("AbsClosedForms");
}

// ---------------------------------------------------------------------------------------------
// Periodic functions.

TEST(SupportPeriodic, IntegralDataIsConsistent) {
  // The P1/P2 inputs (first and second integral over one period) match quadrature of p and P1.
  const Fns<double>& F = fns<double>();
  auto check = [](const auto& p, const auto& p1, const auto& p2, double T) {
    for (double t = 0; t < T; t += T / 16) {
      double i1 = 0, i2 = 0;
      const double b[] = {0, 0.5, 1, 1.5, 2};
      for (int j = 0; j + 1 < 5; ++j) {
        double a = b[j], e = std::min(b[j + 1], t);
        if (e > a) {
          i1 += gk([&](double u) { return bd::periodic_eval(u, T, p); }, a, e);
          i2 += gk([&](double u) { return bd::pw_eval(u, p1); }, a, e);
        }
      }
      EXPECT_NEAR(bd::pw_eval(t, p1), i1, 1e-14) << t;
      EXPECT_NEAR(bd::pw_eval(t, p2), i2, 1e-14) << t;
    }
  };
  check(F.saw, F.saw1, F.saw2, 1.0);
  check(F.tri, F.tri1, F.tri2, 2.0);
  check(F.sq, F.sq1, F.sq2, 1.0);
}

TEST(SupportPeriodic, EvalStaysInRangeForHugeArguments) {
  const Fns<float>& F = fns<float>();
  Piece<float> saw03[1] = {mk<float>(0.0f, 0.3f, {0.0f, 1.0f})};  // t on [0, 0.3): range [0, 0.3)
  for (float x = -1.0e7f; x <= 1.0e7f; x += 999983.0f) {
    for (float d : {0.0f, 0.25f, 0.5f, 0.75f}) {
      const float xx = x + d;
      const float v = bd::periodic_eval(xx, 0.3f, saw03);
      EXPECT_GE(v, 0.0f) << xx;
      EXPECT_LE(v, 0.3f) << xx;  // [0, period] up to the one rounding of r + period
      // exact reduction in double of the float input (period 0.3f is a float value)
      const double r = std::fmod(double(xx), double(0.3f));
      EXPECT_EQ(double(v), r < 0 ? double(float(r) + 0.3f) : r) << xx;
      const float s = bd::periodic_eval(xx, 1.0f, F.saw);
      EXPECT_GE(s, 0.0f);
      EXPECT_LT(s, 1.0f);
      const double rs = reduce_exact(double(xx), 1.0);
      EXPECT_EQ(double(s), rs < 0 ? rs + 1 : rs) << xx;
      const float t = bd::periodic_eval(xx, 2.0f, F.tri);
      EXPECT_GE(t, 0.0f);
      EXPECT_LE(t, 1.0f);
#ifdef BL_HAVE_GLSL_AS_CPP
      const float g = glsl_per_call(kSaw, kEval, xx, 0.0f);
      EXPECT_GE(g, 0.0f);
      EXPECT_LT(g, 1.0f);
      EXPECT_EQ(double(g), rs < 0 ? rs + 1 : rs) << xx;
#endif
    }
  }
  const double big = 1e15 + 0.375;
  EXPECT_EQ(bd::periodic_eval(big, 1.0, fns<double>().saw), 0.375);
  EXPECT_EQ(bd::periodic_eval(-big, 1.0, fns<double>().sq), 0.0);  // reduced to 0.625
  EXPECT_EQ(bd::periodic_eval(-big, 1.0, fns<double>().saw), 0.625);
}

const std::vector<double>& per_xs() {
  static const std::vector<double> xs = {
      0.0, 0.25, 0.5, 1.0, 1 + 1e-9, 1 - 1e-9, 0.5 + 1e-9, 0.3, 2.7, -3.3, 1e6 + 0.3125,
      -1e6 - 0.6875, 1e15 + 0.375, -1e15 + 0.5,
      // fine-grained x within a tiny kernel of a period boundary or a jump, both sides
      1.234567e-12, -1.234567e-12, 2 - 3.3e-12, -0.5 + 7.7e-13, 7 + 1.234567e-12};
  return xs;
}
const std::vector<double>& per_sigmas() {
  static const std::vector<double> ss = {0.0, 1e-12, 1e-8, 1e-4, 0.05, 0.2,
                                         0.5, 1.0,   3.0,  10.0, 1e3,  1e6};
  return ss;
}

TEST(SupportPeriodic, GaussianImageSum) {
  Worst W;
  for (int id = 0; id < kNumPer; ++id) {
    const PerInfo& I = per_info(id);
    for (double x : per_xs())
      for (double s : per_sigmas()) {
        if (s > 1e3) continue;  // 1e6 sd would be 10^7 periods: the Fourier path's domain
        const double xr = reduce_exact(x, I.period);
        std::vector<double> refs;
        if (s <= 10) refs.push_back(ref_gauss(I.f, I.breaks, I.period, xr, s));
        if (s >= 0.2) refs.push_back(fourier_gauss(id, x, s));
        if (refs.size() == 2) {  // the two references agree
          EXPECT_LE(err_of(refs[0], refs[1]), 1e-13) << I.name << " " << x << " " << s;
        }
        const double got = per_call<double>(id, kGauss, x, s);
        for (double ref : refs) {
          const double e = err_of(got, ref);
          W.add("double gauss", e, at_str(I.name, "gauss", x, s));
          EXPECT_LE(e, kTolDouble)
              << at_str(I.name, "gauss", x, s) << " got " << got << " ref " << ref;
        }
        const float xf = float(x), sf = float(s);
        if (std::fabs(x) > 1e7) continue;
        const double xrf = reduce_exact(xf, I.period);
        const double reff =
            sf <= 10 ? ref_gauss(I.f, I.breaks, I.period, xrf, sf) : fourier_gauss(id, xf, sf);
        const double ef = err_of(per_call<float>(id, kGauss, xf, sf), reff);
        W.add("float gauss", ef, at_str(I.name, "gauss", xf, sf));
        EXPECT_LE(ef, kTolFloat) << "float " << at_str(I.name, "gauss", xf, sf);
#ifdef BL_HAVE_GLSL_AS_CPP
        const double eg = err_of(glsl_per_call(id, kGauss, xf, sf), reff);
        W.add("glsl gauss", eg, at_str(I.name, "gauss", xf, sf));
        EXPECT_LE(eg, kTolFloat) << "glsl " << at_str(I.name, "gauss", xf, sf);
#endif
      }
  }
  W.print("GaussianImageSum");
}

TEST(SupportPeriodic, BoxAndTent) {
  Worst W;
  for (int id = 0; id < kNumPer; ++id) {
    const PerInfo& I = per_info(id);
    for (int k = kBox; k <= kTent; ++k)
      for (double x : per_xs())
        for (double s : per_sigmas()) {
          std::vector<double> refs;
          if (s <= 10)
            refs.push_back(ref_kernel(k, I.f, I.breaks, I.period, reduce_exact(x, I.period), s));
          if (s >= 1) refs.push_back(appendix_c(id, k, x, s));
          if (refs.size() == 2) {
            EXPECT_LE(err_of(refs[0], refs[1]), 1e-12) << I.name << " " << x << " " << s;
          }
          const double got = per_call<double>(id, k, x, s);
          for (double ref : refs) {
            const double e = err_of(got, ref);
            W.add(std::string("double ") + kname(k), e, at_str(I.name, kname(k), x, s));
            EXPECT_LE(e, kTolDouble)
                << at_str(I.name, kname(k), x, s) << " got " << got << " ref " << ref;
          }
          if (std::fabs(x) > 1e7) continue;
          const float xf = float(x), sf = float(s);
          const double reff =
              sf <= 10 ? ref_kernel(k, I.f, I.breaks, I.period, reduce_exact(xf, I.period), sf)
                       : appendix_c(id, k, xf, sf);
          const double ef = err_of(per_call<float>(id, k, xf, sf), reff);
          W.add(std::string("float ") + kname(k), ef, at_str(I.name, kname(k), xf, sf));
          EXPECT_LE(ef, kTolFloat) << "float " << at_str(I.name, kname(k), xf, sf);
#ifdef BL_HAVE_GLSL_AS_CPP
          const double eg = err_of(glsl_per_call(id, k, xf, sf), reff);
          W.add(std::string("glsl ") + kname(k), eg, at_str(I.name, kname(k), xf, sf));
          EXPECT_LE(eg, kTolFloat) << "glsl " << at_str(I.name, kname(k), xf, sf);
#endif
        }
  }
  W.print("BoxAndTent");
}

TEST(SupportPeriodic, RandomSweep) {
  Worst W;
  Rng g{67890};
  const int n = sweep_count();
  for (int id = 0; id < kNumPer; ++id) {
    const PerInfo& I = per_info(id);
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < n; ++i) {
        double x, s;
        sample(g, I.breaks, I.period, x, s);
        auto ref_at = [&](double xx, double ss) {
          if (k == kGauss) {
            return ss <= 10 ? ref_gauss(I.f, I.breaks, I.period, reduce_exact(xx, I.period), ss)
                            : fourier_gauss(id, xx, ss);
          }
          return ss <= 10 ? ref_kernel(k, I.f, I.breaks, I.period, reduce_exact(xx, I.period), ss)
                          : appendix_c(id, k, xx, ss);
        };
        const double ref = ref_at(x, s);
        const double e = err_of(per_call<double>(id, k, x, s), ref);
        W.add(std::string("double ") + kname(k), e, at_str(I.name, kname(k), x, s));
        EXPECT_LE(e, kTolDouble) << at_str(I.name, kname(k), x, s);
        const float xf = float(x), sf = float(s);
        const double reff = ref_at(xf, sf);
        const double ef = err_of(per_call<float>(id, k, xf, sf), reff);
        W.add(std::string("float ") + kname(k), ef, at_str(I.name, kname(k), xf, sf));
        EXPECT_LE(ef, kTolFloat) << "float " << at_str(I.name, kname(k), xf, sf);
#ifdef BL_HAVE_GLSL_AS_CPP
        const double eg = err_of(glsl_per_call(id, k, xf, sf), reff);
        W.add(std::string("glsl ") + kname(k), eg, at_str(I.name, kname(k), xf, sf));
        EXPECT_LE(eg, kTolFloat) << "glsl " << at_str(I.name, kname(k), xf, sf);
#endif
      }
  }
  W.print("PeriodicRandomSweep");
}

// ---------------------------------------------------------------------------------------------
// Series truncation.

double true_fourier_tail(double s, double B, int K) {
  double a = 2 * kPi * kPi * s * s, t = 0;
  for (long k = K + 1; k < K + 20000000L; ++k) {
    double e = B * std::exp(-a * double(k) * double(k));
    t += e;
    if (e < 1e-40 * (t + 1e-300)) break;
  }
  return t;
}

TEST(SupportSeries, FourierTermsIsTheCertifiedMinimum) {
  for (double s : {0.003, 0.01, 0.05, 0.1, 0.2, 0.5, 1.0, 3.0})
    for (double B : {0.5, 1.0, 10.0})
      for (double tol : {1e-13, 1e-8, 1e-4}) {
        const int K = bd::fourier_terms(s, B, tol);
        ASSERT_GE(K, 0);
        EXPECT_LE(true_fourier_tail(s, B, K), tol) << s << " " << B << " " << tol;
        if (K >= 2) {
          EXPECT_GT(true_fourier_tail(s, B, K - 2), tol) << s << " " << B << " " << tol;
        }
        const int Kf = bd::fourier_terms(float(s), float(B), float(tol));
        EXPECT_LE(true_fourier_tail(s, B, Kf), tol * 1.001) << "float " << s;
        EXPECT_LE(std::abs(Kf - K), 1) << "float " << s;
#ifdef BL_HAVE_GLSL_AS_CPP
        const int Kg = glsl::fourier_terms(float(s), float(B), float(tol));
        EXPECT_LE(true_fourier_tail(s, B, Kg), tol * 1.001) << "glsl " << s;
        EXPECT_LE(std::abs(Kg - K), 1) << "glsl " << s;
#endif
      }
  EXPECT_EQ(bd::fourier_terms(0.0, 1.0, 1e-13), 1 << 30);
  EXPECT_GE(bd::fourier_terms(1e-9, 1.0, 1e-13), 1 << 20);
}

TEST(SupportSeries, ImagePeriodsCoversTheTailBound) {
  for (double fmax : {0.5, 1.0, 100.0})
    for (double tol : {1e-13, 1e-8})
      for (double s : {0.0, 0.01, 0.1, 1.0, 10.0}) {
        // exact z with 2 fmax Phic(z) = tol, by bisection on the 50-digit erfc
        double lo = 0, hi = 20;
        for (int it = 0; it < 200; ++it) {
          double m = 0.5 * (lo + hi);
          double v = static_cast<double>(boost::math::erfc(mp50(m) / sqrt(mp50(2)))) * fmax;
          (v > tol ? lo : hi) = m;
        }
        const int P = bd::image_periods(s, fmax, tol);
        EXPECT_GE(P, int(std::ceil(2 * hi * s)) + 1) << fmax << " " << tol << " " << s;
        EXPECT_LE(P, int(std::ceil(2 * hi * s * 1.1)) + 2) << fmax << " " << tol << " " << s;
        const int Pf = bd::image_periods(float(s), float(fmax), float(tol));
        EXPECT_LE(std::abs(Pf - P), 1);
#ifdef BL_HAVE_GLSL_AS_CPP
        EXPECT_LE(std::abs(glsl::image_periods(float(s), float(fmax), float(tol)) - P), 1);
#endif
      }
}

TEST(SupportSeries, PreferFourierFollowsTheCostModel) {
  for (double s : {0.001, 0.01, 0.05, 0.1, 0.15, 0.2, 0.3, 1.0, 10.0})
    for (int np : {1, 2, 4}) {
      const bool pf = bd::prefer_fourier(s, np, 1.0, 1.0);
      const int K = bd::fourier_terms(s, 1.0, bd::series_tol<double>());
      const int P = bd::image_periods(s, 1.0, bd::series_tol<double>());
      // 3 units per Fourier term; 4 per image piece, 20 when the piece is narrower than 2 sigma.
      const double per_piece = s * np > 0.5 ? 20.0 : 4.0;
      EXPECT_EQ(pf, 3.0 * K < P * np * per_piece) << s << " " << np;
      const bool pff = bd::prefer_fourier(float(s), np, 1.0f, 1.0f);
      const int Kf = bd::fourier_terms(float(s), 1.0f, bd::series_tol<float>());
      const int Pf = bd::image_periods(float(s), 1.0f, bd::series_tol<float>());
      EXPECT_EQ(pff, 3.0 * Kf < Pf * np * per_piece) << s << " " << np;
#ifdef BL_HAVE_GLSL_AS_CPP
      EXPECT_EQ(glsl::prefer_fourier(float(s), np, 1.0f, 1.0f), pff) << s << " " << np;
#endif
    }
  EXPECT_FALSE(bd::prefer_fourier(0.01, 2, 1.0, 1.0));  // narrow kernel: a few images
  EXPECT_TRUE(bd::prefer_fourier(1.0, 2, 1.0, 1.0));    // wide kernel: one or two harmonics
}

// ---------------------------------------------------------------------------------------------
// cpp_bin_float_50: everything instantiates, agrees with the double references, and the
// narrow-piece quadrature keeps (near) 50-digit accuracy.
TEST(SupportMultiprecision, AgreesAndKeepsPrecision) {
  Worst W;
  for (int id = 0; id < kNumPw; ++id)
    for (int k = 0; k < 3; ++k)
      for (double x : {0.0, 0.3, 1.0 + 1e-9, -0.7, 1e6})
        for (double s : {0.0, 1e-8, 0.1, 1.0, 1e6}) {
          const double ref = ref_kernel(k, pw_info(id).f, pw_info(id).breaks, 0, x, s);
          const double got = static_cast<double>(pw_call<mp50>(id, k, mp50(x), mp50(s)));
          W.add("mp50 vs double ref", err_of(got, ref), at_str(pw_info(id).name, kname(k), x, s));
          EXPECT_LE(err_of(got, ref), 1e-13)
              << pw_info(id).name << " " << kname(k) << " " << x << " " << s;
        }
  for (int id = 0; id < kNumPer; ++id)
    for (int k = 0; k < 3; ++k)
      for (double x : {0.3, 1.0 - 1e-9, 1e6 + 0.3125})
        for (double s : {1e-8, 0.1, 1.0, 30.0}) {
          if (k == kGauss && s > 1) continue;
          const PerInfo& I = per_info(id);
          const double ref =
              k == kGauss
                  ? ref_gauss(I.f, I.breaks, I.period, reduce_exact(x, I.period), s)
                  : (s >= 1 ? appendix_c(id, k, x, s)
                            : ref_kernel(k, I.f, I.breaks, I.period, reduce_exact(x, I.period), s));
          const double got = static_cast<double>(per_call<mp50>(id, k, mp50(x), mp50(s)));
          W.add("mp50 vs double ref", err_of(got, ref), at_str(I.name, kname(k), x, s));
          EXPECT_LE(err_of(got, ref), 1e-12) << I.name << " " << kname(k) << " " << x << " " << s;
        }
  // 50-digit closed forms: constant piece [0,1] under a Gaussian of sd 1e6 (narrow-piece rule),
  // and E|X| (moment path).
  const mp50 one[8] = {1, 0, 0, 0, 0, 0, 0, 0};
  const mp50 mu = mp50(3) / 10, sg = mp50(1000000);
  mp50 ref = (boost::math::erfc((mu - 1) / (sg * sqrt(mp50(2)))) -
              boost::math::erfc(mu / (sg * sqrt(mp50(2))))) /
             2;
  mp50 got = bd::gauss_piece(mu, sg, mp50(0), mp50(1), one);
  EXPECT_LE(static_cast<double>(abs(got - ref) / ref), 1e-40);
  // the quadrature rule's worst corner (|cz| hw = 10): Phic(9) - Phic(11)
  ref = (boost::math::erfc(9 / sqrt(mp50(2))) - boost::math::erfc(11 / sqrt(mp50(2)))) / 2;
  got = bd::gauss_piece(mp50(0), mp50(1), mp50(9), mp50(11), one);
  EXPECT_LE(static_cast<double>(abs(got - ref) / ref), 1e-45);
  const mp50 X = mp50(3) / 10, S = mp50(7) / 10;
  mp50 rabs = S * sqrt(2 / boost::math::constants::pi<mp50>()) * exp(-X * X / (2 * S * S)) +
              X * boost::math::erf(X / (S * sqrt(mp50(2))));
  EXPECT_LE(static_cast<double>(abs(pw_call<mp50>(kAbs, kGauss, X, S) - rabs) / rabs), 1e-45);
  EXPECT_LE(static_cast<double>(abs(bd::sinhc(mp50(1e-6)) - sinh(mp50(1e-6)) / mp50(1e-6))), 1e-48);
  W.print("AgreesAndKeepsPrecision");
}

// ---------------------------------------------------------------------------------------------
// GLSL: the file compiles as a fragment shader in both dialects.
TEST(SupportGlsl, ValidatesAs450And320es) {
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
    p[i].lo = -1.0e30; p[i].hi = 1.0e30;
    for (int k = 0; k < 8; ++k) p[i].c[k] = 0.0;
  }
  float x = gl_FragCoord.x;
  float r = bl_gauss_pw(x, 0.1, 1, p) + bl_box_pw(x, 0.1, 1, p) + bl_tent_pw(x, 0.1, 1, p)
      + bl_pw_eval(x, 1, p) + bl_periodic_eval(x, 1.0, 1, p)
      + bl_gauss_periodic_image(x, 0.1, 1.0, 1, p, 1.0) + bl_box_periodic(x, 0.1, 1.0, 1, p, p)
      + bl_tent_periodic(x, 0.1, 1.0, 1, p, p, p) + bl_gauss_piece(x, 1.0, 0.0, 1.0, p[0].c)
      + bl_box_piece(x, 1.0, 0.0, 1.0, p[0].c) + bl_tent_piece(x, 1.0, 0.0, 1.0, p[0].c)
      + bl_poly(p[0].c, x) + bl_Phi(x) + bl_Phic(x) + bl_phi(x) + bl_sinc(x) + bl_sinhc(x)
      + bl_exp_sinhc(x, x) + bl_exp_sinhc2(x, x) + bl_logcosh(x)
      + float(bl_fourier_terms(x, 1.0, 1.0e-8)) + float(bl_image_periods(x, 1.0, 1.0e-8))
      + (bl_prefer_fourier(x, 2, 1.0, 1.0) ? 1.0 : 0.0);
  bl_frag = vec4(r);
}
)";
  const std::string headers[2] = {
      "#version 450\n", "#version 320 es\nprecision highp float;\nprecision highp int;\n"};
  const char* tags[2] = {"450", "320es"};
  for (int v = 0; v < 2; ++v) {
    const std::string base =
        ::testing::TempDir() + "bl_support_" + tags[v] + "_" + std::to_string(::getpid());
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

TEST(SupportGlsl, RunsAsCppFloat) {
#ifndef BL_HAVE_GLSL_AS_CPP
  GTEST_SKIP() << "GLSL-as-C++ checks need GCC (-fsingle-precision-constant); not built";
#else
  // The numerical GLSL checks are folded into the tests above (labels "glsl ..."); this one makes
  // sure the wrappers are really the GLSL code: a sample value and sigma = 0 exactness.
  EXPECT_EQ(glsl_pw_call(kStep, kEval, 0.0f, 0.0f), 1.0f);
  EXPECT_EQ(glsl_pw_call(kSs2, kGauss, 0.25f, 0.0f), pw_call<float>(kSs2, kEval, 0.25f, 0.0f));
  EXPECT_NEAR(glsl_pw_call(kAbs, kGauss, 0.0f, 1.0f), 0.7978845608f, 1e-6f);
#endif
}

}  // namespace
#endif  // BL_SUPPORT_GLSL_AS_CPP
