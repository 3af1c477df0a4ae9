#include "normalmap/lobe.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>

#include "normalmap/brdf.hpp"

namespace bl::normalmap {

std::vector<double> cos_power_coefficients(int s) {
  if (s < 0) throw std::invalid_argument("cos_power_coefficients: negative exponent");
  std::vector<double> c(s / 2 + 1);
  for (int k = 0; k <= s / 2; ++k)
    c[k] =
        std::exp(std::lgamma(s + 1.0) - std::lgamma(k + 1.0) - std::lgamma(s - k + 1.0) - s * std::log(2.0));
  return c;
}

double expected_cos_power(const std::vector<double>& coef, int s, double mu, double sigma) {
  // Terms k and s - k share j = s - 2k: 2 C(s,k) for k < s/2, C(s, s/2) once for even s. Walk j
  // upward from s mod 2 in steps of 2 with recurrences instead of a cos and an exp per term:
  //   cos((j+2) mu) = 2 cos(2 mu) cos(j mu) - cos((j-2) mu),
  //   g_j = exp(-j^2 v): g_{j+2} = g_j r_j, r_j = exp(-(4j + 4) v), r_{j+2} = r_j exp(-8 v)
  // (upward, so a vanishing g underflows harmlessly to 0).
  const double v = 0.5 * sigma * sigma, c2 = 2 * std::cos(2 * mu), q = std::exp(-8 * v);
  int j = s % 2;
  double c_prev = j == 0 ? std::cos(2 * mu) : std::cos(mu);  // cos((j-2) mu): cos(-2mu) or cos(-mu)
  double c = j == 0 ? 1.0 : std::cos(mu);
  double g = j == 0 ? 1.0 : std::exp(-v), r = std::exp(-(4.0 * j + 4) * v);
  double sum = 0;
  for (int k = s / 2; k >= 0; --k, j += 2) {
    sum += (j == 0 ? coef[k] : 2 * coef[k]) * c * g;
    const double c_next = c2 * c - c_prev;
    c_prev = c, c = c_next;
    g *= r, r *= q;
  }
  return sum;
}

const Quadrature& gauss_hermite(int n) {
  static std::mutex mu;
  static std::map<int, Quadrature> cache;
  std::lock_guard<std::mutex> lock(mu);
  auto it = cache.find(n);
  if (it != cache.end()) return it->second;
  // Physicists' Hermite nodes by Newton's method on the orthonormal recurrence (Numerical Recipes
  // gauher), then scaled to the standard normal: x = sqrt(2) t, w = w_t / sqrt(pi).
  std::vector<double> t(n), wt(n);
  const double pim4 = 0.7511255444649425;  // pi^-1/4
  double z = 0;
  for (int i = 0; i < (n + 1) / 2; ++i) {
    if (i == 0)
      z = std::sqrt(2.0 * n + 1) - 1.85575 * std::pow(2.0 * n + 1, -0.16667);
    else if (i == 1)
      z -= 1.14 * std::pow(double(n), 0.426) / z;
    else if (i == 2)
      z = 1.86 * z - 0.86 * t[0];
    else if (i == 3)
      z = 1.91 * z - 0.91 * t[1];
    else
      z = 2.0 * z - t[i - 2];
    double pp = 0;
    for (int its = 0; its < 100; ++its) {
      double p1 = pim4, p2 = 0;
      for (int j = 0; j < n; ++j) {
        const double p3 = p2;
        p2 = p1;
        p1 = z * std::sqrt(2.0 / (j + 1)) * p2 - std::sqrt(double(j) / (j + 1)) * p3;
      }
      pp = std::sqrt(2.0 * n) * p2;
      const double z1 = z;
      z = z1 - p1 / pp;
      if (std::fabs(z - z1) <= 1e-14) break;
    }
    t[i] = z;
    t[n - 1 - i] = -z;
    wt[i] = wt[n - 1 - i] = 2.0 / (pp * pp);
  }
  Quadrature q;
  for (int i = 0; i < n; ++i) {
    q.x.push_back(std::sqrt(2.0) * t[i]);
    q.w.push_back(wt[i] / std::sqrt(M_PI));
  }
  return cache.emplace(n, std::move(q)).first->second;
}

double expected_ggx_d_dense(double mu, double sigma, double alpha) {
  if (sigma <= 0) return ggx_d(std::cos(mu), alpha);
  const double lo = std::max(-0.5 * M_PI, mu - 8 * sigma), hi = std::min(0.5 * M_PI, mu + 8 * sigma);
  if (!(hi > lo)) return 0;
  int n = 2 * static_cast<int>(std::ceil((hi - lo) / std::min(alpha / 24, sigma / 8) / 2));
  n = std::max(n, 16);
  const double h = (hi - lo) / n;
  double sum = 0;
  for (int i = 0; i <= n; ++i) {
    const double t = lo + i * h, z = (t - mu) / sigma;
    const double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    sum += w * ggx_d(std::cos(t), alpha) * std::exp(-0.5 * z * z);
  }
  return sum * h / 3 / (sigma * std::sqrt(2 * M_PI));
}

GgxLobeTable::GgxLobeTable(double alpha) : alpha_(alpha), step_(alpha / 8), sigma0_(alpha / 2) {
  n_mu_ = static_cast<int>(std::ceil(M_PI / step_)) + 2;
  n_sigma_ = static_cast<int>(std::ceil((0.5 * M_PI - sigma0_) / step_)) + 2;
  table_.resize(std::size_t(n_mu_) * n_sigma_);
  for (int j = 0; j < n_sigma_; ++j)
    for (int i = 0; i < n_mu_; ++i)
      table_[std::size_t(j) * n_mu_ + i] = expected_ggx_d_dense(i * step_, sigma0_ + j * step_, alpha);
}

double GgxLobeTable::expected(double mu, double sigma) const {
  mu = std::fabs(mu);  // D(cos theta) is even in theta
  if (sigma <= sigma0_) {
    if (sigma <= 0) return ggx_d(std::cos(mu), alpha_);
    static const Quadrature& q = gauss_hermite(16);
    double sum = 0;
    for (std::size_t i = 0; i < q.x.size(); ++i) sum += q.w[i] * ggx_d(std::cos(mu + sigma * q.x[i]), alpha_);
    return sum;
  }
  const double fm = std::min(mu / step_, n_mu_ - 1.000001),
               fs = std::min((sigma - sigma0_) / step_, n_sigma_ - 1.000001);
  const int i = static_cast<int>(fm), j = static_cast<int>(fs);
  const double a = fm - i, b = fs - j;
  const double* r0 = &table_[std::size_t(j) * n_mu_ + i];
  const double* r1 = r0 + n_mu_;
  return (1 - b) * ((1 - a) * r0[0] + a * r0[1]) + b * ((1 - a) * r1[0] + a * r1[1]);
}

const GgxLobeTable& ggx_lobe_table(double alpha) {
  static std::mutex m;
  static std::map<double, std::unique_ptr<GgxLobeTable>> tables;
  std::lock_guard<std::mutex> lock(m);
  auto& slot = tables[alpha];
  if (!slot) slot = std::make_unique<GgxLobeTable>(alpha);
  return *slot;
}

double expected_ggx_d(double mu, double sigma, double alpha) {
  return ggx_lobe_table(alpha).expected(mu, sigma);
}

AngleStats angle_stats(double n_dot_h_unit, double len) {
  AngleStats a;
  a.mu = std::acos(std::clamp(n_dot_h_unit, -1.0, 1.0));
  a.sigma = 0.5 * std::acos(std::clamp(len, 0.0, 1.0));
  return a;
}

double toksvig_variance(double len) {
  len = std::clamp(len, 1e-4, 1.0);
  return (1 - len) / len;
}

double toksvig_blinn_phong(double c, int s, double sigma2) {
  if (c <= 0) return 0;
  const double sp = s / (1 + s * sigma2);
  return (1 + sp) / (1 + s) * std::pow(c, sp);
}

double toksvig_ggx_alpha(double alpha, double sigma2) {
  return std::sqrt(alpha * alpha + 2 * sigma2);
}

SlopeStats slope_stats(const float m[5]) {
  SlopeStats s;
  s.bx = m[0], s.by = m[1];
  s.sxx = std::max(0.0, double(m[2]) - s.bx * s.bx);
  s.syy = std::max(0.0, double(m[3]) - s.by * s.by);
  s.sxy = double(m[4]) - s.bx * s.by;
  return s;
}

namespace {

// exp(-q/2) / (2 pi sqrt(det)) for the 2x2 covariance [[a, c], [c, b]] at offset (dx, dy).
double gauss2(double a, double b, double c, double dx, double dy) {
  double det = a * b - c * c;
  if (!(det > 0)) det = 1e-300;
  const double q = (b * dx * dx - 2 * c * dx * dy + a * dy * dy) / det;
  return std::exp(-0.5 * q) / (2 * M_PI * std::sqrt(det));
}

}  // namespace

double lean_blinn_phong(const SlopeStats& st, double hx, double hy, double hz, int s) {
  if (hz <= 0) return 0;
  const double e = 1.0 / s;
  // (2 pi / s) N(h~; E[b], Sigma + I/s): the integral of exp(-s |b - h~|^2 / 2) against the slopes.
  return 2 * M_PI * e * gauss2(st.sxx + e, st.syy + e, st.sxy, hx / hz - st.bx, hy / hz - st.by);
}

double lean_beckmann_p22(const SlopeStats& st, double sx, double sy, double m) {
  const double e = 0.5 * m * m;
  return gauss2(st.sxx + e, st.syy + e, st.sxy, sx - st.bx, sy - st.by);
}

double lean_beckmann_d(const SlopeStats& st, double hx, double hy, double hz, double m) {
  if (hz <= 0) return 0;
  const double hz2 = hz * hz;
  return lean_beckmann_p22(st, hx / hz, hy / hz, m) / (hz2 * hz2);
}

double lean_ggx_d(const SlopeStats& st, double hx, double hy, double hz, double alpha) {
  if (hz <= 0) return 0;
  const double a = alpha * alpha + 2 * st.sxx, b = alpha * alpha + 2 * st.syy, c = 2 * st.sxy;
  const double det = std::max(a * b - c * c, 1e-300);
  const double dx = hx / hz - st.bx, dy = hy / hz - st.by;
  const double q = (b * dx * dx - 2 * c * dx * dy + a * dy * dy) / det;
  const double hz2 = hz * hz, t = 1 + q;
  return 1.0 / (M_PI * std::sqrt(det) * t * t * hz2 * hz2);
}

}  // namespace bl::normalmap
