// The rules of Li et al. 2020 (clamped domain) composed by hand, node by node, from the generated
// table (bandlimit/table.hpp, rules_clamped.hpp, rules_mode.hpp), and the quadrature reference they
// are measured against. Shared by tests/clamped_paper_test.cpp and the clamped_paper notebook.
#pragma once

#include <bandlimit/rules_clamped.hpp>
#include <bandlimit/rules_mode.hpp>
#include <functional>
#include <limits>

namespace clamped_paper {

using Fn = std::function<double(double)>;
using Stat = bl::stat<double>;  // a node value: the Gaussian a rule passes on (mean, variance)
inline constexpr double kInf = std::numeric_limits<double>::infinity();

// The reference: E[f(X)], X ~ N(mu, s^2), by Boost tanh-sinh quadrature over mu +- 12 s split at mu.
double truth(const Fn& f, double mu, double s);

// X * X, X ~ N(mu, s^2): its exact mean and variance (the table's pow2 and pow2_sq entries).
Stat square_of_normal(double mu, double s);

// Adaptive Gaussian (Yang & Barnes 2018): the table's Gaussian entries g, g_sq applied to a*X + b.
Stat adaptive(double (*g)(double, double), double (*g_sq)(double, double), double a, double b, Stat x);

// Rule 1: the node X lies in [lo, hi]; its Gaussian is renormalized there (eq. 8,
// bl::rule1::renormalize) and the consumer g is averaged under it (eqs. 3-4, bl::rule1::expect).
// `steps`, when given, is raised to the Newton steps the solver used.
// Where bl::rule1::expect gives NaN for a renormalized Gaussian narrower than ~1e-13 relative to its
// centre (a point mass at a finite bound), the point mass g(centre) is taken (below 1e-10 relative);
// rule1_point_mass_count() says how often that happened in this process.
Stat rule1(const Fn& g, Stat x, double lo, double hi, int* steps = nullptr);
int rule1_point_mass_count();

// "Yang-fract" (the paper's Sec. 5.1): the node's Gaussian cut to [lo, hi], not renormalized.
Stat clamped_only(const Fn& g, Stat x, double lo, double hi);

// Rule 2 (mode fit, bl::rule2) of a table atomic applied to a*X + b.
Stat rule2(Stat (*g)(double, double), double a, double b, Stat x);

// Rule 3 on a whole composition: value and first two derivatives at a point, by the chain rule on
// bl::deriv, then the second-order Taylor polynomial under the normal (bl::rule3::from_derivatives).
struct Jet {
  double f0, f1, f2;
};
Jet chain(Jet h, double g0, double g1, double g2);  // g(h) from g and its derivatives at h.f0
Jet affine(Jet h, double a, double b);              // a h + b
Jet jet_sq(double x);                               // x^2 at x
Jet jet_exp(Jet h);                                 // exp(h)
Jet jet_sin(Jet h);                                 // sin(h)
Stat rule3(Jet j, double mu, double s);

}  // namespace clamped_paper
