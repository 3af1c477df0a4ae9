// See paper_examples.hpp. The printed MSEs are the paper's Table 1 and the captions' text of
// Figures 3 and 4 (Sections 3.3, 3.4 and 5.1).
#include "paper_examples.hpp"

#include <boost/math/constants/constants.hpp>
#include <cmath>

namespace clamped_paper {
namespace {

// exp(g x^2) through x1 = x*x (range [0, inf)), then exp(g x1).
Example exp_of_square(double g, double sigma, const std::string& title) {
  Example e{title, [g](double x) { return std::exp(g * x * x); }, sigma, {}, {}, ""};
  const Fn eg = [g](double u) { return std::exp(g * u); };
  e.methods = {
      {"adaptive", "adaptive Gaussian [YB18]",
       [=](double mu) {
         return adaptive(bl::gaussian::exp, bl::gaussian::exp_sq, g, 0, square_of_normal(mu, sigma)).mean;
       }},
      {"yang_fract", "Yang-fract (clamped, not renormalized)",
       [=](double mu) { return clamped_only(eg, square_of_normal(mu, sigma), 0, kInf).mean; }},
      {"rule1", "Rule 1 (renormalized Gaussian)",
       [=](double mu) { return rule1(eg, square_of_normal(mu, sigma), 0, kInf).mean; }},
      {"rule2", "Rule 2 (mode fit at exp)",
       [=](double mu) { return rule2(bl::rule2::exp, g, 0, square_of_normal(mu, sigma)).mean; }},
      {"rule3", "Rule 3 (Taylor of the composition)",
       [=](double mu) { return rule3(jet_exp(affine(jet_sq(mu), g, 0)), mu, sigma).mean; }},
  };
  return e;
}

Example sin_of_square(double sigma) {
  Example e{"sin(x^2)", [](double x) { return std::sin(x * x); }, sigma, {}, {}, ""};
  const Fn sn = [](double u) { return std::sin(u); };
  e.methods = {
      {"adaptive", "adaptive Gaussian [YB18]",
       [=](double mu) {
         return adaptive(bl::gaussian::sin, bl::gaussian::sin_sq, 1, 0, square_of_normal(mu, sigma)).mean;
       }},
      {"yang_fract", "Yang-fract (clamped, not renormalized)",
       [=](double mu) { return clamped_only(sn, square_of_normal(mu, sigma), 0, kInf).mean; }},
      {"rule1", "Rule 1 (renormalized Gaussian)",
       [=](double mu) { return rule1(sn, square_of_normal(mu, sigma), 0, kInf).mean; }},
      {"rule3", "Rule 3 (Taylor of the composition)",
       [=](double mu) { return rule3(jet_sin(jet_sq(mu)), mu, sigma).mean; }},
  };
  e.note = "no Rule 2: the table has no mode fit for sin or pow2 (not monotone; manifest `not_derived`)";
  return e;
}

double gauss_pdf(double y, double c, double sd) {
  const double z = (y - c) / sd;
  return std::exp(-0.5 * z * z) * boost::math::constants::one_div_root_two_pi<double>() / sd;
}

}  // namespace

std::vector<double> grid(double lo, double hi, int n) {
  std::vector<double> g;
  for (int i = 0; i < n; ++i) g.push_back(lo + (hi - lo) * i / (n - 1));
  return g;
}

Evaluation evaluate(const Example& e, const std::vector<double>& mus) {
  Evaluation r;
  r.mu = mus;
  for (const double mu : mus) r.truth.push_back(truth(e.f, mu, e.sigma));
  for (const Method& m : e.methods) {
    std::vector<double> v;
    double se = 0;
    for (std::size_t i = 0; i < mus.size(); ++i) {
      v.push_back(m.approx(mus[i]));
      se += (v.back() - r.truth[i]) * (v.back() - r.truth[i]);
    }
    r.values.push_back(v);
    r.mse.push_back(se / static_cast<double>(mus.size()));
  }
  return r;
}

std::vector<Example> table1() {
  const double s = 0.5;  // sigma_X^2 = 0.25
  std::vector<Example> t = {exp_of_square(-1, s, "exp(-x^2)"), sin_of_square(s),
                            exp_of_square(-2, s, "exp(-2x^2)")};
  t[0].paper_mse = {{"rule1", 0.00006}, {"yang_fract", 0.00221}, {"adaptive", 0.00099}};
  t[1].paper_mse = {{"rule1", 0.00065}, {"yang_fract", 0.00216}, {"adaptive", 0.00189}};
  t[2].paper_mse = {{"rule1", 0.00019}, {"yang_fract", 0.00389}, {"adaptive", 0.54072}};
  return t;
}

Example figure2() {
  Example e = exp_of_square(-1, std::sqrt(0.5), "exp(-x*x)");
  e.note = "plotted only in the paper (no MSE printed)";
  return e;
}

Example figure4(int* rule1_steps) {
  const double s = std::sqrt(0.13);
  Example e{"sin(0.5 - 0.5 exp(-2x^2))",
            [](double x) { return std::sin(0.5 - 0.5 * std::exp(-2 * x * x)); },
            s,
            {},
            {},
            ""};
  const Fn e2 = [](double u) { return std::exp(-2 * u); };
  const Fn sn = [](double u) { return std::sin(u); };
  e.methods = {
      {"adaptive", "adaptive Gaussian [YB18]",
       [=](double mu) {
         const Stat x3 = adaptive(bl::gaussian::exp, bl::gaussian::exp_sq, -2, 0, square_of_normal(mu, s));
         return adaptive(bl::gaussian::sin, bl::gaussian::sin_sq, -0.5, 0.5, x3).mean;
       }},
      {"rule1", "Rule 1 (renormalized Gaussian at every clamped node)",
       [=](double mu) {
         // x1 = x^2 in [0, inf); x3 = exp(-2 x1) in [0, 1]; x4 = 0.5 - 0.5 x3 in [0, 0.5].
         const Stat x3 = rule1(e2, square_of_normal(mu, s), 0, kInf, rule1_steps);
         const Stat x4{0.5 - 0.5 * x3.mean, 0.25 * x3.var};
         return rule1(sn, x4, 0, 0.5, rule1_steps).mean;
       }},
      {"rule2", "Rule 2 (mode fit at exp, adaptive at sin)",
       [=](double mu) {
         const Stat x3 = rule2(bl::rule2::exp, -2, 0, square_of_normal(mu, s));
         return adaptive(bl::gaussian::sin, bl::gaussian::sin_sq, -0.5, 0.5, x3).mean;
       }},
      {"rule3", "Rule 3 (Taylor of the composition)",
       [=](double mu) {
         return rule3(jet_sin(affine(jet_exp(affine(jet_sq(mu), -2, 0)), -0.5, 0.5)), mu, s).mean;
       }},
  };
  e.paper_mse = {{"adaptive", 0.05}, {"rule1", 0.000023}, {"rule2", 0.0037}, {"rule3", 0.000018}};
  e.note =
      "Rule 2 is fitted at the exp node only: the table has no mode fit for sin or pow2 (not monotone), "
      "so x^2 keeps its exact moments and sin the adaptive Gaussian";
  return e;
}

Figure3 figure3() {
  Figure3 f{};
  f.sigma = 0.5;
  const double m = bl::gaussian::exp(0.0, f.sigma);
  f.adaptive = {m, bl::gaussian::exp_sq(0.0, f.sigma) - m * m};
  f.rule1 = bl::rule1::renormalize(bl::rule1::Kernel::gaussian, f.adaptive.mean, f.adaptive.var, 0.0, kInf);
  f.rule1_tm = bl::truncnorm::moments(f.rule1.center, f.rule1.sigma, 0.0, kInf);
  f.rule2 = bl::rule2::exp(0.0, f.sigma);
  f.paper_mse = {{"adaptive", 0.033}, {"rule1", 0.038}, {"rule2", 0.021}};
  return f;
}

double Figure3::lognormal(double y) const {
  if (!(y > 0)) return 0;
  const double z = std::log(y) / sigma;
  return std::exp(-0.5 * z * z) * boost::math::constants::one_div_root_two_pi<double>() / (y * sigma);
}

double Figure3::density(const std::string& key, double y) const {
  if (key == "adaptive") return gauss_pdf(y, adaptive.mean, std::sqrt(adaptive.var));
  if (key == "rule2") return gauss_pdf(y, rule2.mean, std::sqrt(rule2.var));
  if (key == "rule1") return y < 0 ? 0 : gauss_pdf(y, rule1.center, rule1.sigma) / rule1_tm.mass;
  return NAN;
}

double density_mse(const Figure3& f, const std::string& key) {
  const std::vector<double> ys = grid(kDensityLo, kDensityHi, kDensityN);
  double se = 0;
  for (const double y : ys) se += std::pow(f.density(key, y) - f.lognormal(y), 2);
  return se / static_cast<double>(ys.size());
}

}  // namespace clamped_paper
