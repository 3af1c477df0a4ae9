// See emit_stat_pairs.hpp.
#include "emit_stat_pairs.hpp"

#include <cmath>

#include "emit_gauss_periodic.hpp"
#include "emit_syntax.hpp"

namespace bl::rulegen {
namespace {
using namespace GiNaC;

const Derived* find_entry(const std::vector<Derived>& ds, const std::string& atomic, bool squared) {
  for (const Derived& e : ds)
    if (e.kernel == sym::Kernel::Gaussian && e.rule == "convolution" && e.atomic_name == atomic &&
        e.squared == squared)
      return &e;
  return nullptr;
}

// a + b x as (a, b) when poly is a polynomial of degree <= 1 in x with number coefficients.
bool linear(const ex& poly, numeric& a, numeric& b) {
  const ex p = poly.expand();
  if (!p.is_polynomial(sym::var_x()) || p.degree(sym::var_x()) > 1) return false;
  const ex a0 = p.coeff(sym::var_x(), 0), b0 = p.coeff(sym::var_x(), 1);
  if (!is_a<numeric>(a0) || !is_a<numeric>(b0)) return false;
  a = ex_to<numeric>(a0), b = ex_to<numeric>(b0);
  return true;
}

std::string lit(const numeric& v) {
  return Syntax{Lang::Cpp}.dbl(v.to_double());
}

}  // namespace

std::string StatPair::name() const {
  return "gaussian_" + f->atomic_name + "_stat";
}

std::vector<StatPair> stat_pairs(const std::vector<Derived>& ds) {
  std::vector<StatPair> out;
  for (const Derived& d : ds) {
    if (d.kernel != sym::Kernel::Gaussian || d.rule != "convolution" || d.squared || !d.atomic) continue;
    StatPair p;
    p.f = &d;
    p.f2 = find_entry(ds, d.atomic_name, true);
    if (!p.f2) continue;
    std::string atomic = d.atomic_name;
    if (d.body == sym::Body::Combination) {
      // f = poly + c A(s x): one smoothed term, no first moment, no square.
      if (d.terms.size() != 1) continue;
      const sym::CombinationTerm& t = d.terms[0];
      if (t.kind != sym::CombinationTerm::Kind::Smoothed || t.xpow != 0 || t.squared) continue;
      if (!linear(d.poly, p.a, p.b)) continue;
      p.c = t.coeff, p.s = t.arg_sign, atomic = t.atomic;
    } else if (d.body != sym::Body::PeriodicTable) {
      continue;
    }
    p.A = fusable_pair(atomic, &ds);
    if (!p.A.a || !GiNaC::is_a<GiNaC::numeric>(p.A.a->period) || periodic_spec(*p.A.a).lo.empty()) continue;
    out.push_back(p);
  }
  return out;
}

std::string stat_pair_definition(const StatPair& p, Lang lang) {
  const Syntax s{lang};
  const Derived& A = *p.A.a;
  const Derived& A2 = *p.A.a2;
  const ex sig = sym::var_sigma();
  const numeric T = ex_to<numeric>(A.period);
  std::vector<numeric> g = A.pieces[0].c;
  g.resize(2, 0);
  const numeric J = -g[1] * T;                            // g(0) - g(T)
  const numeric c2 = p.c * p.c, w = 2 * p.b * p.c * p.s;  // w: the weight of sigma^2 (g1 + J theta)

  GaussPeriodicSpec sp = periodic_spec(A);  // channel 0: A~(y)
  sp.y = "y";
  GaussPeriodicSpec ch1 = periodic_spec(A2);  // channel 1, scaled
  for (auto& q : ch1.c)
    for (auto& k : q) k = (c2 * k).expand();
  ch1.a0 = (c2 * A2.a0 + p.b * p.b * sig * sig + w * sig * sig * (g[1] + J / T)).expand();
  ch1.ak = (c2 * A2.ak + w * sig * sig * 2 * J / T).expand();
  ch1.bk = (c2 * A2.bk).expand();
  // sigma^2 in the theta term is bounded by 4 T^2 in the plan, as in fused_periodic.
  ch1.coef_bound = c2.to_double() * A2.coef_bound +
                   std::fabs(w.to_double()) * 2 * std::fabs(J.to_double()) * 4 * T.to_double();
  ch1.delta = w * J * sig;  // sum_m phi(t_m) (w J sigma): w J sigma^2 theta
  ch1.break_extra = (w * g[1] * sig * sig + p.b * p.b * sig * sig).expand();
  sp.more = {ch1};
  // E f = a + b x + c @0 (kept inside f's range when it has one), Var f = @1 - c^2 @0^2 (>= 0).
  std::string mean = "@0";
  if (!p.c.is_equal(1)) mean = lit(p.c) + " * " + mean;
  if (!p.b.is_zero()) mean = (p.b.is_equal(1) ? std::string("x") : lit(p.b) + " * x") + " + " + mean;
  if (!p.a.is_zero()) mean = lit(p.a) + " + " + mean;
  const sym::Atomic& fa = *p.f->atomic;
  if (fa.range_hi.finite() && is_a<numeric>(fa.range_hi.value))
    mean = "detail::min2(" + mean + ", " + lit(ex_to<numeric>(fa.range_hi.value)) + ")";
  if (fa.range_lo.finite() && is_a<numeric>(fa.range_lo.value))
    mean = "detail::at_least(" + mean + ", " + lit(ex_to<numeric>(fa.range_lo.value)) + ")";
  const std::string var = "@1 - " + (c2.is_equal(1) ? std::string() : lit(c2) + " * ") + "@0 * @0";
  sp.finish = "detail::make_stat(" + mean + ", detail::at_least(" + var + ", T(0.0)))";

  const std::string fast = lang == Lang::Cpp ? gauss_periodic_fast_cpp(sp) : gauss_periodic_fast_glsl(sp);
  if (fast.empty())
    throw std::logic_error("rulegen: the stat entry of " + p.f->atomic_name + " has no straight-line plan");
  const std::string f = p.f->atomic_name;
  std::string o;
  // C++: pixel-sized sigma by the nearest break alone (gauss_periodic_hot), the full pass out of line.
  // (Several channels: no path of it is claimed in range, so no clamp is passed.)
  bool in_range = false;
  const std::string hot =
      lang == Lang::Cpp ? gauss_periodic_hot(sp, p.name() + "_general", "", &in_range) : "";
  if (lang == Lang::Cpp) {
    o += "// {E f(X), Var f(X)}, X ~ N(x, sigma^2), f = " + f +
         ", from one pass (rulegen/emit_stat_pairs.hpp); other types and\n"
         "// sigma below the fast regimes read the two entries.\n";
    o += "template <class T>\n" + std::string(hot.empty() ? "" : "BL_NOINLINE ") + "stat<T> " + p.name() +
         (hot.empty() ? "" : "_general") + "(T x, T sigma) {\n  BL_MATH_USING\n";
    o += "  if (!(sigma >= T(0.0))) return detail::make_stat(detail::nan<T>(), detail::nan<T>());\n";
  } else {
    o += "vec2 bl_" + p.name() + "(float x, float sigma) {\n";
    o += "  if (!(sigma >= 0.0)) return vec2(bl_nan(), bl_nan());\n";
  }
  o += s.decl("y", p.s < 0 ? "-x" : "x");
  o += s.decl("period", s.ex(A.period));
  o += fast;
  const std::string m = lang == Lang::Cpp ? impl_name(*p.f) + "<T>" : p.f->glsl_name();
  const std::string m2 = lang == Lang::Cpp ? impl_name(*p.f2) + "<T>" : p.f2->glsl_name();
  o += s.decl("m", m + "(x, sigma)");
  o += s.decl("m2", m2 + "(x, sigma)");
  if (lang == Lang::Cpp) {
    o += "  return detail::make_stat(m, detail::at_least(m2 - m * m, T(0.0)));\n}\n\n";
    if (!hot.empty())
      o += "// The same, pixel-sized sigma inline.\ntemplate <class T>\nstat<T> " + p.name() +
           "(T x, T sigma) {\n  BL_MATH_USING\n" + s.decl("y", p.s < 0 ? "-x" : "x") + hot + "}\n\n";
  } else {
    o += "  return vec2(m, max(m2 - m * m, 0.0));\n}\n\n";
  }
  return o;
}

}  // namespace bl::rulegen
