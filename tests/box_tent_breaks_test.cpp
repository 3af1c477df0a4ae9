// Box and tent entries of piecewise, periodic and staircase atomics (emitted as break sums, see
// rulegen/emit_box_tent_breaks.cpp) at the inputs that form is weakest at: kernels far below float's
// normal range (the exact power-of-two rescale), x at and one ulp beside a break, the width where the
// break sum hands over to the wide regime (both sides of it), |x| = 1e6 and huge sigma. Reference:
// the kernel integral in long double, split at every break and at x (tent), 8-point Gauss-Legendre
// on each part (exact for these polynomial pieces times a linear weight); positions are offsets
// u = t - x, so a tiny kernel at a huge x is integrated without rounding its ends.
#include <gtest/gtest.h>

#include <bandlimit/table.hpp>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace {

using LD = long double;

// f on the piece that contains `anchor`, evaluated at t (pieces: polynomials between multiples of
// 1/2, so an anchor 1/8 inside a part identifies its piece exactly).
struct Fn {
  std::string name;
  std::function<LD(LD t, LD anchor)> f;
  std::function<double(double, double)> box_d, tent_d;
  std::function<float(float, float)> box_f, tent_f;
};

LD fl(LD a) {
  return std::floor(a);
}

#define BL_FN(nm, expr)                                                                        \
  Fn {                                                                                         \
#nm, [](LD t, LD a) { (void)t; (void)a; return LD(expr); },                                  \
        [](double x, double s) { return bl::box::nm(x, s); },                                    \
        [](double x, double s) { return bl::tent::nm(x, s); },                                   \
        [](float x, float s) { return bl::box::nm(x, s); }, [](float x, float s) { return bl::tent::nm(x, s); } \
  }

std::vector<Fn> functions() {
  return {
      BL_FN(fract, t - fl(a)),
      BL_FN(fract_sq, (t - fl(a)) * (t - fl(a))),
      BL_FN(square, a - fl(a) < 0.5L ? 1 : 0),
      BL_FN(triangle, (a - 2 * fl(a / 2) < 1) ? t - 2 * fl(a / 2) : 2 - (t - 2 * fl(a / 2))),
      BL_FN(floor, fl(a)),
      BL_FN(floor_sq, fl(a) * fl(a)),
      BL_FN(ceil_sq, (fl(a) + 1) * (fl(a) + 1)),
      BL_FN(trunc, a < 0 ? fl(a) + 1 : fl(a)),
      BL_FN(trunc_sq, a < 0 ? (fl(a) + 1) * (fl(a) + 1) : fl(a) * fl(a)),
      BL_FN(step, a < 0 ? 0 : 1),
      BL_FN(abs, a < 0 ? -t : t),
      BL_FN(saturate, a < 0 ? 0 : (a < 1 ? t : 1)),
      BL_FN(smoothstep, a < 0 ? 0 : (a < 1 ? t * t * (3 - 2 * t) : 1)),
  };
}

// E f(x + U), U box (half-width h = sqrt3 sigma) or tent (w = sqrt6 sigma).
LD reference(const Fn& fn, double x, double sigma, bool box) {
  static const LD gx[4] = {0.1834346424956498049394761L, 0.5255324099163289858177390L,
                           0.7966664774136267395915539L, 0.9602898564975362316835609L};
  static const LD gw[4] = {0.3626837833783619829651504L, 0.3137066458778872873379622L,
                           0.2223810344533744705443560L, 0.1012285362903762591525314L};
  const LD hw = (box ? std::sqrt(3.0L) : std::sqrt(6.0L)) * LD(sigma);
  // Split points as offsets from x: the multiples of 1/2 inside the support (exact: b - x), and 0.
  std::vector<LD> cut = {-hw};
  std::vector<LD> anchors;
  const LD xl = x;
  LD b = std::ceil((xl - hw) * 2) / 2;
  if (b - xl <= -hw) b += 0.5L;
  for (; b - xl < hw; b += 0.5L) cut.push_back(b - xl);
  cut.push_back(hw);
  LD s = 0;
  for (size_t i = 0; i + 1 < cut.size(); ++i) {
    // The part's absolute piece: 1/8 right of its left break, or 1/8 left of the first break.
    const LD anchor = i > 0 ? xl + cut[i] + 0.125L : (cut.size() > 2 ? xl + cut[1] - 0.125L : xl);
    std::vector<std::pair<LD, LD>> parts;
    if (!box && cut[i] < 0 && cut[i + 1] > 0)
      parts = {{cut[i], 0}, {0, cut[i + 1]}};
    else
      parts = {{cut[i], cut[i + 1]}};
    for (const auto& [lo, hi] : parts) {
      const LD mid = (lo + hi) / 2, half = (hi - lo) / 2;
      for (int k = 0; k < 4; ++k)
        for (int sg = -1; sg <= 1; sg += 2) {
          const LD u = mid + sg * half * gx[k];
          const LD wt = box ? 1 / (2 * hw) : (hw - std::fabs(u)) / (hw * hw);
          s += gw[k] * half * wt * fn.f(xl + u, anchor);
        }
    }
  }
  return s;
}

struct Case {
  double x, sigma;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  const double xs[] = {0,
                       1e-31,
                       -1e-31,
                       std::nextafter(0.0, 1.0),
                       0.5,
                       std::nextafter(0.5, 0.0),
                       1,
                       std::nextafter(1.0, 0.0),
                       std::nextafter(1.0, 2.0),
                       -0.25,
                       0.3,
                       2.75,
                       -3.7,
                       37.5,
                       1e6 + 0.5,
                       -1e6 - 0.25,
                       -1e-9,        // the nearest break (0) far beyond a tiny kernel, x just left of it
                       8388607.75,   // 2^23 - 1/4: float's last quarter steps
                       16777215.0};  // 2^24 - 1: an odd integer, float's last one
  // 1e-40: float's subnormal range (the rescale by 2^100); 2/sqrt3, 2/sqrt6, 3/sqrt6: where box and
  // tent hand over from the break sum (2 and 3 units each side) to the wide regime; 0.25/sqrt3,
  // 0.25/sqrt6: where square's one-break regime ends (half its gap), 0.45/sqrt3: where the box
  // square hands over to the wide regime (and the near-break sums end).
  // 1e-30/sqrt3, 1e-30/sqrt6, 0.5/sqrt3, 0.5/sqrt6: the ends of the pixel-sized path (one break in
  // reach: half-width from 1e-30 to half the gap between breaks, 1/4 for square, 1/2 for fract,
  // triangle and the staircases).
  const double ss[] = {1e-40,
                       1e-35,
                       1e-31,
                       1e-30 / std::sqrt(3.0),
                       1e-30 / std::sqrt(6.0),
                       0.01,
                       0.5 / std::sqrt(3.0),
                       0.5 / std::sqrt(6.0),
                       1e-12,
                       1e-3,
                       0.25 / std::sqrt(3.0),
                       0.25 / std::sqrt(6.0),
                       0.3,
                       0.45 / std::sqrt(3.0),
                       2 / std::sqrt(3.0),
                       2 / std::sqrt(6.0),
                       3 / std::sqrt(6.0),
                       2.5,
                       40};
  for (double x : xs)
    for (double s : ss) {
      out.push_back({x, s});
      out.push_back({x, std::nextafter(s, 0.0)});
      out.push_back({x, std::nextafter(s, 10.0)});
    }
  for (double s : {1e-40, 1e-31, 1e-12, 0.01})  // a kernel a fraction of its width from a break
    for (double a : {-0.9, -0.5, -0.1, 0.1, 0.5, 0.9}) out.push_back({a * s, s});
  return out;
}

TEST(BoxTentBreaks, DoubleAgainstTheKernelIntegral) {
  for (const Fn& fn : functions())
    for (const Case& c : cases()) {
      if (fn.name == "floor_sq" || fn.name == "ceil_sq" || fn.name == "trunc_sq")
        if (c.sigma > 3) continue;  // the reference's parts: 1e4 at |x| = 1e6, fine; keep it short
      for (bool box : {true, false}) {
        const LD ref = reference(fn, c.x, c.sigma, box);
        const double got = box ? fn.box_d(c.x, c.sigma) : fn.tent_d(c.x, c.sigma);
        EXPECT_NEAR(got, double(ref), 1e-9 * std::fmax(1.0, std::fabs(double(ref))))
            << (box ? "box/" : "tent/") << fn.name << " x=" << c.x << " sigma=" << c.sigma;
      }
    }
}

TEST(BoxTentBreaks, FloatAgainstTheKernelIntegral) {
  for (const Fn& fn : functions())
    for (const Case& c : cases()) {
      const float x = float(c.x), s = float(c.sigma);
      if (c.sigma > 3 && (fn.name == "floor_sq" || fn.name == "ceil_sq" || fn.name == "trunc_sq")) continue;
      for (bool box : {true, false}) {
        const LD ref = reference(fn, x, s, box);  // at the float inputs
        const float got = box ? fn.box_f(x, s) : fn.tent_f(x, s);
        EXPECT_NEAR(got, double(ref), 2e-5 * std::fmax(1.0, std::fabs(double(ref))))
            << (box ? "box/" : "tent/") << fn.name << " x=" << x << " sigma=" << s;
      }
    }
}

}  // namespace
