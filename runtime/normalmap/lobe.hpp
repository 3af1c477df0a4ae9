// Specular filtering formulas over a footprint's normal statistics (no textures here: numbers in,
// numbers out, so the tests can check each against an independent reference).
//
// Ours (Li et al. 2020, Sec. 4.3.1, eqs. 24-25): the angle theta between the normal and a vector h
// is taken as Gaussian, theta ~ N(mu, sigma^2), with mu = acos(dot(N/|N|, h)) and
// sigma = acos(|N|) / 2 for N the averaged (unnormalized) normal at the footprint's mip level; the
// filtered specular is E[f(cos theta)].
//   Blinn-Phong, closed form: for an integer s, cos^s t = 2^-s sum_k C(s,k) cos((s-2k) t) and
//   E[cos(j theta)] = cos(j mu) exp(-j^2 sigma^2 / 2), so
//     E[cos^s theta] = 2^-s sum_k C(s,k) cos((s-2k) mu) exp(-(s-2k)^2 sigma^2 / 2)
//   (exact for cos^s; the max(0, .) clamp differs only where theta passes pi/2, where cos^s is ~0
//   for the exponents used).
//   GGX D: no closed form. For sigma <= alpha / 2, 16-node Gauss-Hermite quadrature over theta; for
//   wider footprints the Gaussian's nodes would step over the lobe (width ~alpha), so the expectation
//   is read from a table over (mu, sigma) built once per alpha by dense quadrature (composite
//   Simpson, step alpha / 24) and interpolated bilinearly (steps alpha / 8 in mu and sigma).
// Toksvig (2005): sigma_T^2 = (1 - |N|) / |N| (eq. 23). Blinn-Phong: s' = s / (1 + s sigma_T^2) and
// the lobe scaled by (1 + s') / (1 + s) (energy of the unnormalized lobe kept); GGX: alpha'^2 =
// alpha^2 + 2 sigma_T^2 (slope variance adds, the form of Tokuyoshi & Kaplanyan's kernel roughness).
// LEAN (Olano & Baker 2010): slopes b = (n_x/n_z, n_y/n_z) with first and second moments
// mip-filtered linearly; Sigma = E[b b^T] - E[b] E[b]^T is the footprint's slope covariance; the
// per-texel lobe (Blinn-Phong s ~ a slope-space Gaussian of covariance I/s, Beckmann m ~ m^2/2 I)
// adds to it, and the filtered lobe is evaluated at the half vector's slope h~ = (h_x/h_z, h_y/h_z).
#pragma once

#include <vector>

namespace bl::normalmap {

// Binomial weights 2^-s C(s, k), k = 0..s/2 (the closed form's coefficients), for s >= 0.
std::vector<double> cos_power_coefficients(int s);

// E[cos^s theta], theta ~ N(mu, sigma^2); `coef` from cos_power_coefficients(s).
double expected_cos_power(const std::vector<double>& coef, int s, double mu, double sigma);

// E[ggx_d(cos theta, alpha)], theta ~ N(mu, sigma^2): Gauss-Hermite or the table, as above.
class GgxLobeTable {
 public:
  explicit GgxLobeTable(double alpha);
  double expected(double mu, double sigma) const;
  double alpha() const { return alpha_; }

 private:
  double alpha_, step_, sigma0_;
  int n_mu_ = 0, n_sigma_ = 0;
  std::vector<double> table_;  // [i_sigma * n_mu + i_mu]
};
// The table for alpha, built on first use and kept (thread-safe).
const GgxLobeTable& ggx_lobe_table(double alpha);
// The same through the per-alpha table cache (thread-safe; builds the table on first use).
double expected_ggx_d(double mu, double sigma, double alpha);
// The dense reference the table is built from (Simpson over theta in (-pi/2, pi/2)).
double expected_ggx_d_dense(double mu, double sigma, double alpha);

// Eqs. 24-25 for the averaged normal N (length len, 0 < len <= 1) and unit h: mu and sigma.
struct AngleStats {
  double mu = 0, sigma = 0;
};
AngleStats angle_stats(double n_dot_h_unit, double len);

// Toksvig's variance from |N| (eq. 23), clamped to |N| in [1e-4, 1].
double toksvig_variance(double len);
// Blinn-Phong lobe value for unit-normal cosine c under Toksvig (scale and exponent above).
double toksvig_blinn_phong(double c, int s, double sigma2);
double toksvig_ggx_alpha(double alpha, double sigma2);

// Gauss-Hermite nodes x_i and weights w_i for E[f(Z)], Z ~ N(0, 1): E ~ sum w_i f(x_i).
struct Quadrature {
  std::vector<double> x, w;
};
const Quadrature& gauss_hermite(int n);  // n in {8, 16, 32, 64}

// LEAN: the moments at a footprint (E[b], E[b b^T]) -> slope mean and covariance.
struct SlopeStats {
  double bx = 0, by = 0;             // mean slope
  double sxx = 0, syy = 0, sxy = 0;  // covariance
};
SlopeStats slope_stats(const float m[5]);  // m = (E bx, E by, E bx^2, E by^2, E bx by)

// Blinn-Phong under LEAN: ks is the caller's; returns exp(-q/2) / (s sqrt(det Sigma')) with
// Sigma' = Sigma + I/s and q the Mahalanobis distance of h~ - E[b] (1 at Sigma = 0, h~ = E[b]).
double lean_blinn_phong(const SlopeStats& st, double hx, double hy, double hz, int s);
// Beckmann NDF of roughness m under LEAN: the slope density N(h~; E[b], Sigma + m^2/2 I) divided
// by h_z^4 (a microfacet NDF D(h), with the projected-area normalization of Beckmann's).
double lean_beckmann_d(const SlopeStats& st, double hx, double hy, double hz, double m);
// The slope-space density alone (P22 of the filtered distribution) at slope (sx, sy).
double lean_beckmann_p22(const SlopeStats& st, double sx, double sy, double m);
// GGX from LEAN's covariance (our extension, not in Olano & Baker: GGX has no finite slope
// variance): an anisotropic GGX with slope matrix A = alpha^2 I + 2 Sigma centred on E[b],
// D = 1 / (pi sqrt(det A) (1 + d^T A^-1 d)^2 h_z^4), d = h~ - E[b]. Equals ggx_d at Sigma = 0, E[b] = 0.
double lean_ggx_d(const SlopeStats& st, double hx, double hy, double hz, double alpha);

}  // namespace bl::normalmap
