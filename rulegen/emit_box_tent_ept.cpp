// Box and tent of exp-polynomial terms as straight-line code; see emit_box_tent_ept.hpp.
//
// A term is f(t) = e^{a s} q(s), s = t - ref, on a half-line or the whole line. A term with a > 0 is
// reflected (t -> -t, x -> u = -x: a -> -a, ref -> -ref, q(s) -> q(-s), (-inf, E) -> [-E, inf)), as
// box and tent are symmetric, so every printed term has a = -b < 0 and lives on [E, inf) or the
// whole line. Each piece of the kernel's support is integrated from its left end s0 (where e^{a s}
// is largest), v = distance from there, with q's Taylor coefficients g_k about s0 (exact constants
// where s0 is the break E):
//   box:  e^{a s0} lam   sum_k g_k len^k j_k(y),                       lam = len/(2h)
//   tent: e^{a s0} lam   sum_k g_k len^k (gam j_k + sw lam j_{k+1}),   lam = len/w,
// len the piece's length, y = b len, gam = G/w the tent weight at s0 (times w), sw = -1 where the
// weight falls along v (right half), +1 where it rises (left half), and
//   j_k(y) = int_0^1 u^k e^{-y u} du in (0, 1/(k+1)].
// Everything is O(1) (no len^k/len^k or 1/h^2 that leave float's range at tiny or huge sigma).
// j_K (K the top degree) is the positive series e^{-y} sum_n y^n K!/(K+n+1)! for y < y0 and
// K!/y^{K+1} (1 - e^{-y} sum_{j<=K} y^j/j!) above, whose bracket P(K+1, y) >= p_min there: it
// loses at most (K+2) eps/p_min relative; y0 and the series length are chosen here per precision
// (float: p_min = 1/4, error < 4 (K+2) eps ~ 1.5e-6 relative; double: p_min = 1e-3, < 2e-12; series
// truncation below 3e-8 / 1e-16 relative; C++ takes a lone j_0 as -expm1(-y)/y, a few eps). Lower j by
// j_{k-1} = (y j_k + e^{-y})/k: positive terms, a few eps per step. The tent's gam j_k - lam j_{k+1} (gam >=
// lam) loses at most a factor k + 2. Errors are relative to the L1 scale int e^{a s} sum_k |g_k| v^k of the
// term; the exponent a s0 carries the rounding of s0 (eps |a s0|, as the plain e^{a x} does). Cost: one exp
// per piece of the support cut by the break, two for a kernel wholly on one side (the tent's right half
// reuses e^{-b w}). |x| or sigma beyond 1e4, NaN/inf x and multiprecision T: the generic runtime
// (box_ept/tent_ept, which widens float to double there).
#include "emit_box_tent_ept.hpp"

#include <cmath>
#include <functional>
#include <stdexcept>

namespace bl::rulegen {
namespace {

using GiNaC::ex;
using GiNaC::numeric;

constexpr int kMaxDeg = 3;  // K = deg + 1 <= 4: y^{K+1} stays in float's range for y <= 1e5

// A term with a = -b < 0, on [E, inf) (half) or the whole line, in the variable named u.
struct Term {
  bool reflect = false;
  bool half = false;
  numeric b;
  ex E, ref;
  std::vector<ex> c;
  int deg = -1;
};

Term normalise(const sym::ExpTermSpec& t) {
  Term r;
  r.reflect = t.a > 0;
  r.b = r.reflect ? numeric(t.a) : numeric(-t.a);
  r.half = t.lo.finite() || t.hi.finite();
  if (r.half) r.E = r.reflect ? ex(-t.hi.value) : t.lo.value;
  r.ref = r.reflect ? ex(-t.ref) : t.ref;
  for (size_t k = 0; k < t.c.size(); ++k) {
    r.c.push_back(r.reflect && (k % 2) ? ex(-t.c[k]) : t.c[k]);
    if (!t.c[k].is_zero()) r.deg = static_cast<int>(k);
  }
  return r;
}

bool qualifies(const sym::ExpTermSpec& t) {
  if (t.lo.finite() && t.hi.finite()) return false;
  if (t.a.is_zero()) return false;
  if (t.lo.finite() && !(t.a < 0)) return false;  // [E, inf) must decay towards +inf
  if (t.hi.finite() && !(t.a > 0)) return false;  // (-inf, E) towards -inf
  for (const auto& v : t.c)
    if (!GiNaC::is_a<numeric>(v)) return false;
  if (!GiNaC::is_a<numeric>(t.ref.evalf())) return false;
  const Term n = normalise(t);
  return n.deg >= 0 && n.deg <= kMaxDeg;
}

// P(K+1, y) = 1 - e^{-y} sum_{j<=K} y^j/j!, without cancellation below y = 1.
long double lower_gamma_p(int K, long double y) {
  if (y < 1) {
    long double term = std::exp(-y), sum = 0;
    for (int n = 1; n <= K; ++n) term *= y / n;
    for (int n = K + 1; n < K + 60; ++n) {
      term *= y / n;
      sum += term;
    }
    return sum;
  }
  long double term = 1, sum = 1;
  for (int j = 1; j <= K; ++j) sum += (term *= y / j);
  return 1 - std::exp(-y) * sum;
}

// Where j_K switches from the series to the closed form, and the series' coefficients.
struct JPlan {
  double y0;
  std::vector<double> series;  // K!/(K+n+1)!, n = 0..N
};

JPlan plan_j(int K, double p_min, double tol) {
  double y0 = 1e-4;
  while (lower_gamma_p(K, y0) < p_min) y0 *= 1.01;
  JPlan p{y0, {}};
  long double c = 1.0L / (K + 1);  // c_0
  const long double c0 = c;
  for (int n = 0; n < 200; ++n) {
    p.series.push_back(static_cast<double>(c));
    const long double next = c / (K + n + 2);  // c_{n+1}
    const long double r = y0 / (K + n + 3);
    if (next * std::pow(static_cast<long double>(y0), n + 1) / (1 - r) <= tol * c0) break;
    c = next;
  }
  return p;
}

std::string horner(const std::vector<std::string>& c, const std::string& v, const Syntax& s) {
  int top = static_cast<int>(c.size()) - 1;
  while (top >= 0 && c[top].empty()) --top;
  if (top < 0) return s.dbl(0);
  std::string r = c[top];
  for (int k = top - 1; k >= 0; --k)
    r = c[k].empty() ? "(" + r + ") * " + v : c[k] + " + " + v + " * (" + r + ")";
  return r;
}

// c * m as text ("" for c = 0, m alone for c = 1).
std::string times(const ex& c, const std::string& m, const Syntax& s) {
  if (c.is_zero()) return "";
  if ((c - 1).is_zero()) return m;
  return s.num(c) + " * " + m;
}

// Taylor coefficient g_k of q about s0 = v (exact).
ex g_const(const Term& t, int k, const ex& v) {
  ex g = 0;
  for (int j = k; j <= t.deg; ++j)
    g += GiNaC::binomial(numeric(j), numeric(k)) * t.c[j] * (j == k ? ex(1) : GiNaC::pow(v, j - k));
  return g.expand();
}

// Taylor coefficient g_k of q about the local s0 (a polynomial in it), parenthesised.
std::string g_poly(const Term& t, int k, const std::string& s0, const Syntax& s) {
  std::vector<std::string> cs;
  for (int j = k; j <= t.deg; ++j) {
    const ex v = (GiNaC::binomial(numeric(j), numeric(k)) * t.c[j]).expand();
    cs.push_back(v.is_zero() ? "" : s.num(v));
  }
  const std::string h = horner(cs, s0, s);
  return h == s.dbl(0) ? "" : "(" + h + ")";
}

// Declares j0..jK (prefix p) from y and ey = e^{-y}.
std::string jset(const std::string& p, int K, const std::string& y, const std::string& ey, const Syntax& s,
                 const std::string& in) {
  const JPlan pf = plan_j(K, 0.25, 3e-8), pd = plan_j(K, 1e-3, 1e-16);
  auto series = [&](const JPlan& pl) {
    std::vector<std::string> cs;
    for (double v : pl.series) cs.push_back(s.dbl(v));
    return ey + " * (" + horner(cs, y, s) + ")";
  };
  double fact = 1;
  for (int k = 2; k <= K; ++k) fact *= k;
  std::vector<std::string> ek;
  double inv_fact = 1;
  for (int j = 0; j <= K; ++j) {
    if (j > 0) inv_fact /= j;
    ek.push_back(s.dbl(inv_fact));
  }
  std::string yk = y;
  for (int k = 0; k < K; ++k) yk += " * " + y;
  if (K == 0 && s.cpp())
    // One moment: expm1 has no cancellation at any y (GLSL has no expm1: the series and 1 - e^{-y}).
    return in + "const T " + p + "j0 = " + y + " > T(0) ? -expm1(-" + y + ") / " + y + " : T(1);\n";
  const std::string top = p + "j" + std::to_string(K);
  std::string out = in + s.T() + " " + top + ";\n";
  const std::string closed = top + " = " + s.dbl(fact) + " * (" + s.dbl(1) + " - " + ey + " * (" +
                             horner(ek, y, s) + ")) / (" + yk + ");\n";
  if (s.cpp()) {
    out += in + "if (" + y + " < (sizeof(T) < sizeof(double) ? " + s.dbl(pf.y0) + " : " + s.dbl(pd.y0) +
           ")) {\n";
    out += in + "  if constexpr (sizeof(T) < sizeof(double))\n" + in + "    " + top + " = " + series(pf) +
           ";\n" + in + "  else\n" + in + "    " + top + " = " + series(pd) + ";\n";
  } else {
    out += in + "if (" + y + " < " + s.dbl(pf.y0) + ") {\n" + in + "  " + top + " = " + series(pf) + ";\n";
  }
  out += in + "} else {\n" + in + "  " + closed + in + "}\n";
  for (int k = K; k >= 1; --k) {
    const std::string v = "(" + y + " * " + p + "j" + std::to_string(k) + " + " + ey + ")";
    out += in + (s.cpp() ? "const " : "") + s.T() + " " + p + "j" + std::to_string(k - 1) + " = " +
           (k == 1 ? v : v + " * " + s.dbl(1.0 / k)) + ";\n";
  }
  return out;
}

// sum_k g_k len^k m_k with m_k from mk(k); g constant (about v) or a polynomial in the local s0.
std::string side_sum(const Term& t, const std::function<std::string(int)>& mk, const std::string& len,
                     const ex* v, const std::string& s0, const Syntax& s) {
  std::vector<std::string> terms;
  for (int k = 0; k <= t.deg; ++k) {
    if (v) {
      terms.push_back(times(g_const(t, k, *v), mk(k), s));
    } else {
      const std::string g = g_poly(t, k, s0, s);
      terms.push_back(g.empty() ? "" : g + " * " + mk(k));
    }
  }
  return "(" + horner(terms, len, s) + ")";
}

std::string jn(int k) {
  return "j" + std::to_string(k);
}

// acc += e^{pre} * value without overflowing in e^{pre} alone where the product is finite (only
// whole-line terms can have pre > 30).
std::string add_scaled(const std::string& pre, const std::string& value, bool can_be_large, const Syntax& s,
                       const std::string& in) {
  if (!can_be_large) return in + "acc += exp(" + pre + ") * " + value + ";\n";
  return in + "if (" + pre + " < " + s.dbl(30) + ") {\n" + in + "  acc += exp(" + pre + ") * " + value +
         ";\n" + in + "} else {\n" + in + "  " +
         s.decl("eh", "exp(" + s.dbl(0.5) + " * " + pre + ")").substr(2) + in + "  acc += eh * (eh * " +
         value + ");\n" + in + "}\n";
}

// The kernel wholly on the term's support: integrated from its left end u - hw.
std::string whole_kernel(const Term& t, bool tent, const Syntax& s, const std::string& in) {
  const std::string B = s.num(t.b), A = s.num(-t.b);
  const std::string ref = t.ref.is_zero() ? "" : " - (" + s.ex(t.ref) + ")";
  const std::string hw = tent ? "w" : "h";
  // Half-lines with ref = E: e^{a s0} <= 1; else the exponent may be large.
  const bool large = !t.half || !(t.E - t.ref).is_zero();
  std::string out;
  if (!tent) {
    out += in + s.decl("s0", "u" + ref + " - h").substr(2);
    out += in + s.decl("len", s.dbl(2) + " * h").substr(2);
    out += in + s.decl("y", B + " * len").substr(2);
    if (t.deg > 0 || !s.cpp()) out += in + s.decl("ey", "exp(-y)").substr(2);
    out += jset("", t.deg, "y", "ey", s, in);
    out += in + s.decl("sum", side_sum(t, jn, "len", nullptr, "s0", s)).substr(2);
    return out + add_scaled(A + " * s0", "sum", large, s, in);
  }
  // Left half [u - w, u]: weight v/w (gam = 0, sw = +1); right half [u, u + w]: 1 - v/w, and
  // e^{a s} at u is e^{a s} at u - w times e^{-b w}: one exp pair and one j set for both.
  out += in + s.decl("sl", "u" + ref + " - w").substr(2);
  if (t.deg >= 1) out += in + s.decl("sr", "u" + ref).substr(2);
  out += in + s.decl("y", B + " * w").substr(2);
  out += in + s.decl("ey", "exp(-y)").substr(2);
  out += jset("", t.deg + 1, "y", "ey", s, in);
  const std::string left = side_sum(
      t, [](int k) { return jn(k + 1); }, "w", nullptr, "sl", s);
  const std::string right = side_sum(
      t, [](int k) { return "(" + jn(k) + " - " + jn(k + 1) + ")"; }, "w", nullptr, "sr", s);
  out += in + s.decl("sum", left + " + ey * " + right).substr(2);
  return out + add_scaled(A + " * sl", "sum", large, s, in);
}

std::string half_term(const Term& t, bool tent, const Syntax& s) {
  const std::string B = s.num(t.b);
  const std::string in = "    ";
  const ex Eoff = (t.E - t.ref).expand();         // s at the break
  const ex CE = GiNaC::exp(-t.b * Eoff).evalf();  // e^{a s} at the break
  const bool unit = Eoff.is_zero();
  const std::string ce = unit ? "" : s.num(CE) + " * ";
  const std::string E = "(" + s.ex(t.E) + ")";
  std::string out = "  " + s.decl("el", E + " - u");  // the break's offset from the centre
  const std::string hw = tent ? "w" : "h";
  out += "  if (el < " + hw + ") {\n";
  if (!tent) {
    // The break inside the kernel: [E, u + h] from E.
    out += "    if (el > -h) {\n";
    const std::string in2 = "      ";
    out += in2 + s.decl("len", "h - el").substr(2);
    out += in2 + s.decl("y", B + " * len").substr(2);
    if (t.deg > 0 || !s.cpp()) out += in2 + s.decl("ey", "exp(-y)").substr(2);
    out += jset("", t.deg, "y", "ey", s, in2);
    out += in2 + "acc += " + ce + "(len / (" + s.dbl(2) + " * h)) * " + side_sum(t, jn, "len", &Eoff, "", s) +
           ";\n";
    out += "    } else {\n";
    out += whole_kernel(t, false, s, in2);
    return out + "    }\n  }\n";
  }
  const std::string in2 = "      ";
  // A: only the right half meets [E, inf): [E, u + w] from E, weight (w - el - v)/w^2: gam = lam.
  out += "    if (el > " + s.dbl(0) + ") {\n";
  out += in2 + s.decl("len", "w - el").substr(2);
  out += in2 + s.decl("lam", "len / w").substr(2);
  out += in2 + s.decl("y", B + " * len").substr(2);
  out += in2 + s.decl("ey", "exp(-y)").substr(2);
  out += jset("", t.deg + 1, "y", "ey", s, in2);
  out += in2 + "acc += " + ce + "lam * lam * " +
         side_sum(
             t, [](int k) { return "(" + jn(k) + " - " + jn(k + 1) + ")"; }, "len", &Eoff, "", s) +
         ";\n";
  // B: the break in the left half: [E, u] from E (weight rising from gam = 1 - lam), and the
  // whole right half [u, u + w] from u, where e^{a s} is e^{a s} at E times e^{-b (u - E)}.
  out += "    } else if (el > -w) {\n";
  out += in2 + s.decl("lenl", "-el").substr(2);
  out += in2 + s.decl("laml", "lenl / w").substr(2);
  out += in2 + s.decl("yl", B + " * lenl").substr(2);
  out += in2 + s.decl("eyl", "exp(-yl)").substr(2);
  out += jset("l", t.deg + 1, "yl", "eyl", s, in2);
  out += in2 + s.decl("yr", B + " * w").substr(2);
  out += in2 + s.decl("eyr", "exp(-yr)").substr(2);
  out += jset("r", t.deg + 1, "yr", "eyr", s, in2);
  out += in2 + s.decl("gaml", "(w + el) / w").substr(2);
  const std::string ref = t.ref.is_zero() ? "" : " - (" + s.ex(t.ref) + ")";
  if (t.deg >= 1) out += in2 + s.decl("sr", "u" + ref).substr(2);
  const std::string left = side_sum(
      t,
      [](int k) { return "(gaml * lj" + std::to_string(k) + " + laml * lj" + std::to_string(k + 1) + ")"; },
      "lenl", &Eoff, "", s);
  const std::string right = side_sum(
      t, [](int k) { return "(rj" + std::to_string(k) + " - rj" + std::to_string(k + 1) + ")"; }, "w",
      nullptr, "sr", s);
  out += in2 + "acc += " + ce + "(laml * " + left + " + eyl * " + right + ");\n";
  // C: the whole kernel on [E, inf).
  out += "    } else {\n";
  out += whole_kernel(t, true, s, in2);
  return out + "    }\n  }\n";
}

std::string term_code(const Term& t, bool tent, const Syntax& s) {
  std::string out = "  " + s.decl("u", t.reflect ? "-x" : "x");
  if (t.half) return out + half_term(t, tent, s);
  return out + whole_kernel(t, tent, s, "  ");
}

}  // namespace

bool box_tent_ept_straight(const sym::Derived& d) {
  if (d.kernel != sym::Kernel::Box && d.kernel != sym::Kernel::Tent) return false;
  if (d.eterms.empty()) return false;
  for (const auto& t : d.eterms)
    if (!qualifies(t)) return false;
  return true;
}

std::string body_box_tent_ept(const sym::Derived& d, const Syntax& s, const std::string& table,
                              const std::string& pieces_arg) {
  const bool tent = d.kernel == sym::Kernel::Tent;
  const std::string generic = s.helper(tent ? "tent_ept" : "box_ept") + "(x, sigma, " + pieces_arg + ")";
  std::string out = table;
  out += "  if (!(sigma >= " + s.dbl(0) + ")) return " + s.nan() + ";  // sigma < 0 or NaN\n";
  out += "  if (sigma == " + s.dbl(0) + ") return " + s.helper("ept_eval") + "(x, " + pieces_arg + ");\n";
  // Multiprecision T: the generic runtime, and the straight-line code not even instantiated.
  if (s.cpp()) out += "  if constexpr (detail::kWide<T>) {\n    return " + generic + ";\n  } else {\n";
  out += "  if (!(abs(x) <= " + s.dbl(1e4) + ") || sigma > " + s.dbl(1e4) + ") return " + generic + ";\n";
  const std::string k = tent ? (s.cpp() ? "detail::k_sqrt6<T>()" : "BL_SQRT6")
                             : (s.cpp() ? "detail::k_sqrt3<T>()" : "BL_SQRT3");
  out += s.decl(tent ? "w" : "h", k + " * sigma");
  out += "  " + s.T() + " acc = " + s.dbl(0) + ";\n";
  for (size_t i = 0; i < d.eterms.size(); ++i) {
    const Term t = normalise(d.eterms[i]);
    std::string code = term_code(t, tent, s);
    for (size_t at = 0; (at = code.find('\n', at)) != std::string::npos && at + 1 < code.size(); at += 3)
      code.insert(at + 1, "  ");
    out += "  {  // term " + std::to_string(i) + (t.reflect ? " (reflected: u = -x)" : "") + "\n  " + code +
           "  }\n";
  }
  return out + "  return acc;\n" + (s.cpp() ? "  }\n" : "");
}

}  // namespace bl::rulegen
