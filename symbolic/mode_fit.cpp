#include "mode_fit.hpp"

#include <cmath>
#include <sstream>

#include "functions.hpp"
#include "monotone.hpp"
#include "printer.hpp"

namespace bl::sym {
using namespace GiNaC;

const symbol& var_mu() {
  static const symbol s("mu");
  return s;
}
const symbol& var_sig() {
  static const symbol s("sigma");
  return s;
}

namespace {

std::string text(const ex& e) {
  return print(e, Lang::Text);
}

double num30(const ex& e) {
  const int saved = Digits;
  Digits = 30;
  double r = std::nan("");
  try {
    const ex v = e.evalf();
    if (is_a<numeric>(v) && ex_to<numeric>(v).is_real()) r = ex_to<numeric>(v).to_double();
  } catch (const std::exception&) {
  }
  Digits = saved;
  return r;
}

// sinh/cosh -> tanh, so the emitted ratio does not overflow to inf/inf.
ex tidy(const ex& e) {
  const symbol& x = var_x();
  return e.subs(sinh(x) == tanh(x) * cosh(x)).normal();
}

// Why Rule 2 is ill posed for a, or "" when it is well posed.
std::string why_not(const Atomic& a) {
  if (a.monotone.empty())
    return "the catalog declares no monotone pieces (f is constant on intervals, or has a critical point "
           "where the density of Y is unbounded)";
  const symbol& x = var_x();
  for (const Monotone& m : a.monotone) {
    const ex fp = monotone_f(a, m).diff(x);
    for (const Bound* b : {&m.lo, &m.hi}) {
      if (!b->finite()) continue;
      const double e = b->to_double(), inside = b == &m.lo ? e + 1e-10 : e - 1e-10;
      if (std::abs(num30(fp.subs(x == numeric(inside)))) < 1e-6) {
        std::ostringstream o;
        o << "f'(" << text(b->value)
          << ") = 0 at the end of a monotone piece: the density of Y is unbounded at f(" << text(b->value)
          << "), so the mode is there with zero width (degenerate fit)";
        return o.str();
      }
    }
  }
  // The pieces must tile the domain (or one period): a flat part puts an atom into Y.
  double covered = 0;
  for (size_t i = 0; i < a.monotone.size(); ++i) {
    if (i > 0 && std::abs(a.monotone[i].lo.to_double() - a.monotone[i - 1].hi.to_double()) > 1e-12)
      return "the monotone pieces leave gaps (f is constant there: Y has atoms)";
    covered += a.monotone[i].hi.to_double() - a.monotone[i].lo.to_double();
  }
  if (a.period) {
    if (std::abs(covered - num30(*a.period)) > 1e-12) return "the monotone pieces do not tile a period";
  } else if (a.monotone.front().lo.to_double() > a.domain_lo.to_double() ||
             a.monotone.back().hi.to_double() < a.domain_hi.to_double()) {
    return "f is constant outside its monotone pieces (Y has atoms at the clamp values: Rule 1 territory)";
  }
  return "";
}

// Sample (mu, sigma) at which a closed-form root choice is tested.
const double kMu[] = {-2.5, -0.7, 0.0, 0.4, 3.0};
const double kSig[] = {0.05, 0.6, 2.0};

// For a degree-2 numerator, the root (+1 or -1) that is a mode (inside the piece, q' > 0) at every
// sample, or 0 when neither is.
int choose_root(const ModePiece& p) {
  const symbol& x = var_x();
  for (int sgn : {1, -1}) {
    bool ok = true;
    for (double m : kMu)
      for (double s : kSig) {
        const lst at{var_mu() == numeric(m), var_sig() == numeric(s)};
        const double c2 = num30(p.c2.subs(at)), c1 = num30(p.c1.subs(at)), c0 = num30(p.c0.subs(at));
        const double disc = c1 * c1 - 4 * c2 * c0;
        if (!(disc >= 0)) {
          ok = false;
          continue;
        }
        const double r = (-c1 + sgn * std::sqrt(disc)) / (2 * c2);
        const bool inside = r > p.lo.to_double() && r < p.hi.to_double();
        const double dq = inside ? num30(p.dq.subs(at).subs(x == numeric(r))) : -1;
        if (!(dq > 0)) ok = false;
      }
    if (ok) return sgn;
  }
  return 0;
}

// Cross-check against Li's equation in y through the catalog inverse: E(f(x)) = q(x) / f'(x)^2.
void check_against_inverse(const Atomic& a, const Monotone& m, const ModePiece& p) {
  const symbol& x = var_x();
  for (double xv : interior_points(m.lo, m.hi, 4))
    for (double s : kSig) {
      const lst at{var_mu() == numeric(0.3), var_sig() == numeric(s)};
      const double yv = num30(p.f.subs(x == numeric(xv)));
      const double lhs = num30(p.y_equation.subs(at).subs(var_y() == numeric(yv)));
      const double rhs = num30((p.q / pow(p.fp, 2)).subs(at).subs(x == numeric(xv)));
      if (!(std::abs(lhs - rhs) <= 1e-9 * std::max(1.0, std::abs(rhs))))
        throw std::runtime_error("rule2 " + a.name +
                                 ": the mode equation in x disagrees with Li's equation in y");
    }
}

}  // namespace

std::vector<ModeFit> derive_mode_fits(const Catalog& cat, std::vector<NotDerived>* not_derived) {
  register_functions();
  const symbol& x = var_x();
  const symbol& y = var_y();
  const ex mu = var_mu(), s = var_sig();
  std::vector<ModeFit> out;
  for (const Atomic& a : cat.atomics) {
    const std::string reason = why_not(a);
    if (!reason.empty()) {
      if (not_derived) not_derived->push_back({a.name, "gaussian (rule2)", false, reason});
      continue;
    }
    ModeFit fit;
    fit.atomic = &a;
    fit.period = a.period;
    bool newton = false;
    std::string eqs;
    for (const Monotone& m : a.monotone) {
      ModePiece p;
      p.lo = m.lo;
      p.hi = m.hi;
      p.f = monotone_f(a, m);
      p.fp = p.f.diff(x).normal();
      const ex r = tidy(p.f.diff(x, 2) / p.f.diff(x));
      p.q = (x - mu) + pow(s, 2) * r;
      p.dq = tidy(p.q.diff(x));
      const ex g = m.inverse;
      p.y_equation = pow(g.diff(y), 2) * (g - mu) - pow(s, 2) * g.diff(y, 2);
      check_against_inverse(a, m, p);
      const ex qn = p.q.normal();
      const ex num = qn.numer().expand();
      if (num.is_polynomial(x) && num.degree(x) >= 1 && num.degree(x) <= 2 && !qn.denom().has(mu)) {
        p.degree = num.degree(x);
        p.c2 = num.coeff(x, 2);
        p.c1 = num.coeff(x, 1);
        p.c0 = num.coeff(x, 0);
        if (p.degree == 2) p.root = choose_root(p);
        if (p.degree == 2 && p.root == 0) p.degree = -1;
      }
      if (p.degree < 0) newton = true;
      std::string piece = "[" + (m.lo.finite() ? text(m.lo.value) : std::string("-inf")) + ", " +
                          (m.hi.finite() ? text(m.hi.value) : std::string("inf")) + ")";
      eqs += (eqs.empty() ? "" : "; ") + std::string("on ") + piece + ": Li eq. 13 " + text(p.y_equation) +
             " = 0 <=> q(x) = " + text(p.q) + " = 0";
      if (p.degree == 1) eqs += ", x* = " + text(-p.c0 / p.c1);
      if (p.degree == 2)
        eqs += ", x* = root " + std::string(p.root > 0 ? "+" : "-") + " of " + text(p.c2) + " x^2 + " +
               text(p.c1) + " x + " + text(p.c0);
      fit.pieces.push_back(p);
    }
    fit.method = newton ? "newton (bracket from x0 = mu by doubling steps, safeguarded Newton <= 100 "
                          "iterations, |dx| <= 4 eps (|x| + sigma))"
                        : "closed form";
    fit.formula =
        "mode fit of Y = " + a.name + "(X), X ~ N(mu, sigma^2), on the monotone piece containing mu" +
        std::string(a.period ? " (mu reduced to one period)" : "") +
        " (nearest piece when mu is outside): " + eqs +
        "; mY = f(x*), var = (sigma |f'(x*)| exp((x* - mu)^2 / (2 sigma^2)))^2; sigma = 0 gives f(mu)";
    out.push_back(fit);
  }
  return out;
}

}  // namespace bl::sym
