#include "catalog_checks.hpp"

#include <cln/real.h>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <sstream>

#include "functions.hpp"

namespace bl::sym {
using namespace GiNaC;

namespace {

constexpr int kDigits = 40;

struct DigitsGuard {
  long saved;
  explicit DigitsGuard(long d) : saved(Digits) { Digits = d; }
  ~DigitsGuard() { Digits = saved; }
};

[[noreturn]] void fail(const Atomic& a, const std::string& field, const std::string& msg) {
  throw CatalogError("catalog entry '" + a.name + "', field '" + field + "': " + msg);
}

std::string show(const numeric& v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v.to_double());
  return buf;
}

numeric pow10(int e);

// A located point for messages: a simple fraction when it is one to ~1e-14 (x = 0, not 1e-20).
std::string show_point(const numeric& c) {
  for (long q = 1; q <= 64; ++q) {
    const numeric k = numeric(cln::round1(cln::the<cln::cl_R>((c * q).to_cl_N())));
    if (abs(c - k / q) < pow10(-14) * (1 + abs(c))) {
      std::ostringstream s;
      s << k / q;
      return s.str();
    }
  }
  return show(c);
}

numeric pow10(int e) {
  return ex_to<numeric>(pow(ex(10), e));
}
numeric constant(const ex& e) {
  return ex_to<numeric>(e.evalf());
}

// The real value of e at x = at, or nothing (not real, not defined, an evaluation error).
std::optional<numeric> value_at(const ex& e, const numeric& at) {
  try {
    const ex v = e.subs(var_x() == at).evalf();
    if (!is_a<numeric>(v) || !ex_to<numeric>(v).is_real()) return std::nullopt;
    return ex_to<numeric>(v);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// Distance from t to the nearest singular point (or its periodic image).
numeric singular_distance(const Atomic& a, const numeric& t) {
  numeric best = pow10(30);
  for (const ex& s : a.singular) {
    numeric r = t - constant(s);
    if (a.period) {
      const numeric T = constant(*a.period);
      r = r - T * numeric(cln::round1(cln::the<cln::cl_R>((r / T).to_cl_N())));
    }
    best = std::min(best, abs(r), [](const numeric& u, const numeric& v) { return u < v; });
  }
  return best;
}

bool in_domain(const Atomic& a, const numeric& t) {
  if (a.domain_lo.finite() && !(t > constant(a.domain_lo.value))) return false;
  if (a.domain_hi.finite() && !(t < constant(a.domain_hi.value))) return false;
  return true;
}

// A zero of u in [a, b] where u(a) = fa and u(b) = fb have opposite signs: regula falsi with the
// Illinois modification (superlinear, and the bracket is kept), to ~1e-25 relative.
numeric bracketed_zero(const ex& u, numeric a, numeric fa, numeric b, numeric fb) {
  int side = 0;
  for (int i = 0; i < 200; ++i) {
    if (abs(b - a) <= pow10(-25) * (1 + abs(a))) break;
    numeric c = (a * fb - b * fa) / (fb - fa);
    if (!(c > std::min(a, b, [](const numeric& p, const numeric& q) { return p < q; }) &&
          c < std::max(
                  a, b, [](const numeric& p, const numeric& q) { return p < q; })))
      c = (a + b) / 2;
    const auto fc = value_at(u, c);
    if (!fc) return (a + b) / 2;  // not defined inside: the caller looks at both sides anyway
    if (fc->is_zero()) return c;
    if (fc->is_positive() == fb.is_positive()) {
      b = c;
      fb = *fc;
      if (side == -1) fa = fa / 2;
      side = -1;
    } else {
      a = c;
      fa = *fc;
      if (side == 1) fb = fb / 2;
      side = 1;
    }
  }
  return (a + b) / 2;
}

// Sign changes of u between consecutive points, each located by bisection to ~1e-19 relative.
std::vector<numeric> sign_changes(const ex& u, const std::vector<numeric>& pts) {
  std::vector<numeric> out;
  std::optional<numeric> prev;
  numeric prev_x;
  for (const numeric& p : pts) {
    const auto v = value_at(u, p);
    if (v && v->is_zero()) out.push_back(p);
    if (v && prev && ((prev->is_positive() && v->is_negative()) || (prev->is_negative() && v->is_positive())))
      out.push_back(bracketed_zero(u, prev_x, *prev, p, *v));
    if (v) {
      prev = v;
      prev_x = p;
    }
  }
  return out;
}

// Arguments whose zeros are where e may jump, kink, branch or blow up.
void break_arguments(const ex& e, std::vector<ex>& out) {
  if (is_a<function>(e)) {
    const std::string name = ex_to<function>(e).get_name();
    if (name == "abs" || name == "sgn" || name == "step" || name == "csgn" || name == "log")
      out.push_back(e.op(0));
    else if (name == "tan")
      out.push_back(cos(e.op(0)));
    else if (name == "Li2")
      out.push_back(1 - e.op(0));
  }
  if (is_a<power>(e)) {
    const ex k = e.op(1);
    if (!is_a<numeric>(k) || !ex_to<numeric>(k).is_integer() || ex_to<numeric>(k).is_negative())
      out.push_back(e.op(0));
  }
  for (size_t i = 0; i < e.nops(); ++i) break_arguments(e.op(i), out);
}

// Zeros of break arguments of e inside the domain and away from singular points: every real root
// where the argument's numerator is a rational polynomial (isolated exactly, however close together
// or far out), else the sign changes between the sample points.
std::vector<std::pair<numeric, ex>> break_points(const Atomic& a, const ex& e,
                                                 const std::vector<numeric>& pts) {
  std::vector<ex> args;
  break_arguments(e, args);
  std::vector<std::pair<numeric, ex>> out;
  for (const ex& u : args) {
    if (!u.has(var_x())) continue;
    std::vector<numeric> zs = real_roots(u);
    if (zs.empty()) zs = sign_changes(u, pts);
    for (const numeric& c : zs)
      if (in_domain(a, c) && singular_distance(a, c) > pow10(-9) * (1 + abs(c))) out.push_back({c, u});
  }
  return out;
}

std::string text(const ex& e) {
  std::ostringstream s;
  s << e;
  return s.str();
}

// Polynomial helpers (exact rational coefficients, evaluated at kDigits).
using Poly = std::vector<numeric>;
Poly coefficients(const ex& p) {
  const ex q = p.expand();
  Poly c;
  for (int k = 0; k <= q.degree(var_x()); ++k) c.push_back(ex_to<numeric>(q.coeff(var_x(), k)));
  while (c.size() > 1 && c.back().is_zero()) c.pop_back();
  return c;
}
numeric peval(const Poly& c, const numeric& t) {
  numeric r = 0;
  for (size_t k = c.size(); k-- > 0;) r = r * t + c[k];
  return r;
}
Poly derivative(const Poly& c) {
  Poly d;
  for (size_t k = 1; k < c.size(); ++k) d.push_back(c[k] * numeric(static_cast<long>(k)));
  if (d.empty()) d.push_back(0);
  return d;
}
// Real roots in (lo, hi): p is monotone between consecutive roots of p', so each such interval
// holds at most one root, found by bisection.
std::vector<numeric> roots_in(const Poly& c, const numeric& lo, const numeric& hi) {
  if (c.size() <= 1) return {};
  std::vector<numeric> cuts{lo};
  for (const numeric& r : roots_in(derivative(c), lo, hi)) cuts.push_back(r);
  cuts.push_back(hi);
  std::vector<numeric> out;
  for (size_t i = 0; i + 1 < cuts.size(); ++i) {
    numeric u = cuts[i], v = cuts[i + 1];
    const numeric pu = peval(c, u), pv = peval(c, v);
    if (pu.is_zero() && i > 0) out.push_back(u);
    if (pu.is_zero() || pv.is_zero() || pu.is_positive() == pv.is_positive()) continue;
    for (int k = 0; k < 140; ++k) {
      const numeric m = (u + v) / 2;
      (peval(c, m).is_positive() == pu.is_positive() ? u : v) = m;
    }
    out.push_back((u + v) / 2);
  }
  return out;
}

}  // namespace

// The real roots of u's numerator when that is a polynomial in x with rational coefficients
// (roots_in over the Cauchy bound), else none: the caller then samples.
std::vector<numeric> real_roots(const ex& u) {
  const ex num = u.normal().numer().expand();
  if (!num.is_polynomial(var_x()) || num.degree(var_x()) < 1) return {};
  Poly c;
  for (int k = 0; k <= num.degree(var_x()); ++k) {
    const ex ck = num.coeff(var_x(), k);
    if (!is_a<numeric>(ck) || !ex_to<numeric>(ck).is_rational()) return {};
    c.push_back(ex_to<numeric>(ck));
  }
  numeric bound = 1;
  for (size_t k = 0; k + 1 < c.size(); ++k)
    bound = std::max(bound, 1 + abs(c[k] / c.back()), [](const numeric& p, const numeric& q) { return p < q; });
  std::vector<numeric> out;
  if (c[0].is_zero()) {  // x divides u: the root 0 exactly, then the rest (bisection would not land on 0)
    out.push_back(0);
    while (c.size() > 1 && c[0].is_zero()) c.erase(c.begin());
  }
  for (const numeric& r : roots_in(c, -bound - 1, bound + 1)) out.push_back(r);
  return out;
}

namespace {

struct Extreme {
  int inf = 0;  // -1/+1: f tends to -inf/+inf
  numeric value;
  std::string where;
};

void check_value(const Atomic& a, const Extreme& e) {
  const numeric tol = pow10(-30);
  auto outside = [&]() {
    if (e.inf == 1) return !(a.range_hi.inf == 1);
    if (e.inf == -1) return !(a.range_lo.inf == -1);
    const numeric slack = tol * (1 + abs(e.value));
    if (a.range_lo.finite() && e.value < constant(a.range_lo.value) - slack) return true;
    if (a.range_hi.finite() && e.value > constant(a.range_hi.value) + slack) return true;
    return false;
  };
  if (!outside()) return;
  auto bound = [](const Bound& b) {
    return b.inf ? std::string(b.inf > 0 ? "inf" : "-inf") : show(constant(b.value));
  };
  const std::string v = e.inf ? (e.inf > 0 ? "+inf" : "-inf") : show(e.value);
  fail(a, "range",
       "declares [" + bound(a.range_lo) + ", " + bound(a.range_hi) + "] but f takes the value " + v + " " +
           e.where + " (the range clamps every smoothed output, so it must contain all of f)");
}

void check_polynomial_range(const Atomic& a, const Piece& p, size_t index) {
  const Poly c = coefficients(p.f);
  const std::string piece = "(piece " + std::to_string(index) + ", ";
  const int deg = static_cast<int>(c.size()) - 1;
  numeric bound = 1;  // Cauchy bound on the critical points
  if (deg >= 1) {
    const Poly d = derivative(c);
    for (size_t k = 0; k + 1 < d.size(); ++k)
      bound =
          std::max(bound, 1 + abs(d[k] / d.back()), [](const numeric& u, const numeric& v) { return u < v; });
  }
  const numeric lo = p.lo.finite() ? constant(p.lo.value) : -bound - 1;
  const numeric hi = p.hi.finite() ? constant(p.hi.value) : bound + 1;
  for (const Bound* b : {&p.lo, &p.hi}) {
    if (b->finite()) {
      const numeric t = constant(b->value);
      check_value(a, {0, peval(c, t), piece + "as x -> " + show(t) + ")"});
    } else if (deg >= 1) {
      // x -> +-inf: the sign of the leading term
      const bool neg_x = b->inf < 0;
      const bool pos = c.back().is_positive() != (neg_x && deg % 2 == 1);
      check_value(a, {pos ? 1 : -1, 0, piece + "as x -> " + (neg_x ? "-inf" : "inf") + ")"});
    } else {
      check_value(a, {0, c[0], piece + "constant)"});
    }
  }
  for (const numeric& r : roots_in(derivative(c), lo, hi))
    check_value(a, {0, peval(c, r), piece + "critical point x = " + show(r) + ")"});
}

// An exp-polynomial piece (sum of c x^n e^{ax}): checked, not proved. f at the finite ends, at
// points spread over the piece (geometrically towards an infinite end, out to 1e6 from its finite
// end: check_exp_piece has made every growing term impossible there, so f settles to its polynomial
// part's constant) and at the zeros of f' between them.
void check_sampled_piece_range(const Atomic& a, const Piece& p, size_t index) {
  const std::string piece = "(piece " + std::to_string(index) + ", ";
  const numeric off = constant(Pi / 1000);
  std::vector<numeric> pts;
  if (p.lo.finite() && p.hi.finite()) {
    const numeric lo = constant(p.lo.value), hi = constant(p.hi.value);
    for (int k = 0; k <= 256; ++k) pts.push_back(lo + (hi - lo) * numeric(k, 256));
  } else {
    const int dir = p.lo.finite() ? 1 : -1;  // towards the infinite end
    const numeric base = p.lo.finite() ? constant(p.lo.value) : p.hi.finite() ? constant(p.hi.value) : 0;
    if (!p.lo.finite() && !p.hi.finite())
      for (int k = 1; k <= 400; ++k) pts.push_back(-numeric(k) * constant(sqrt(ex(2))) / 16 - off);
    pts.push_back(base);
    for (int k = 1; k <= 600; ++k) {  // steps of 1/64 growing by 2% each: past 1e6 by the end
      const numeric d = numeric(k, 64) * constant(exp(ex(numeric(k, 50))));
      pts.push_back(base + dir * (d + off));
    }
  }
  std::sort(pts.begin(), pts.end(), [](const numeric& u, const numeric& v) { return u < v; });
  // Ends and critical points first: an error then names the extreme, not the first sample past it.
  for (const Bound* b : {&p.lo, &p.hi})
    if (b->finite())
      if (const auto v = value_at(p.f, constant(b->value)))
        check_value(a, {0, *v, piece + "as x -> " + show(constant(b->value)) + ")"});
  for (const numeric& t : sign_changes(p.f.diff(var_x()), pts))
    if (const auto v = value_at(p.f, t))
      check_value(a, {0, *v, piece + "critical point x = " + show(t) + ")"});
  for (const numeric& t : pts)
    if (const auto v = value_at(p.f, t)) check_value(a, {0, *v, piece + "at x = " + show(t) + ")"});
}

}  // namespace

std::vector<numeric> sample_points(const Atomic& a) {
  DigitsGuard g(kDigits);
  const numeric s2 = constant(sqrt(ex(2))), off = constant(Pi / 100);
  std::vector<numeric> c;
  for (int k = -40; k <= 40; ++k) c.push_back(k * s2 / 3 + off);
  for (int m : {30, 300, 3000}) {
    c.push_back(m * s2 + off);
    c.push_back(-m * s2 + off);
  }
  for (int j = 1; j <= 8; j += 1) {
    const numeric d = s2 * pow10(-j);
    if (a.domain_lo.finite()) c.push_back(constant(a.domain_lo.value) + d);
    if (a.domain_hi.finite()) c.push_back(constant(a.domain_hi.value) - d);
    if (j % 2 == 0)
      for (const ex& s : a.singular) {
        c.push_back(constant(s) + d);
        c.push_back(constant(s) - d);
      }
  }
  std::vector<numeric> out;
  for (const numeric& t : c)
    if (in_domain(a, t) && singular_distance(a, t) > pow10(-12) * (1 + abs(t))) out.push_back(t);
  std::sort(out.begin(), out.end(), [](const numeric& u, const numeric& v) { return u < v; });
  return out;
}

void check_antiderivative(const Atomic& a, const std::string& field, const ex& F, const ex& f) {
  const symbol& x = var_x();
  {  // symbolic: x real, so that abs and conjugate simplify
    const realsymbol xr("x");
    try {
      const ex d = F.subs(x == xr).diff(xr) - f.subs(x == xr);
      if (d.normal().is_zero() || d.expand().normal().is_zero()) return;
    } catch (const std::exception&) {
      // undecided: fall through to the numerical check
    }
  }
  DigitsGuard g(kDigits);
  const ex dF = F.diff(x);
  const numeric tol = pow10(-25);
  int used = 0;
  for (const numeric& t : sample_points(a)) {
    const auto fv = value_at(f, t);
    if (!fv) continue;
    const auto dv = value_at(dF, t);
    if (!dv)
      fail(a, field,
           "its derivative is not real (or not defined) at x = " + show(t) + ", where the integrand is " +
               show(*fv));
    ++used;
    if (abs(*dv - *fv) > tol * (1 + abs(*fv)))
      fail(a, field,
           "d/dx of the given antiderivative differs from the integrand at x = " + show(t) + ": " +
               show(*dv) + " vs " + show(*fv));
  }
  if (used < 3) fail(a, field, "fewer than 3 sample points to check the antiderivative in the domain");
}

void check_continuity(const Atomic& a, const std::string& field, const ex& F) {
  DigitsGuard g(kDigits);
  const std::vector<numeric> pts = sample_points(a);
  for (const numeric& t : pts)
    if (!value_at(F, t))
      fail(a, field,
           "not a real number at x = " + show(t) + " (inside the domain, away from the singular points)");
  for (const auto& [c, u] : break_points(a, F, pts)) {
    const numeric eps = pow10(-15) * (1 + abs(c));
    const auto l = value_at(F, c - eps), r = value_at(F, c + eps);
    const std::string at = " at x = " + show_point(c) + " (where " + text(u) + " changes sign)";
    if (!l || !r)
      fail(a, field,
           "not finite and real on both sides" + at + "; a singularity of f there belongs in 'singular'");
    if (abs(*r - *l) > pow10(-9) * (1 + abs(*l) + abs(*r)))
      fail(a, field,
           "jumps by " + show(*r - *l) + at +
               ": an antiderivative must be continuous between singular points (the box and tent take "
               "differences of it across the kernel's support)");
  }
}

void check_smooth(Atomic& a) {
  DigitsGuard g(kDigits);
  for (const auto& [c, u] : break_points(a, a.f, sample_points(a)))
    fail(a, "f",
         "not smooth at x = " + show_point(c) + " (" + text(u) +
             " changes sign there): the antiderivative class evaluates a Taylor series of f, so f must be "
             "analytic between the points listed in 'singular'; list it there, or write f as a piecewise "
             "atomic");
  if (a.f.has(abs(wild(0)))) a.f = a.f.subs(abs(wild(0)) == wild(0) * sgn(wild(0)));
}

void check_flat(const Atomic& a) {
  if (!a.flat) return;
  DigitsGuard g(kDigits);
  const numeric ulp = pow10(-16) * 2;  // 2e-16 ~ 2^-52
  for (const double m : {1.0, 1.5, 4.0, 100.0}) {
    for (int side : {-1, 1}) {
      const numeric t = numeric(side) * numeric(a.flat->beyond) * numeric(m);
      const numeric want = numeric(side < 0 ? a.flat->left : a.flat->right);
      if (!in_domain(a, t)) continue;
      const auto v = value_at(a.f, t);
      if (!v || abs(*v - want) > ulp * (1 + abs(want)))
        fail(a, "flat",
             "f(" + show(t) + ") = " + (v ? show(*v) : std::string("undefined")) + " is not " +
                 (side < 0 ? "left" : "right") + " = " + show(want) + " to within 2e-16");
    }
  }
}

void check_range(const Atomic& a) {
  DigitsGuard g(kDigits);
  if (a.cls == AtomicClass::Combination) return;  // its range follows from the atomics it combines
  if (a.cls == AtomicClass::Piecewise || a.cls == AtomicClass::Periodic) {
    for (size_t i = 0; i < a.pieces.size(); ++i) {
      if (a.pieces[i].f.is_polynomial(var_x()))
        check_polynomial_range(a, a.pieces[i], i);
      else
        check_sampled_piece_range(a, a.pieces[i], i);  // exp-polynomial pieces
    }
    return;
  }
  // Entire and antiderivative: f at the sample points and at the zeros of f' between them.
  const std::vector<numeric> pts = sample_points(a);
  std::vector<numeric> far = pts;  // and far out, where an unbounded f leaves a finite range
  for (int e : {6, 12})
    for (int side : {-1, 1}) {
      const numeric t = side * constant(sqrt(ex(2))) * pow10(e);
      if (in_domain(a, t)) far.push_back(t);
    }
  for (const numeric& t : far)
    if (const auto v = value_at(a.f, t)) check_value(a, {0, *v, "at x = " + show(t)});
  for (const numeric& t : sign_changes(a.f.diff(var_x()), pts))
    if (const auto v = value_at(a.f, t)) check_value(a, {0, *v, "at its critical point x = " + show(t)});
}

}  // namespace bl::sym
