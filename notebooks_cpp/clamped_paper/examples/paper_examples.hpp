// The analytic examples of Li et al. 2020 (clamped domain), Sections 3-5: Figures 2-5 and Table 1,
// each as the function, the input sigma, the rules composed node by node (paper_rules.hpp) and the
// MSEs the paper prints. Shared by tests/clamped_paper_test.cpp and the clamped_paper notebook.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "paper_rules.hpp"

namespace clamped_paper {

// One rule applied to a whole example: mu_X -> the approximate smoothed value.
struct Method {
  std::string key;    // adaptive, yang_fract, rule1, rule2, rule3
  std::string label;  // for tables and plot keys
  Fn approx;
};

struct Example {
  std::string title;  // the function, as the paper writes it
  Fn f;
  double sigma;  // of X ~ N(mu_X, sigma^2)
  std::vector<Method> methods;
  std::map<std::string, double> paper_mse;  // the MSE the paper prints, per method key
  std::string note;                         // how the rules were composed, where not obvious
};

// The mu_X grid of the MSEs (the paper does not state its range or grid).
inline constexpr double kMuLo = -3, kMuHi = 3;
inline constexpr int kMuN = 121;
std::vector<double> grid(double lo, double hi, int n);

// Every method of an example on a mu grid against the quadrature reference.
struct Evaluation {
  std::vector<double> mu, truth;
  std::vector<std::vector<double>> values;  // per method, per mu
  std::vector<double> mse;                  // per method
};
Evaluation evaluate(const Example& e, const std::vector<double>& mus);

// Table 1 / Figure 5 (sigma_X^2 = 0.25): exp(-x^2), sin(x^2), exp(-2x^2), in the paper's order.
std::vector<Example> table1();
// Figure 2: x1 = -x*x, x2 = exp(x1), sigma_X^2 = 0.5 (the adaptive rule is the constant exp(-1/4)).
Example figure2();
// Figure 4: sin(0.5 - 0.5 exp(-2x^2)), sigma_X^2 = 0.13. `rule1_steps` (kept by the Rule 1 method,
// may be null) is raised to the most Newton steps the Rule 1 solver used at any node.
Example figure4(int* rule1_steps);

// Figure 3: Y = exp(X), X ~ N(0, 0.5^2); the density of Y (log-normal) against the Gaussians the
// rules fit: adaptive (the table's exact mean and variance of Y), Rule 1 (a Gaussian with the same
// mean and variance once renormalized on [0, inf)), Rule 2 (the mode fit, eqs. 14-15).
struct Figure3 {
  double sigma;
  Stat adaptive, rule2;
  bl::rule1::Params<double> rule1;          // centre and sigma of the renormalized Gaussian
  bl::truncnorm::Moments<double> rule1_tm;  // its truncated moments (mass renormalizes the density)
  std::map<std::string, double> paper_mse;  // adaptive, rule1, rule2
  double lognormal(double y) const;         // the true density of Y
  double density(const std::string& key, double y) const;  // key: adaptive, rule1, rule2
};
Figure3 figure3();
inline constexpr double kDensityLo = 0.01, kDensityHi = 4;  // the MSE's y grid (paper: not stated)
inline constexpr int kDensityN = 400;
double density_mse(const Figure3& f, const std::string& key);

}  // namespace clamped_paper
