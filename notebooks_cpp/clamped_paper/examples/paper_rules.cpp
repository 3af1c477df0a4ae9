// See paper_rules.hpp.
#include "paper_rules.hpp"

#include <algorithm>
#include <boost/math/constants/constants.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <cmath>

namespace clamped_paper {

double truth(const Fn& f, double mu, double s) {
  static boost::math::quadrature::tanh_sinh<double> ts;
  const double inv_sqrt_2pi = boost::math::constants::one_div_root_two_pi<double>();
  auto w = [&](double z) { return f(mu + s * z) * std::exp(-0.5 * z * z) * inv_sqrt_2pi; };
  return ts.integrate(w, -12.0, 0.0) + ts.integrate(w, 0.0, 12.0);
}

Stat square_of_normal(double mu, double s) {
  const double m = bl::gaussian::pow2(mu, s);
  return {m, bl::gaussian::pow2_sq(mu, s) - m * m};
}

Stat adaptive(double (*g)(double, double), double (*g_sq)(double, double), double a, double b, Stat x) {
  const double m = a * x.mean + b, s = std::abs(a) * std::sqrt(x.var);
  const double y = g(m, s);
  return {y, std::max(0.0, g_sq(m, s) - y * y)};
}

namespace {
int g_point_mass = 0;
}

Stat rule1(const Fn& g, Stat x, double lo, double hi, int* steps) {
  const auto p = bl::rule1::renormalize(bl::rule1::Kernel::gaussian, x.mean, x.var, lo, hi);
  if (steps) *steps = std::max(*steps, p.steps);
  const Stat r = bl::rule1::expect(bl::rule1::Kernel::gaussian, p, lo, hi, g);
  // bl::rule1::expect used to return NaN when the renormalized Gaussian was narrower than about
  // 1e-13 relative to its centre (a point mass at a finite bound); it now returns the point mass
  // itself, so this guard no longer fires (the count the notebook prints should be 0).
  if (std::isnan(r.mean) && !std::isnan(p.center) && p.sigma <= 1e-10 * (1 + std::abs(p.center))) {
    ++g_point_mass;
    return {g(std::clamp(p.center, lo, hi)), 0};
  }
  return r;
}

int rule1_point_mass_count() {
  return g_point_mass;
}

Stat clamped_only(const Fn& g, Stat x, double lo, double hi) {
  const bl::rule1::Params<double> p{x.mean, std::sqrt(x.var), 0};
  return bl::rule1::expect(bl::rule1::Kernel::gaussian, p, lo, hi, g);
}

Stat rule2(Stat (*g)(double, double), double a, double b, Stat x) {
  return g(a * x.mean + b, std::abs(a) * std::sqrt(x.var));
}

Jet chain(Jet h, double g0, double g1, double g2) {
  return {g0, g1 * h.f1, g2 * h.f1 * h.f1 + g1 * h.f2};
}
Jet affine(Jet h, double a, double b) {
  return {a * h.f0 + b, a * h.f1, a * h.f2};
}
Jet jet_sq(double x) {
  return {x * x, bl::deriv::pow2_d1(x), bl::deriv::pow2_d2(x)};
}
Jet jet_exp(Jet h) {
  return chain(h, std::exp(h.f0), bl::deriv::exp_d1(h.f0), bl::deriv::exp_d2(h.f0));
}
Jet jet_sin(Jet h) {
  return chain(h, std::sin(h.f0), bl::deriv::sin_d1(h.f0), bl::deriv::sin_d2(h.f0));
}

Stat rule3(Jet j, double mu, double s) {
  const auto m = bl::truncnorm::moments(mu, s, -kInf, kInf);
  return bl::rule3::from_derivatives(j.f0, j.f1, j.f2, m);
}

}  // namespace clamped_paper
