// The exp-polynomial term primitives of the runtime support (support.hpp: gauss_ept, box_ept,
// tent_ept; support.glsl: their GLSL twins) on the Laplace bump e^{-|x|}, against the closed forms
// of ../exp_poly_refs.hpp (written from the definition, never calling the code under test), at
// the hard inputs: at the kink and 1e-9 next to it, sigma from 1e-12 to 1e6, |x| up to 1e6.
// Bounds: double 1e-12, float and GLSL-as-C++ float 2e-5 (relative to max(1, |ref|)).
//
// Like support_test.cpp, this file is compiled a second time (GCC only) as an object that includes
// support.glsl as C++ float code, so the GLSL versions run through the float checks.

#ifdef BL_SUPPORT_GLSL_AS_CPP
#include <algorithm>
#include <cmath>

namespace bl_glsl_exp_cpp {
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
inline float min(float a, float b) {
  return b < a ? b : a;
}
inline float max(float a, float b) {
  return a < b ? b : a;
}
inline int min(int a, int b) {
  return b < a ? b : a;
}
inline int max(int a, int b) {
  return a < b ? b : a;
}
inline float clamp(float x, float a, float b) {
  return min(max(x, a), b);
}
inline float mod(float a, float b) {
  return a - b * floor(a / b);
}
inline float sign(float a) {
  return a > 0 ? 1.0f : (a < 0 ? -1.0f : 0.0f);
}
struct vec2 {
  float x, y;
  vec2(float a, float b) : x(a), y(b) {}
};
#define out
#define inout
#include "support.glsl"
#undef out
#undef inout
}  // namespace bl_glsl_exp_cpp

// The Laplace bump's two terms in the GLSL layout (1e30: an infinite end).
float glsl_laplace(int kernel, float x, float s) {
  using namespace bl_glsl_exp_cpp;
  BlExpTerm p[8];
  for (int i = 0; i < 8; ++i) {
    p[i].lo = p[i].hi = p[i].a = p[i].ref = 0.0f;
    for (int k = 0; k < 8; ++k) p[i].c[k] = 0.0f;
  }
  p[0].lo = -BL_INF;
  p[0].a = 1.0f;
  p[0].c[0] = 1.0f;
  p[1].hi = BL_INF;
  p[1].a = -1.0f;
  p[1].c[0] = 1.0f;
  if (kernel == 0) return bl_gauss_ept(x, s, 2, p);
  if (kernel == 1) return bl_box_ept(x, s, 2, p);
  return bl_tent_ept(x, s, 2, p);
}

// The ramp t e^{-t} on [0, inf) under a Gaussian.
float glsl_gauss_ramp(float x, float s) {
  using namespace bl_glsl_exp_cpp;
  BlExpTerm p[8];
  for (int i = 0; i < 8; ++i) {
    p[i].lo = p[i].hi = p[i].a = p[i].ref = 0.0f;
    for (int k = 0; k < 8; ++k) p[i].c[k] = 0.0f;
  }
  p[0].hi = BL_INF;
  p[0].a = -1.0f;
  p[0].c[1] = 1.0f;
  return bl_gauss_ept(x, s, 1, p);
}
#else
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "../exp_poly_refs.hpp"
#include "support.hpp"

#ifdef BL_HAVE_GLSL_AS_CPP
float glsl_laplace(int kernel, float x, float s);
float glsl_gauss_ramp(float x, float s);
#endif

namespace {
using namespace exp_refs;

template <class T>
T laplace(int kernel, T x, T s) {
  using bl::detail::ExpTerm;
  const T inf = bl::detail::inf<T>();
  const ExpTerm<T> p[2] = {{-inf, T(0), T(1), T(0), {T(1)}}, {T(0), inf, T(-1), T(0), {T(1)}}};
  if (kernel == 0) return bl::detail::gauss_ept(x, s, p);
  if (kernel == 1) return bl::detail::box_ept(x, s, p);
  return bl::detail::tent_ept(x, s, p);
}

double ref(int kernel, double x, double s) {
  if (s == 0) return std::exp(-std::abs(x));
  return kernel == 0 ? gauss_laplace(x, s) : kernel == 1 ? box_laplace(x, s) : tent_laplace(x, s);
}

TEST(SupportExp, LaplaceTermsAtHardInputs) {
  double worst[3] = {0, 0, 0};
  for (int kernel = 0; kernel < 3; ++kernel)
    for (double x : {0.0, 1e-9, -1e-9, 1e-4, -0.25, 1.0, -3.7, 10.0, 1e3 + 0.3, -1e6 - 0.3})
      for (double s : {0.0, 1e-12, 1e-8, 1e-4, 0.01, 0.3, 1.0, 3.0, 10.0, 100.0, 1e4, 1e6}) {
        const float xf = float(x), sf = float(s);
        const double rd = ref(kernel, x, s), rf = ref(kernel, xf, sf);
        const double ed = rel(laplace<double>(kernel, x, s), rd);
        const double ef = rel(laplace<float>(kernel, xf, sf), rf);
        EXPECT_LE(ed, 1e-12) << kernel << " " << x << " " << s;
        EXPECT_LE(ef, 2e-5) << kernel << " " << x << " " << s;
        worst[0] = std::max(worst[0], ed);
        worst[1] = std::max(worst[1], ef);
#ifdef BL_HAVE_GLSL_AS_CPP
        const double eg = rel(glsl_laplace(kernel, xf, sf), rf);
        EXPECT_LE(eg, 2e-5) << "glsl " << kernel << " " << x << " " << s;
        worst[2] = std::max(worst[2], eg);
#endif
      }
  std::printf("laplace terms, worst error: double %.1e, float %.1e, GLSL-as-C++ %.1e\n", worst[0], worst[1],
              worst[2]);
}

// The ramp's Gaussian at large sigma, where the shifted centre x - sigma^2 lies far from the piece
// (the Laplace tail integrals from the piece end, V_k by Miller's recurrence).
TEST(SupportExp, RampUnderAWideGaussian) {
  using bl::detail::ExpTerm;
  for (double x : {0.0, 1.0, -3.7, 10.0})
    for (double s : {0.3, 3.0, 30.0, 1e3, 1e4, 1e6}) {
      const ExpTerm<double> pd[1] = {{0.0, bl::detail::inf<double>(), -1.0, 0.0, {0.0, 1.0}}};
      const ExpTerm<float> pf[1] = {{0.0f, bl::detail::inf<float>(), -1.0f, 0.0f, {0.0f, 1.0f}}};
      const double r = gauss_ramp(x, s);
      EXPECT_LE(rel(bl::detail::gauss_ept(x, s, pd), r), 1e-12) << x << " " << s;
      EXPECT_LE(rel(bl::detail::gauss_ept(float(x), float(s), pf), r), 2e-6) << x << " " << s;
#ifdef BL_HAVE_GLSL_AS_CPP
      EXPECT_LE(rel(glsl_gauss_ramp(float(x), float(s)), r), 2e-5) << "glsl " << x << " " << s;
#endif
    }
}

}  // namespace
#endif
