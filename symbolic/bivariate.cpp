#include "bivariate.hpp"

#include <stdexcept>

#include "functions.hpp"
#include "gauss_expect.hpp"
#include "printer.hpp"

namespace bl::sym {
using namespace GiNaC;

const BivariateSymbols& biv() {
  static const BivariateSymbols s;
  return s;
}

namespace {

const symbol z1("z1"), z2("z2"), z3("z3"), w("w"), v("v"), q("q"), rc("rc");

std::string text(const ex& e) {
  return print(e, Lang::Text);
}

// A = ma + sa z1, B = mb + sb (rho z1 + sqrt(1 - rho^2) z2): jointly normal with correlation rho.
ex A() {
  return biv().ma + biv().sa * z1;
}
ex B() {
  return biv().mb + biv().sb * (biv().rho * z1 + rc * z2);
}

// E[p(A, B)]: rc only appears squared after integrating out z2 (odd moments vanish).
ex E2(const ex& p) {
  return normal_expect(p, {z1, z2}).subs(rc == sqrt(1 - pow(biv().rho, 2))).expand();
}

void require_equal(const std::string& what, const ex& derived, const ex& emitted) {
  if (!(derived - emitted).expand().is_zero())
    throw std::runtime_error("bivariate " + what + ": emitted form " + text(emitted) + " != derived " +
                             text(derived));
}

// Var(A + k B) for k = +-1, emitted as (sa - sb)^2 + 2 (1 + k rho) sa sb (two non-negative terms).
ex stable_sum_var(int k) {
  const auto& S = biv();
  return pow(S.sa - S.sb, 2) + 2 * (1 + k * S.rho) * S.sa * S.sb;
}

BivariateRule linear(const std::string& op, int k) {
  const auto& S = biv();
  BivariateRule r;
  r.op = op;
  const ex Y = A() + k * B();
  r.mean = E2(Y);
  r.var = stable_sum_var(k);
  require_equal(op + " variance", E2(pow(Y - r.mean, 2)), r.var);
  r.formula = "mean = " + text(r.mean) + "; var = " + text(r.var) + " (= sa^2 + sb^2 " + (k > 0 ? "+" : "-") +
              " 2 rho sa sb)";
  r.assumption = "A, B jointly normal with correlation rho (exact)";
  r.method = "closed form";
  (void)S;
  return r;
}

BivariateRule product() {
  const auto& S = biv();
  BivariateRule r;
  r.op = "mul";
  const ex Y = A() * B();
  r.mean = E2(Y);
  const ex derived = E2(pow(Y, 2)) - pow(r.mean, 2);
  // Sum of non-negative terms for |rho| <= 1 (no cancellation at rho = -1).
  r.var = pow(S.ma * S.sb + S.rho * S.mb * S.sa, 2) + (1 - S.rho) * (1 + S.rho) * pow(S.mb * S.sa, 2) +
          (1 + pow(S.rho, 2)) * pow(S.sa * S.sb, 2);
  require_equal("mul variance", derived, r.var);
  r.formula = "mean = " + text(r.mean) + "; var = " + text(derived.collect(lst{S.ma, S.mb}, true)) +
              " (exact; Yang & Barnes 2018 eq. 4.9 prints ma^2 sb + sa mb^2 for the first two terms, a "
              "typo: the units do not even match)";
  r.assumption = "A, B jointly normal with correlation rho (exact)";
  r.method = "closed form";
  return r;
}

// max (sign = +1) or min (sign = -1). With the argument of the larger (max) or smaller (min) mean
// as A (the emitted code swaps), max = A + (B - A)_+ and min = A - (A - B)_+: the correction has
// mean <= 0 inside ( )_+, so it is small where the means are far apart and nothing large cancels.
// E = sign (B - A) = me + s W with W standard normal; A - ma = (cv / s) W + d V with V independent
// of W, cv = Cov(A, E), d^2 = sa^2 - cv^2 / s^2; ( )_+ = (me + s W) 1{W > -t}, t = me / s.
BivariateRule extreme(int sign) {
  const auto& S = biv();
  BivariateRule r;
  r.op = sign > 0 ? "max" : "min";
  const ex Ediff = sign * (B() - A());
  const ex me = E2(Ediff);
  const ex var_e = E2(pow(Ediff - me, 2));
  require_equal(r.op + " Var(B - A)", var_e, stable_sum_var(-1));
  const ex cov = E2((A() - S.ma) * (Ediff - me));
  r.locals = {{S.s2, stable_sum_var(-1)}, {S.s, sqrt(S.s2)}, {S.t, me / S.s}, {S.cv, cov}};
  const ex d = sqrt(pow(S.sa, 2) - pow(S.cv / S.s, 2));
  const ex Y = (S.cv / S.s) * w + d * v + sign * (S.s * S.t + S.s * w) * q;
  const ex m1 = gauss_expect(Y, w, {v}, q, S.t);
  const ex m2 = gauss_expect(pow(Y, 2), w, {v}, q, S.t);
  r.mean = (S.ma + m1).expand();
  r.var = (m2 - pow(m1, 2)).expand().collect(lst{Phi(S.t), phi(S.t)}, true);
  r.formula = std::string(sign > 0 ? "max(A, B) = A + (B - A)_+" : "min(A, B) = A - (A - B)_+") +
              " with A the " + (sign > 0 ? "larger" : "smaller") + " mean; s2 = " + text(stable_sum_var(-1)) +
              ", s = sqrt(s2), t = " + text(me) + "/s, cv = " + text(cov) + "; mean = " + text(r.mean) +
              "; var = " + text(r.var) + " (Clark 1961; s = 0 gives A)";
  r.assumption = "A, B jointly normal with correlation rho (exact)";
  r.method = "closed form (Phi, phi)";
  return r;
}

// less(a, b) = step(b - a), greater(a, b) = step(a - b): P(D > 0) for D = sign (B - A) normal.
BivariateRule compare(int sign) {
  const auto& S = biv();
  BivariateRule r;
  r.op = sign > 0 ? "less" : "greater";
  const ex D = sign * (B() - A());
  const ex md = E2(D);
  require_equal(r.op + " Var(D)", E2(pow(D - md, 2)), stable_sum_var(-1));
  r.locals = {{S.s2, stable_sum_var(-1)}, {S.s, sqrt(S.s2)}, {S.t, md / S.s}};
  r.mean = gauss_expect(q, w, {}, q, S.t);
  const ex derived = gauss_expect(q, w, {}, q, S.t) - pow(r.mean, 2);  // step^2 = step
  r.var = Phi(S.t) * Phi(-S.t);                                        // 1 - Phi(t) without cancellation
  require_equal(r.op + " variance", derived, r.var.subs(Phi(-S.t) == 1 - Phi(S.t)));
  r.formula = std::string(sign > 0 ? "less(a, b) = step(b - a)" : "greater(a, b) = step(a - b)") +
              "; s2 = " + text(stable_sum_var(-1)) + ", t = " + text(md) +
              "/sqrt(s2); mean = " + text(r.mean) + "; var = " + text(r.var) +
              " (= mean (1 - mean); s = 0 gives step of the mean difference)";
  r.assumption = "A, B jointly normal with correlation rho (exact); step(0) = 0";
  r.method = "closed form (Phi)";
  return r;
}

// select(c, a, b) = c a + (1 - c) b with C, A, B independent. Only E[C] and E[C^2] enter, so the
// result holds for any distribution of C (a comparison's Bernoulli-like value included).
BivariateRule select() {
  const auto& S = biv();
  BivariateRule r;
  r.op = "select";
  const ex C = S.mc + S.sc * z3, Aa = S.ma + S.sa * z1, Bb = S.mb + S.sb * z2;
  const ex Y = C * Aa + (1 - C) * Bb;
  const ex mean = normal_expect(Y, {z1, z2, z3});
  const ex var = normal_expect(pow(Y - mean, 2), {z1, z2, z3});
  r.mean = S.mb + S.mc * (S.ma - S.mb);  // exact at mc = 0 and 1
  require_equal("select mean", mean, r.mean);
  r.var = pow((1 - S.mc) * S.sb, 2) + pow(S.mc * S.sa, 2) +
          pow(S.sc, 2) * (pow(S.sa, 2) + pow(S.sb, 2) + pow(S.ma - S.mb, 2));
  require_equal("select variance", var, r.var);
  r.formula = "mean = " + text(r.mean) + "; var = " + text(r.var);
  r.assumption =
      "C, A, B mutually independent (the signature has no correlations); exact for any distribution of C "
      "with mean mc and standard deviation sc";
  r.method = "closed form";
  return r;
}

// mod(a, c) = c fract(a / c), X = a / c ~ N(xm, sn^2), sn = sa / |c|. For sn <= 0.05 the mass of
// X meets at most the jump k nearest to xm (the next ones are >= 0.5 = 10 sn away): with
// mu = xm - k and X = k + mu + sn Z, fract(X) = mu + sn Z + 1{Z < -mu/sn}; with w = -Z the
// indicator is 1{w > t}, t = mu / sn. Wider kernels use the table's fract and fract_sq.
BivariateRule mod() {
  const auto& S = biv();
  BivariateRule r;
  r.op = "mod";
  r.locals = {{S.t, S.mu / S.sn}};
  const ex Y = S.mu - S.sn * w + q;
  const ex m1 = gauss_expect(Y, w, {}, q, -S.t).subs(phi(-S.t) == phi(S.t));
  const ex m2 = gauss_expect(pow(Y, 2), w, {}, q, -S.t).subs(phi(-S.t) == phi(S.t));
  r.mean = m1;
  const ex derived = (m2 - pow(m1, 2)).expand();
  r.var = pow(S.sn, 2) - 2 * S.sn * phi(S.t) + Phi(S.t) * Phi(-S.t);
  require_equal("mod variance", derived.subs(Phi(-S.t) == 1 - Phi(S.t)),
                r.var.subs(Phi(-S.t) == 1 - Phi(S.t)));
  r.formula =
      "mod(a, c) = c fract(a/c) (Yang & Barnes 2018 eq. 4.10 with sigma = sa/|c|); for sn = sa/|c| <= 0.05, "
      "with k the integer nearest to xm = ma/c, mu = xm - k, t = mu/sn: fract mean = " +
      text(r.mean) + ", fract var = " + text(r.var) +
      "; otherwise mean = gaussian::fract(xm, sn), var = gaussian::fract_sq(xm, sn) - mean^2; then mean *= "
      "c, "
      "var *= c^2";
  r.assumption = "c is a constant (not random); A normal";
  r.method = "closed form (local jump for sn <= 0.05, table fract/fract_sq beyond)";
  return r;
}

}  // namespace

ex paper_product_variance_eq49() {
  const auto& S = biv();
  return pow(S.ma, 2) * S.sb + S.sa * pow(S.mb, 2) + 2 * S.rho * S.ma * S.mb * S.sa * S.sb +
         pow(S.sa * S.sb, 2) * (1 + pow(S.rho, 2));
}

std::vector<BivariateRule> derive_bivariate() {
  register_functions();
  std::vector<BivariateRule> rs;
  rs.push_back(linear("add", 1));
  rs.push_back(linear("sub", -1));
  rs.push_back(product());
  rs.push_back(extreme(-1));
  rs.push_back(extreme(1));
  rs.push_back(compare(1));
  rs.push_back(compare(-1));
  rs.push_back(select());
  rs.push_back(mod());
  return rs;
}

}  // namespace bl::sym
