// The box and tent exp-polynomial entries (straight-line code from rulegen/emit_box_tent_ept.cpp)
// against Gauss-Kronrod quadrature of the kernel integral in long double (Boost.Math; independent of
// the emitter and of the runtime), float and double, at the hard inputs: sigma -> 0, huge sigma,
// |x| = 1e6 and 1e30, at and next to the break at 0 and where the kernel's edge or centre meets it.
#include <gtest/gtest.h>

#include <bandlimit/table.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace {

using ld = long double;

struct Atom {
  const char* name;
  std::function<ld(ld)> f;
  double lo_cut, hi_cut;  // where f is below 1e-80 of its scale (quadrature range)
  float (*bf)(float, float);
  double (*bd)(double, double);
  float (*tf)(float, float);
  double (*td)(double, double);
};

ld xe(ld t) {
  return t * std::exp(t);
}

std::vector<Atom> atoms() {
  using namespace bl;
  return {
      {"xexp", xe, -200, 11000, box::xexp, box::xexp, tent::xexp, tent::xexp},
      {"xexp_sq", [](ld t) { return xe(t) * xe(t); }, -120, 5600, box::xexp_sq, box::xexp_sq, tent::xexp_sq,
       tent::xexp_sq},
      {"laplace", [](ld t) { return std::exp(-std::fabs(t)); }, -200, 200, box::laplace, box::laplace,
       tent::laplace, tent::laplace},
      {"laplace_sq", [](ld t) { return std::exp(-2 * std::fabs(t)); }, -100, 100, box::laplace_sq,
       box::laplace_sq, tent::laplace_sq, tent::laplace_sq},
      {"exp_decay", [](ld t) { return t >= 0 ? std::exp(-t) : ld(0); }, 0, 200, box::exp_decay,
       box::exp_decay, tent::exp_decay, tent::exp_decay},
      {"exp_decay_sq", [](ld t) { return t >= 0 ? std::exp(-2 * t) : ld(0); }, 0, 100, box::exp_decay_sq,
       box::exp_decay_sq, tent::exp_decay_sq, tent::exp_decay_sq},
      {"exp_ramp", [](ld t) { return t >= 0 ? t * std::exp(-t) : ld(0); }, 0, 220, box::exp_ramp,
       box::exp_ramp, tent::exp_ramp, tent::exp_ramp},
      {"exp_ramp_sq", [](ld t) { return t >= 0 ? t * t * std::exp(-2 * t) : ld(0); }, 0, 120,
       box::exp_ramp_sq, box::exp_ramp_sq, tent::exp_ramp_sq, tent::exp_ramp_sq},
  };
}

// E f(x + U) as an integral over the offset u in [-hw, hw] (so a tiny kernel is not lost in x's
// rounding), cut to where f is not negligible, split at the break 0 and at the tent's apex.
ld reference(const Atom& a, bool tent, ld x, ld sigma) {
  const ld hw = (tent ? std::sqrt(ld(6)) : std::sqrt(ld(3))) * sigma;
  const ld lo = std::max(-hw, ld(a.lo_cut) - x), hi = std::min(hw, ld(a.hi_cut) - x);
  if (!(lo < hi)) return 0;
  std::vector<ld> cuts{lo};
  for (ld c : {-x, tent ? ld(0) : lo})
    if (c > lo && c < hi) cuts.push_back(c);
  std::sort(cuts.begin(), cuts.end());
  cuts.push_back(hi);
  auto g = [&](ld u) {
    const ld k = tent ? (hw - std::fabs(u)) / (hw * hw) : 1 / (2 * hw);
    return a.f(x + u) * k;
  };
  ld sum = 0;
  for (size_t i = 0; i + 1 < cuts.size(); ++i)
    if (cuts[i + 1] > cuts[i])
      sum += boost::math::quadrature::gauss_kronrod<ld, 31>::integrate(g, cuts[i], cuts[i + 1], 8, 1e-14L);
  return sum;
}

template <class T>
void check(const Atom& a, bool tent, T x, T sigma, double tol) {
  const T v = tent ? (sizeof(T) == 4 ? T(a.tf(float(x), float(sigma))) : T(a.td(double(x), double(sigma))))
                   : (sizeof(T) == 4 ? T(a.bf(float(x), float(sigma))) : T(a.bd(double(x), double(sigma))));
  const std::string where = std::string(tent ? "tent/" : "box/") + a.name +
                            (sizeof(T) == 4 ? " float" : " double") + " x=" + std::to_string(double(x)) +
                            " sigma=" + std::to_string(double(sigma));
  ASSERT_FALSE(std::isnan(v)) << where;
  // x e^x past the cut: beyond long double's range (and so T's); nothing to compare.
  const ld hw = (tent ? std::sqrt(ld(6)) : std::sqrt(ld(3))) * ld(sigma);
  if (a.hi_cut > 1000 && ld(x) + hw > a.hi_cut) return;
  const ld r = reference(a, tent, ld(x), ld(sigma));
  if (!(std::fabs(r) < ld(std::numeric_limits<T>::max()) / 4)) return;
  // The exponent a s0 carries the rounding of s0 (eps |a s0| relative, as the plain e^{a x} of a
  // rounded argument): up to ~eps log|value| where the value is large (x e^x at x + h = 70).
  const double eps = std::numeric_limits<T>::epsilon();
  const double allowed = tol + 2 * eps * double(std::log(std::max(ld(1), std::fabs(r))));
  EXPECT_LE(double(std::fabs(ld(v) - r) / std::max(ld(1), std::fabs(r))), allowed)
      << where << " ref=" << double(r);
}

template <class T>
void check_grid(double tol) {
  const double xs[] = {0, 1e-30, 1e-7, 0.5, 4, 37, 1e6, 1e30};
  const double ss[] = {1e-30, 1e-6, 0.01, 0.3, 1, 30, 1e3, 1e6, 1e30};
  for (const Atom& a : atoms())
    for (int tent = 0; tent < 2; ++tent) {
      for (double s : ss)
        for (double x : xs)
          for (double sign : {1.0, -1.0}) check<T>(a, tent, T(sign * x), T(s), tol);
      // The kernel's edge (and the tent's centre) on the break at 0, and next to it.
      for (double s : {1e-6, 0.01, 0.3, 2.0}) {
        const double hw = (tent ? std::sqrt(6.0) : std::sqrt(3.0)) * s;
        for (double f : {1.0, 1 - 1e-6, 1 + 1e-6, 0.5})
          for (double sign : {1.0, -1.0}) check<T>(a, tent, T(sign * f * hw), T(s), tol);
      }
    }
}

TEST(BoxTentEpt, DoubleMatchesQuadratureAtHardInputs) {
  check_grid<double>(1e-11);
}

TEST(BoxTentEpt, FloatMatchesQuadratureAtHardInputs) {
  check_grid<float>(2e-6);
}

}  // namespace
