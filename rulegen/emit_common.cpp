#include "emit_common.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

#include "emit_box_tent_breaks.hpp"
#include "emit_box_tent_ept.hpp"
#include "emit_gauss_periodic.hpp"
#include "emit_syntax.hpp"
#include "exp_poly.hpp"
#include "functions.hpp"

namespace bl::rulegen {
using namespace GiNaC;
using sym::Body;
using sym::Bound;
using sym::Kernel;
using sym::PolyPiece;

std::string impl_name(const Derived& d) {
  return std::string(sym::to_string(d.kernel)) + "_" + d.fn_suffix();
}
std::string plain_impl_name(const std::string& atomic) {
  return "plain_" + atomic;
}

namespace {

// A piece's 8 coefficients, lowest first, as a comma-separated list.
std::string piece_coeffs(const Syntax& s, const PolyPiece& p) {
  std::string c;
  for (int k = 0; k < 8; ++k) {
    const GiNaC::ex v = k < static_cast<int>(p.c.size()) ? GiNaC::ex(p.c[k]) : GiNaC::ex(0);
    c += (k ? ", " : "") + s.num(v);
  }
  return c;
}

std::string piece_table(const Syntax& s, const std::string& name, const std::vector<PolyPiece>& ps) {
  auto coeffs = [&](const PolyPiece& p) { return piece_coeffs(s, p); };
  if (ps.size() > 4) throw std::runtime_error("more than 4 pieces: the GLSL runtime takes at most 4");
  std::string out;
  if (s.cpp()) {
    // static: the table is a constant in the binary for float/double (built once, thread-safely,
    // for wider types), not 10 T per piece zeroed and stored on the stack at every call (which GCC
    // did with `rep stos` in double, a fixed start-up cost of tens of cycles per call).
    out = "  static const detail::Piece<T> " + name + "[" + std::to_string(ps.size()) + "] = {\n";
    for (const auto& p : ps)
      out += "      {" + s.bound(p.lo) + ", " + s.bound(p.hi) + ", {" + coeffs(p) + "}},\n";
    return out + "  };\n";
  }
  out = "  BlPiece " + name + "[4] = BlPiece[4](\n";
  for (size_t i = 0; i < 4; ++i) {
    if (i < ps.size())
      out += "      BlPiece(" + s.bound(ps[i].lo) + ", " + s.bound(ps[i].hi) + ", float[8](" + coeffs(ps[i]) +
             "))";
    else
      out += "      BlPiece(0.0, 0.0, float[8](0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0))";
    out += i < 3 ? ",\n" : ");\n";
  }
  return out;
}

// GLSL, sigma > 0 past the straight-line block: the generic per-piece sum of support.glsl
// (bl_gauss_pw / bl_box_pw / bl_tent_pw: the same cores, conditions and order) written out piece by
// piece with its bounds and coefficients as literals (Gaussian: bl_gauss_core_s, the core itself
// without arrays, stop 41). A piece table would be a local array, which
// NVIDIA's driver keeps in local memory and reserves per inlined call site whether or not it runs:
// fire_bumps' all-Gaussian program drew at 25 ns/px with the tables and 3.6 without
// (docs/gpu_timing.md, stop 28).
std::string pieces_written_out(const Syntax& s, Kernel kernel, const std::vector<PolyPiece>& ps) {
  std::string out = "  float wide = 0.0;\n";
  if (kernel == Kernel::Box) out += "  float hk = BL_SQRT3 * sigma;\n";
  if (kernel == Kernel::Tent) out += "  float hk = BL_SQRT6 * sigma;\n";
  for (const PolyPiece& p : ps) {
    bool zero = true;  // f = 0 on the piece: every core returns 0 there
    for (const auto& ck : p.c) zero = zero && ck.is_zero();
    if (zero) continue;
    const std::string lo = s.bound(p.lo), hi = s.bound(p.hi), coeffs = piece_coeffs(s, p);
    if (kernel == Kernel::Gaussian) {
      // Scalars, the degree a literal (support.glsl bl_gauss_core_s): no array even in the core.
      int degree = 0;
      for (int k = 0; k < static_cast<int>(p.c.size()); ++k)
        if (!p.c[k].is_zero()) degree = k;
      out += "  wide += bl_gauss_core_s(x, sigma, " + lo + " - x, " + hi + " - x, " + lo + ", " + hi + ", " +
             std::to_string(degree) + ", " + coeffs + ");\n";
      continue;
    }
    const std::string core = kernel == Kernel::Box ? "bl_box_core" : "bl_tent_core";
    out += "  {\n    float dl = " + lo + " - x, dh = " + hi + " - x;\n";
    out += "    if (dh > -hk && dl < hk) wide += " + core + "(x, hk, dl, dh, " + lo + ", " + hi +
           ", float[8](" + coeffs + "));\n  }\n";
  }
  return out + "  return wide;\n";
}

// A table of exp-polynomial terms (detail::ExpTerm / BlExpTerm); GLSL takes at most 8.
std::string eterm_table(const Syntax& s, const std::string& name, const std::vector<sym::ExpTermSpec>& ts) {
  if (ts.empty()) throw std::runtime_error("an exp-polynomial table without terms");
  if (ts.size() > 8)
    throw std::runtime_error("more than 8 exp-polynomial terms: the GLSL runtime takes at most 8");
  auto coeffs = [&](const sym::ExpTermSpec& t) {
    if (t.c.size() > 8) throw std::runtime_error("an exp-polynomial term of degree > 7");
    std::string c;
    for (size_t k = 0; k < 8; ++k) c += (k ? ", " : "") + s.num(k < t.c.size() ? t.c[k] : GiNaC::ex(0));
    return c;
  };
  auto fields = [&](const sym::ExpTermSpec& t) {
    return s.bound(t.lo) + ", " + s.bound(t.hi) + ", " + s.num(t.a) + ", " + s.ex(t.ref);
  };
  std::string out;
  if (s.cpp()) {
    out = "  static const detail::ExpTerm<T> " + name + "[" + std::to_string(ts.size()) + "] = {\n";
    for (const auto& t : ts) out += "      {" + fields(t) + ", {" + coeffs(t) + "}},\n";
    return out + "  };\n";
  }
  out = "  BlExpTerm " + name + "[8] = BlExpTerm[8](\n";
  for (size_t i = 0; i < 8; ++i) {
    if (i < ts.size())
      out += "      BlExpTerm(" + fields(ts[i]) + ", float[8](" + coeffs(ts[i]) + "))";
    else
      out += "      BlExpTerm(0.0, 0.0, 0.0, 0.0, float[8](0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0))";
    out += i < 7 ? ",\n" : ");\n";
  }
  return out;
}

// Arguments of a piecewise runtime call: C++ passes the array (size deduced), GLSL the count too.
std::string pieces_arg(const Syntax& s, const std::string& name, size_t n) {
  return s.cpp() ? name : std::to_string(n) + ", " + name;
}

std::string guard_sigma(const Syntax& s) {
  return "  if (!(sigma >= " + s.dbl(0) + ")) return " + s.nan() + ";  // sigma < 0 or NaN\n";
}

// The closed form of sin^2 / cos^2 under a kernel, written to share the transcendental calls of the
// same kernel's sin / cos entry, which a program calls with the same (x, sigma) for the node's mean:
// cos(2x) = 1 - 2 sin(x)^2 (sin^2) or 2 cos(x)^2 - 1 (cos^2), and the Gaussian's e^{-2 sigma^2} =
// (e^{-sigma^2/2})^4. The compiler then merges the calls (libm's sin, cos and exp are pure), so the
// node's variance costs a few multiplies instead of two more calls. Other entries: unchanged.
std::string shared_closed_text(const Derived& d, const Syntax& s) {
  const GiNaC::ex& x = sym::var_x();
  const GiNaC::ex& sig = sym::var_sigma();
  const bool trig = d.squared && (d.atomic_name == "sin" || d.atomic_name == "cos");
  if (!trig) return s.ex(d.closed);
  const GiNaC::ex c2 = d.atomic_name == "sin" ? 1 - 2 * pow(sin(x), 2) : 2 * pow(cos(x), 2) - 1;
  GiNaC::ex e = d.closed.subs(cos(2 * x) == c2);
  // GiNaC folds (e^a)^4 into e^{4a}: a placeholder symbol stands for e^{-2 sigma^2} until printed as
  // pow4(e^{-sigma^2/2}) (one exp, two squarings).
  const GiNaC::symbol e4("bl_e4_placeholder");
  if (d.kernel == Kernel::Gaussian) e = e.subs(exp(-2 * pow(sig, 2)) == e4);
  std::string text = s.ex(e);
  const std::string e4_text = s.helper("pow4") + "(" + s.ex(exp(-pow(sig, 2) / 2)) + ")";
  for (size_t at = text.find(e4.get_name()); at != std::string::npos; at = text.find(e4.get_name(), at))
    text.replace(at, e4.get_name().size(), e4_text);
  return text;
}

std::string body_closed(const Derived& d, const Syntax& s) {
  // An odd closed form is exactly 0 at x = 0, also where a power of sigma overflows (float x^9
  // moments at sigma = 1e6 would give 0 * inf).
  const GiNaC::ex& x = sym::var_x();
  const bool odd = (d.closed + d.closed.subs(x == -x)).expand().is_zero() && !d.closed.expand().is_zero();
  // sigma < 0 or NaN. sin, cos and their squares run the formula on a NaN sigma (their closed forms
  // propagate it: table_test) instead of returning early, so no branch separates an f^2 entry's
  // calls from its f entry's (see above) and the compiler can merge them; others return early (a
  // form may not read sigma: the Gaussian sign^2 is 1).
  const bool trig = d.atomic_name == "sin" || d.atomic_name == "cos";
  std::string out =
      trig ? "  sigma = sigma >= " + s.dbl(0) + " ? sigma : " + s.nan() + ";  // sigma < 0 or NaN\n"
           : guard_sigma(s);
  if (odd)
    out += "  if (x == " + s.dbl(0) + ") return " +
           (s.cpp() ? "sigma == sigma ? T(0) : sigma" : "isnan(sigma) ? sigma : 0.0") +
           ";  // odd in x (NaN for a bad sigma)\n";
  return out + "  return " + shared_closed_text(d, s) + ";\n";
}

std::string coef(const Syntax& s, const GiNaC::ex& v) {
  if (v.is_zero()) return "";
  if (!is_a<numeric>(v)) {
    const GiNaC::ex f = v.evalf();
    if (!is_a<numeric>(f)) throw std::runtime_error("a non-numeric piecewise coefficient: " + s.ex(v));
    return s.num(f);
  }
  return s.num(v);
}

// E q(v + sigma Z), q = sum c[k] t^k: sum_n v^n sum_m (2m-1)!! C(n+2m, 2m) c_{n+2m} s2^m, Horner in
// v and s2 = sigma^2 (a local the caller declares when q has degree >= 2).
std::string normal_mean(const Syntax& s, const std::vector<GiNaC::ex>& c, const std::string& v) {
  std::vector<std::string> cx;
  for (size_t m = 0; m < c.size(); ++m) {
    std::vector<std::string> cs;
    GiNaC::numeric df = 1;  // (2j-1)!!
    for (size_t j = 0; m + 2 * j < c.size(); ++j) {
      if (j > 0) df *= GiNaC::numeric(static_cast<long>(2 * j - 1));
      cs.push_back(coef(s, (df *
                            GiNaC::binomial(GiNaC::numeric(static_cast<long>(m + 2 * j)),
                                            GiNaC::numeric(static_cast<long>(2 * j))) *
                            c[m + 2 * j])
                               .expand()));
    }
    const std::string h = horner(s, cs, "s2");
    cx.push_back(h == s.dbl(0) ? "" : "(" + h + ")");
  }
  return horner(s, cx, v);
}

// Gaussian of a piecewise polynomial, specialised at emit time (the form of gauss_pw_breaks in
// support.hpp): with j the piece containing x,
//   E f(x+U) = E q_j(x+U) + sum over breaks b of s sum_k e_k (s sigma)^k J_k(|b - x|/sigma),
// s = +1 for b > x, -1 otherwise, e_k the Taylor coefficients about b of the jump q_right - q_left
// (exact here), J_k(t) = int_t^inf (z - t)^k phi(z) dz by J_1 = phi - t J_0, J_{k+1} = k J_{k-1} - t J_k
// from J_0 = Phic(t): one phi_Phic (one exp; float: a polynomial erfcx) per break within tail_cut sd.
// E q_j(x+U) = sum_n x^n sum_m (2m-1)!! C(n+2m, 2m) c_{n+2m} sigma^{2m}, Horner in x and sigma^2.
// Kernels wider than the narrowest bounded piece (the terms would cancel) go to the generic
// per-piece gauss_pw.
std::string body_gauss_pw(const Derived& d, const Syntax& s) {
  const auto& ps = d.pieces;
  const size_t n = ps.size();
  const std::string P = pieces_arg(s, "p", n);
  int maxdeg = 0;
  double wmin = HUGE_VAL;
  for (size_t i = 0; i < n; ++i) {
    for (size_t k = 0; k < ps[i].c.size(); ++k)
      if (!ps[i].c[k].is_zero()) maxdeg = std::max(maxdeg, static_cast<int>(k));
    if (i > 0 && i + 1 < n) wmin = std::min(wmin, ps[i].hi.to_double() - ps[i].lo.to_double());
  }
  // GLSL: the straight-line block first, as `if (sigma > 0 [&& sigma <= thr]) { ... return acc; }`,
  // then f itself at sigma = 0 and the generic sum written out per piece (no piece table: a GPU
  // keeps such an array in local memory, see pieces_written_out).
  const bool glsl = !s.cpp();
  std::string out;
  if (glsl) {
    out = guard_sigma(s);
    const double thr_f = maxdeg <= 3 ? wmin : 0.5 * wmin;
    out += "  if (sigma > " + s.dbl(0) + (n > 2 ? " && sigma <= " + s.dbl(thr_f) : std::string()) + ") {\n";
  } else {
    out = piece_table(s, "p", ps) + guard_sigma(s) + "  if (sigma == " + s.dbl(0) + ") return " +
          s.helper("pw_eval") + "(x, " + P + ");\n";
  }
  // Past degree 3 the terms reach ~400 max|f| at sigma = wmin (smoothstep^2): float keeps the form
  // up to wmin/2 and takes it in double up to wmin (GLSL: the generic gauss_pw there).
  if (n > 2 && !glsl) {
    const double thr_d = wmin, thr_f = maxdeg <= 3 ? wmin : 0.5 * wmin;
    out += "  if (!(sigma <= " + s.dbl(s.cpp() ? thr_d : thr_f) + ")) return " + s.helper("gauss_pw") +
           "(x, sigma, " + P + ");\n";
    if (s.cpp() && thr_f < thr_d)
      out += "  if constexpr (std::is_same<T, float>::value) {\n    if (sigma > " + s.dbl(thr_f) +
             ")\n      return T(" + impl_name(d) + (range_clamp(d, Lang::Cpp).empty() ? "" : "_raw") +
             "<double>(double(x), double(sigma)));\n  }\n";
  }
  if (maxdeg >= 2) out += s.decl("s2", "sigma * sigma");
  out += "  " + s.T() + " acc = " + s.dbl(0) + ";\n";
  for (size_t i = 0; i < n; ++i) {
    const std::vector<GiNaC::ex> c(ps[i].c.begin(), ps[i].c.end());
    const std::string e = "acc = " + normal_mean(s, c, "x") + ";\n";
    if (i + 1 < n)
      out += std::string(i ? "  else if" : "  if") + " (x < " + s.bound(ps[i].hi) + ") " + e;
    else
      out += std::string(n > 1 ? "  else " : "  ") + e;
  }
  const GiNaC::symbol u("u");
  for (size_t i = 0; i + 1 < n; ++i) {
    const GiNaC::ex b = ps[i].hi.value;
    GiNaC::ex jump = 0;
    const size_t nc = std::max(ps[i].c.size(), ps[i + 1].c.size());
    for (size_t k = 0; k < nc; ++k) {
      const GiNaC::numeric cl = k < ps[i].c.size() ? ps[i].c[k] : GiNaC::numeric(0);
      const GiNaC::numeric cr = k < ps[i + 1].c.size() ? ps[i + 1].c[k] : GiNaC::numeric(0);
      jump += (cr - cl) * GiNaC::pow(b + u, static_cast<int>(k));
    }
    jump = jump.expand();
    std::vector<std::string> terms;
    int dd = -1;
    for (size_t k = 0; k < nc; ++k) {
      terms.push_back(coef(s, jump.coeff(u, static_cast<int>(k))));
      if (!terms.back().empty()) {
        terms.back() += " * j" + std::to_string(k);
        dd = static_cast<int>(k);
      }
    }
    if (dd < 0) continue;  // f smooth there
    out += "  {  // break at " + s.bound(ps[i].hi) + "\n";
    out += "  " + s.decl("db", "(" + s.bound(ps[i].hi) + " - x) / sigma");
    out += "  " + s.decl("t", "abs(db)");
    out += "    if (t < " + (s.cpp() ? std::string("detail::tail_cut<T>()") : s.dbl(9)) + ") {\n";
    out += "      " + s.T() + " j0;\n      " + s.T() + " ph;\n";
    out += "      " + (s.cpp() ? std::string("detail::normal_phi_Phic") : s.helper("phi_Phic")) +
           "(t, ph, j0);\n";
    for (int k = 1; k <= dd; ++k) {
      const std::string prev =
          k == 1 ? "ph" : (k == 2 ? "j0" : s.dbl(k - 1) + " * j" + std::to_string(k - 2));
      out += "    " + s.decl("j" + std::to_string(k), prev + " - t * j" + std::to_string(k - 1));
    }
    // The side from x < b, not from db > 0: (b - x)/sigma underflows to 0 for x a subnormal step
    // below b and a wide kernel (step(-5e-324, 3) was 0 instead of 0.5).
    out += "    " + s.decl("st", "x < " + s.bound(ps[i].hi) + " ? sigma : -sigma");
    out += "      acc += (x < " + s.bound(ps[i].hi) + " ? " + s.dbl(1) + " : " + s.dbl(-1) + ") * (" +
           horner(s, terms, "st") + ");\n";
    out += "    }\n  }\n";
  }
  if (!glsl) return out + "  return acc;\n";
  // sigma = 0: f itself piece by piece (right-continuous, as pw_eval); past thr the pieces written
  // out. No table: a GPU would build one in local memory at every call site (NVIDIA refused a large
  // program's many copies, C5041, and drew slowly where it took them, docs/gpu_timing.md).
  out +=
      "  return acc;\n  }\n  if (sigma == " + s.dbl(0) + ") return " + piece_chain(ps, "x", s.lang) + ";\n";
  return out + (n > 2 ? pieces_written_out(s, Kernel::Gaussian, ps)
                      : "  return " + s.nan() + ";  // not reached: sigma >= 0 returned above\n");
}

std::string body_piecewise(const Derived& d, const Syntax& s) {
  if (d.kernel == Kernel::Gaussian) return body_gauss_pw(d, s);
  if (!s.cpp())  // sigma = 0: f piece by piece; else the pieces written out (no table)
    return guard_sigma(s) + "  if (sigma == " + s.dbl(0) + ") return " + piece_chain(d.pieces, "x", s.lang) +
           ";\n" + pieces_written_out(s, d.kernel, d.pieces);
  const std::string P = pieces_arg(s, "p", d.pieces.size());
  std::string call = d.kernel == Kernel::Gaussian ? "gauss_pw"
                     : d.kernel == Kernel::Box    ? "box_pw"
                                                  : "tent_pw";
  return piece_table(s, "p", d.pieces) + guard_sigma(s) + "  if (sigma == " + s.dbl(0) + ") return " +
         s.helper("pw_eval") + "(x, " + P + ");\n  return " + s.helper(call) + "(x, sigma, " + P + ");\n";
}

// Gaussian of exp-polynomial terms e^{a s} q(s), s = t - ref, each on a half-line [E, inf) /
// (-inf, E) or the whole line, specialised at emit time (support.hpp: gauss_exp_term). With
// alpha = (E - x)/sigma, beta = alpha - a sigma = (E - mu)/sigma (mu = x + a sigma^2, the completed
// square) and g = +1 for beta >= 0, else -1, the tail from E towards g is
//   T_g = e^{a (E - ref) - alpha^2/2}/sqrt(2 pi) sum_k h_k (g sigma)^k V_k(|beta|)
// (h: q about E - ref, exact here; V: tail_laplace, no cancellation for |beta| >= 0), and the term
// is T_g when g points into its half-line, else F - T_g with F = e^{a (x - ref) + a^2 sigma^2/2}
// E q(x - ref + a sigma^2 + sigma Z) the whole-line value (then mu lies inside, so F <= max|q|
// scale). One exp and one erfcx per term (two where F is taken). |x| or sigma beyond 1e4: the
// generic gauss_ept (in double for float).
std::string body_gauss_ept(const Derived& d, const Syntax& s) {
  const size_t n = d.eterms.size();
  const std::string P = pieces_arg(s, "p", n);
  std::string out = eterm_table(s, "p", d.eterms) + guard_sigma(s) + "  if (sigma == " + s.dbl(0) +
                    ") return " + s.helper("ept_eval") + "(x, " + P + ");\n";
  out += "  if (abs(x) > " + s.dbl(1e4) + " || sigma > " + s.dbl(1e4) + ") return " + s.helper("gauss_ept") +
         "(x, sigma, " + P + ");\n";
  bool need_s2 = false;
  for (const auto& t : d.eterms) need_s2 = need_s2 || t.c.size() >= 3;
  if (need_s2) out += s.decl("s2", "sigma * sigma");
  out += "  " + s.T() + " acc = " + s.dbl(0) + ";\n";
  const GiNaC::symbol u("u");
  for (size_t i = 0; i < n; ++i) {
    const auto& t = d.eterms[i];
    int deg = -1;
    for (size_t k = 0; k < t.c.size(); ++k)
      if (!t.c[k].is_zero()) deg = static_cast<int>(k);
    if (deg < 0) continue;
    const std::string A = s.num(t.a), ref = "(" + s.ex(t.ref) + ")";
    // F: the whole-line value.
    const std::string y = "(x - " + ref + " + " + A + " * sigma * sigma)";
    const std::string F = "exp(" + A + " * (x - " + ref + ") + " + s.dbl(0.5) + " * " + A + " * " + A +
                          " * sigma * sigma) * (" + normal_mean(s, t.c, "yv") + ")";
    out += "  {  // term " + std::to_string(i) + "\n";
    if (!t.lo.finite() && !t.hi.finite()) {
      out += "  " + s.decl("yv", y) + "    acc += " + F + ";\n  }\n";
      continue;
    }
    if (t.lo.finite() && t.hi.finite()) throw std::runtime_error("body_gauss_ept: a bounded term");
    const bool right = t.lo.finite();
    const Bound& Eb = right ? t.lo : t.hi;
    const std::string E = "(" + s.ex(Eb.value) + ")";
    GiNaC::ex qe = 0;
    for (size_t k = 0; k < t.c.size(); ++k)
      qe += t.c[k] * GiNaC::pow(Eb.value - t.ref + u, static_cast<int>(k));
    qe = qe.expand();
    std::vector<std::string> hs;
    for (int k = 0; k <= deg; ++k) {
      hs.push_back(coef(s, qe.coeff(u, k)));
      if (!hs.back().empty()) hs.back() += " * V[" + std::to_string(k) + "]";
    }
    out += "  " + s.decl("al", "(" + E + " - x) / sigma");
    out += "  " + s.decl("be", "al - " + A + " * sigma");
    // Skipped when |alpha| >= tail_cut (ref = E, degree <= 2): T_g <= e^{-alpha^2/2} sum |h_k| sigma^k
    // V_k(0) with sigma <= (1e4 + |E|)/tail_cut here, below 1e-11 (float) / 1e-25 (double).
    const bool skip = deg <= 2 && (Eb.value - t.ref).is_zero();
    const std::string in = skip ? "      " : "    ";
    out += "    " + s.T() + " tg = " + s.dbl(0) + ";\n";
    if (skip)
      out += "    if (abs(al) < " + (s.cpp() ? std::string("detail::tail_cut<T>()") : s.dbl(9)) + ") {\n";
    if (deg >= 1) out += in + s.decl("gs", "be >= " + s.dbl(0) + " ? sigma : -sigma").substr(2);
    out += in + s.T() + " V[8];\n";
    out += in + s.helper("tail_laplace") + "(abs(be), " + std::to_string(deg) + ", V);\n";
    out += in + "tg = exp(" + A + " * (" + E + " - " + ref + ") - " + s.dbl(0.5) + " * al * al) * " +
           s.dbl(0.3989422804014327) + " * (" + horner(s, hs, "gs") + ");\n";
    if (skip) out += "    }\n";
    out += std::string("    if (be ") + (right ? ">=" : "<") + " " + s.dbl(0) +
           ") {\n      acc += tg;\n    } else {\n";
    out += "    " + s.decl("yv", y) + "      acc += " + F + " - tg;\n    }\n  }\n";
  }
  return out + "  return acc;\n";
}

std::string body_exp_table(const Derived& d, const Syntax& s) {
  if (d.kernel == Kernel::Gaussian) {
    bool half_lines = true;
    for (const auto& t : d.eterms) half_lines = half_lines && !(t.lo.finite() && t.hi.finite());
    if (half_lines) return body_gauss_ept(d, s);
  }
  if (box_tent_ept_straight(d))
    return body_box_tent_ept(d, s, eterm_table(s, "p", d.eterms), pieces_arg(s, "p", d.eterms.size()));
  const std::string P = pieces_arg(s, "p", d.eterms.size());
  const std::string call = d.kernel == Kernel::Gaussian ? "gauss_ept"
                           : d.kernel == Kernel::Box    ? "box_ept"
                                                        : "tent_ept";
  return eterm_table(s, "p", d.eterms) + guard_sigma(s) + "  if (sigma == " + s.dbl(0) + ") return " +
         s.helper("ept_eval") + "(x, " + P + ");\n  return " + s.helper(call) + "(x, sigma, " + P + ");\n";
}

// Emit-time plan of the Gaussian dual series for one tolerance (series_tol: 1e-8 float, 1e-13
// double). The Fourier series is used for s = sigma/T >= s_min, with K = floor(C/s) terms:
// u = K + 1 > C/s gives a u^2 > 2 pi^2 C^2 = L + G (a = 2 pi^2 s^2, L = log(B/tol),
// G = -log(1 - e^{-2 a_min}), a_min = 2 pi^2 s_min^2), so the tail bound B e^{-a u^2} / (1 - e^{-2 a u})
// of fourier_terms (support.hpp) is <= tol: certified, and K at most one above the minimum. s_min is
// where the costs cross (unit: one transcendental call): Fourier 3 + 0.5 (K + extra) (one exp, cos,
// sin, then recurrences), image sum P npieces c (P = ceil(2 z s) + 1 periods, z = image_z, c = 4 for
// an erfc and an exp per piece, 20 for the Gauss-Legendre rule of a piece narrower than 2 sigma).
struct FourierPlan {
  double s_min, C;
};

FourierPlan plan_fourier(const Derived& d, double tol, int extra) {
  const double B = d.coef_bound, pi = 3.14159265358979323846;
  const int np = static_cast<int>(d.pieces.size());
  auto exact_K = [&](double s) {  // smallest certified K, as fourier_terms computes it
    const double a = 2 * pi * pi * s * s;
    for (int K = 0; K < 100000; ++K) {
      const double u = K + 1.0;
      if (B * std::exp(-a * u * u) / (-std::expm1(-2 * a * u)) <= tol) return K;
    }
    return 100000;
  };
  const double arg = 0.7978845608028654 * d.fmax / tol;
  const double z = arg > 1.6487212707001282 ? std::sqrt(2 * std::log(arg)) : 1.0;
  auto fourier_cheaper = [&](double s) {
    const double P = std::ceil(2 * z * s) + 1;
    const double per_piece = s * np > 0.5 ? 20.0 : 4.0;
    return 3.0 + 0.5 * (exact_K(s) + extra) <= P * np * per_piece;
  };
  // Scan down from s = 4 (Fourier always cheaper there) to the first s where it is not.
  double s_min = 4.0;
  for (double sv = 4.0; sv > 1e-3; sv *= 0.97) {
    if (!fourier_cheaper(sv)) break;
    s_min = sv;
  }
  const double L = B > tol ? std::log(B / tol) : 0.0;
  const double amin = 2 * pi * pi * s_min * s_min;
  const double G = -std::log(-std::expm1(-2 * amin));
  return {s_min, std::sqrt((L + G) / (2 * pi * pi))};
}

// The Fourier branch of a Gaussian periodic entry: for s >= s_min (plan_fourier) sum K = floor(C/s)
// terms. Per term k the loop defines kf, pk = (-1)^k (when the coefficients use it), w = 2 pi k / T,
// ck = cos(k w1 x_r), sk = sin(k w1 x_r) (by rotation: one cos and one sin per call; the error grows
// like k eps) and damp = exp(-2 pi^2 k^2 s^2) (by damp_k = damp_{k-1} q^{2k-1}, q = e^{-2 pi^2 s^2});
// `term` is added to acc (initially acc0) and `result` returned. extra: terms beyond the tolerance
// count (for k-weighted series).
std::string fourier_branch(const Derived& d, const Syntax& s, int extra, const std::string& acc0,
                           const std::string& term, const std::string& result, const std::string& arg = "x") {
  const FourierPlan pf = plan_fourier(d, 1e-8, extra), pd = plan_fourier(d, 1e-13, extra);
  auto pick = [&](double vf, double vd) {
    return s.cpp() ? "(sizeof(T) < sizeof(double) ? " + s.dbl(vf) + " : " + s.dbl(vd) + ")" : s.dbl(vf);
  };
  std::string body = term;
  for (auto [from, to] : {std::pair<std::string, std::string>{"cos(th)", "ck"}, {"sin(th)", "sk"}})
    for (size_t at; (at = body.find(from)) != std::string::npos;) body.replace(at, from.size(), to);
  std::string out = s.decl("s", "sigma / period");
  out += "  if (s >= " + pick(pf.s_min, pd.s_min) + ") {\n";
  out +=
      std::string("    ") + (s.cpp() ? "const " : "") + "int K = int(floor(" + pick(pf.C, pd.C) + " / s));\n";
  out += "  " + s.decl("xr", arg + " - period * floor(" + arg + " / period)");
  out += "  " + s.decl("w1", s.dbl(2) + " * " + s.pi() + " / period");
  out += "  " + s.decl("c1", "cos(w1 * xr)");
  out += "  " + s.decl("s1", "sin(w1 * xr)");
  out += "  " + s.decl("q", "exp(" + s.dbl(-2) + " * " + s.pi() + " * " + s.pi() + " * s * s)");
  out += "  " + s.decl("q2", "q * q");
  out += "    " + s.T() + " ck = c1;\n    " + s.T() + " sk = s1;\n";
  out += "    " + s.T() + " ratio = q;\n    " + s.T() + " damp = q;\n";
  out += "    " + s.T() + " acc = " + acc0 + ";\n";
  // Phases of boundaries at p/q of the period: (cph, sph) = (cos, sin)(2 pi k p/q), started at k = 1
  // from emit-time constants and advanced by rotation like (ck, sk) (error ~k eps; no cos or sin
  // inside the loop).
  std::string phase_steps;
  for (const auto& ph : d.phases) {
    const std::string pq = std::to_string(ph.p) + "_" + std::to_string(ph.q);
    const bool used_c =
        d.ak.has(sym::var_phase(ph.p, ph.q, true)) || d.bk.has(sym::var_phase(ph.p, ph.q, true));
    const bool used_s =
        d.ak.has(sym::var_phase(ph.p, ph.q, false)) || d.bk.has(sym::var_phase(ph.p, ph.q, false));
    if (!used_c && !used_s) continue;
    const double ang = 2 * 3.14159265358979323846 * ph.p / ph.q;
    out += "  " + s.decl("cr" + pq, s.dbl(std::cos(ang)));
    out += "  " + s.decl("sr" + pq, s.dbl(std::sin(ang)));
    out +=
        "    " + s.T() + " cph" + pq + " = cr" + pq + ";\n    " + s.T() + " sph" + pq + " = sr" + pq + ";\n";
    phase_steps += "    " + s.decl("cpn" + pq, "cph" + pq + " * cr" + pq + " - sph" + pq + " * sr" + pq);
    phase_steps += "      sph" + pq + " = sph" + pq + " * cr" + pq + " + cph" + pq + " * sr" + pq +
                   ";\n      cph" + pq + " = cpn" + pq + ";\n";
  }
  out +=
      "    for (int k = 1; k <= K" + (extra ? " + " + std::to_string(extra) : std::string()) + "; ++k) {\n";
  out += "    " + s.decl("kf", s.cpp() ? "T(k)" : "float(k)");
  if (d.ak.has(sym::var_pk()) || d.bk.has(sym::var_pk()))
    out += "    " + s.decl("pk", std::string("(k % 2 == 1) ? ") + s.dbl(-1) + " : " + s.dbl(1));
  if (body.find("w") != std::string::npos) out += "    " + s.decl("w", "w1 * kf");
  out += "      acc += " + body + ";\n";
  out += "    " + s.decl("cn", "ck * c1 - sk * s1");
  out += "      sk = sk * c1 + ck * s1;\n      ck = cn;\n      ratio *= q2;\n      damp *= ratio;\n" +
         phase_steps;
  out += "    }\n    return " + result + ";\n  }\n";
  return out;
}

// The exact rational value of a double.
GiNaC::numeric exact_value(double v) {
  int e = 0;
  const double m = std::frexp(v, &e);  // v = m 2^e, |m| in [0.5, 1)
  const GiNaC::numeric mi(static_cast<long>(std::ldexp(m, 53)));
  return mi * GiNaC::pow(GiNaC::numeric(2), GiNaC::numeric(e - 53));
}

// The two-part split b = hi + lo in T (hi = b rounded, lo = the rest rounded): float's split in float,
// double's in double and wider types.
std::pair<std::string, std::string> split_text(const Syntax& s, const GiNaC::numeric& b) {
  const double hd = b.to_double(), ld = (b - exact_value(hd)).to_double();
  const double hf = static_cast<float>(hd), lf = static_cast<float>((b - exact_value(hf)).to_double());
  if (!s.cpp()) return {s.dbl(hf), s.dbl(lf)};
  auto pick = [&](double vf, double vd) {
    return "(sizeof(T) < sizeof(double) ? " + s.dbl(vf) + " : " + s.dbl(vd) + ")";
  };
  return {pick(hf, hd), pick(lf, ld)};
}

// Near an inner break b of d.origins (within its gap of the exact signed remainder r, at b or b - T):
// return call(y, o) with y = (r - bh) - bl the distance from b's exact position (r - bh is exact
// there by Sterbenz, so only bl's small rounding remains) and o the name of the table re-origined
// at b ("o<j>", its integrals "o<j>_1", "o<j>_2"). Everything else falls through to the caller's
// original table. `integrals`: 0 pieces only, 1 with P1, 2 with P1 and P2.
std::string origin_dispatch(const Derived& d, const Syntax& s, int integrals,
                            const std::function<std::string(const std::string&, const std::string&)>& call) {
  if (d.origins.empty()) return "";
  std::string out = s.decl("r_o", s.helper("reduce_signed") + "(x, period)");
  const GiNaC::numeric T = GiNaC::ex_to<GiNaC::numeric>(d.period);
  for (size_t j = 0; j < d.origins.size(); ++j) {
    const auto& o = d.origins[j];
    const std::string nm = "o" + std::to_string(j);
    std::ostringstream bt;
    bt << o.b;
    out += "  {  // break at " + bt.str() + "\n";
    std::string tables = piece_table(s, nm, o.pieces);
    if (integrals >= 1) tables += piece_table(s, nm + "_1", o.P1);
    if (integrals >= 2) tables += piece_table(s, nm + "_2", o.P2);
    for (size_t at = 0; (at = tables.find("\n  ", at)) != std::string::npos; at += 3)
      tables.insert(at + 1, "  ");
    out += "  " + tables;
    const std::string gap = s.dbl(o.gap.to_double());
    for (int side = 0; side < 2; ++side) {
      const auto [bh, bl] = split_text(s, side == 0 ? o.b : o.b - T);
      const std::string v = (side == 0 ? "bh" : "ch") + std::to_string(j);
      const std::string w = (side == 0 ? "bl" : "cl") + std::to_string(j);
      out += "  " + s.decl(v, bh) + "  " + s.decl(w, bl);
      out += "    if (abs(r_o - " + v + ") < " + gap + ") return " + call("(r_o - " + v + ") - " + w, nm) +
             ";\n";
    }
    out += "  }\n";
  }
  return out;
}

}  // namespace

int atomic_index(const sym::Catalog& cat, const sym::Atomic* a) {
  if (!a) return static_cast<int>(cat.atomics.size());
  for (size_t i = 0; i < cat.atomics.size(); ++i)
    if (&cat.atomics[i] == a) return static_cast<int>(i);
  throw std::runtime_error("atomic not in the catalog");
}

// A Gaussian periodic entry whose straight-line plan (gauss_periodic_fast) goes first: no phases or
// origins (those keep the generic image sum).
bool gauss_straight_first(const Derived& d) {
  return d.kernel == Kernel::Gaussian && d.body == Body::PeriodicTable && d.phases.empty() &&
         d.origins.empty();
}

std::string periodic_hot(const Derived& d, const std::string& general, const std::string& clamp,
                         bool* in_range) {
  *in_range = false;
  if (d.kernel != Kernel::Gaussian) return box_tent_periodic_hot(d, general, clamp, in_range);
  return gauss_straight_first(d) ? gauss_periodic_hot(periodic_spec(d), general, clamp, in_range) : "";
}

std::string general_call(const std::string& general, const std::string& clamp) {
  if (clamp.empty()) return "  return " + general + "<T>(x, sigma);\n";
  return "  const T v = " + general + "<T>(x, sigma);\n" + clamp;
}

GaussPeriodicSpec periodic_spec(const Derived& d) {
  GaussPeriodicSpec sp;
  if (!GiNaC::is_a<GiNaC::numeric>(d.period)) return sp;
  sp.period = GiNaC::ex_to<GiNaC::numeric>(d.period);
  for (const PolyPiece& pc : d.pieces) {
    if (!pc.lo.finite() || !GiNaC::is_a<GiNaC::numeric>(pc.lo.value)) return GaussPeriodicSpec{};
    sp.lo.push_back(GiNaC::ex_to<GiNaC::numeric>(pc.lo.value));
    sp.c.emplace_back(pc.c.begin(), pc.c.end());
  }
  sp.a0 = d.a0, sp.ak = d.ak, sp.bk = d.bk, sp.coef_bound = d.coef_bound;
  return sp;
}

namespace {

std::string body_periodic(const Derived& d, const Syntax& s) {
  const size_t n = d.pieces.size();
  // Gaussian: the straight-line regimes go before the piece table, which only sigma = 0 and the
  // generic code below read (a GPU keeps such an array in local memory; a CPU would build it on
  // the stack on every call).
  const bool fast_first = gauss_straight_first(d);
  std::string out;
  if (fast_first) {
    out += s.decl("period", s.ex(d.period)) + guard_sigma(s) +
           (s.cpp() ? gauss_periodic_fast_cpp(periodic_spec(d)) : gauss_periodic_fast_glsl(periodic_spec(d)));
    if (!s.cpp()) {
      // GLSL: the straight-line block took every sigma > 0, so what is left is sigma = 0: f itself in
      // straight lines, and no piece table or generic code (local memory on a GPU, see
      // gauss_periodic_fast).
      std::vector<std::pair<GiNaC::ex, GiNaC::ex>> pieces;
      for (const PolyPiece& pc : d.pieces) pieces.emplace_back(pc.hi.value, poly_in_x(pc.c));
      return out + "  // sigma == 0\n" + periodic_straight(d.period, pieces, s.lang, true);
    }
    out += piece_table(s, "p", d.pieces);
  } else {
    out += piece_table(s, "p", d.pieces);
    if (d.kernel != Kernel::Gaussian) out += piece_table(s, "p1", d.P1);
    if (d.kernel == Kernel::Tent) out += piece_table(s, "p2", d.P2);
    out += s.decl("period", s.ex(d.period));
    out += guard_sigma(s);
  }
  auto plain = [&](const std::string& y, const std::string& t) {
    return s.helper("periodic_eval") + "(" + y + ", period, " + pieces_arg(s, t, n) + ")";
  };
  if (!d.origins.empty()) {
    out += "  if (sigma == " + s.dbl(0) + ") {\n" + origin_dispatch(d, s, 0, plain) + "  return " +
           plain("x", "p") + ";\n  }\n";
  } else if (s.cpp() || !fast_first) {  // (GLSL fast_first: returned above)
    out += "  if (sigma == " + s.dbl(0) + ") return " + plain("x", "p") + ";\n";
  }
  if (d.kernel != Kernel::Gaussian) {
    const bool box = d.kernel == Kernel::Box;
    auto call = [&](const std::string& y, const std::string& t) {
      return s.helper(box ? "box_periodic" : "tent_periodic") + "(" + y + ", sigma, period, " +
             pieces_arg(s, t, n) + ", " + (t == "p" ? "p1" : t + "_1") +
             (box ? "" : std::string(", ") + (t == "p" ? "p2" : t + "_2")) + ")";
    };
    return out + origin_dispatch(d, s, box ? 1 : 2, call) + "  return " + call("x", "p") + ";\n";
  }
  // Gaussian: the dual series, whichever needs fewer terms for the tolerance.
  std::string terms;
  if (!d.ak.is_zero()) terms = s.ex(d.ak) + " * cos(th)";
  if (!d.bk.is_zero()) terms += (terms.empty() ? "" : " + ") + s.ex(d.bk) + " * sin(th)";
  out += fourier_branch(d, s, 0, s.ex(d.a0), "damp * (" + (terms.empty() ? s.dbl(0) : terms) + ")", "acc");
  auto call = [&](const std::string& y, const std::string& t) {
    return s.helper("gauss_periodic_image") + "(" + y + ", sigma, period, " + pieces_arg(s, t, n) + ", " +
           s.dbl(d.fmax) + ")";
  };
  return out + origin_dispatch(d, s, 0, call) + "  return " + call("x", "p") + ";\n";
}

}  // namespace

FusablePair fusable_pair(const std::string& atomic, const std::vector<Derived>* ds) {
  FusablePair f;
  if (!ds) return f;
  for (const Derived& e : *ds) {
    if (e.kernel != Kernel::Gaussian || e.atomic_name != atomic || e.body != sym::Body::PeriodicTable ||
        e.rule == "moment")
      continue;
    (e.squared ? f.a2 : f.a) = &e;
  }
  auto ok = [](const Derived* e, size_t maxdeg) {
    return e && e->pieces.size() == 1 && e->pieces[0].c.size() <= maxdeg + 1 && e->phases.empty();
  };
  if (!ok(f.a, 1) || !ok(f.a2, 2)) f = FusablePair{};
  return f;
}

namespace {

// Fused Gaussian form of the terms c0 A(y) + c2 A(y)^2 + c1 x A(y) of a combination, y = sgn x,
// A periodic with one piece g(t) = g0 + g1 t on [0, T) (fract): one dual series instead of the
// three entries A~, (A^2)~ and E[U A(y+U)] (floor^2 called fract three times). With x = sgn y,
//   E[x' A(y')] = sgn E[y' A(y')] = sgn (y A~(y) + E[V A(y+V)]),  y' = y + V, V ~ N(0, sigma^2),
// and Stein's identity E[V A(y+V)] = sigma^2 E[A'(y+V)] = sigma^2 (g1 + J theta(y)), where
// J = g(0) - g(T) is the jump at the period boundary and theta(y) = sum_m phi_sigma(y - m T) the
// periodised Gaussian. So the terms are E[h(y+V)] + c1 sgn sigma^2 (g1 + J theta(y)) with the
// periodic polynomial h = lam A + c2 A^2, lam = c0 + c1 sgn y (a runtime coefficient). Fourier
// regime: theta = (1/T)(1 + 2 sum_k damp_k cos(2 pi k y/T)) joins the loop of h; image regime:
// gauss_periodic_image of h plus theta's image sum (exps within image_z sigma). lam multiplies
// A~'s absolute error as in x A~(x); the theta coefficient sigma^2 = s^2 T^2 is bounded by 4 T^2
// in the plan (s^2 e^{-2 pi^2 s^2 u^2} is below tol for s > 2 at any u >= 1).
struct FusedTerms {
  std::string atomic;
  int sgn = 0;
  GiNaC::numeric c0 = 0, c1 = 0, c2 = 0;
  std::vector<size_t> idx;  // the terms it replaces
};

std::string fused_periodic(const Derived& d, const FusedTerms& f, const FusablePair& pr, const Syntax& s,
                           const std::string& rest) {
  using GiNaC::ex;
  const Derived& A = *pr.a;
  const Derived& A2 = *pr.a2;
  const GiNaC::symbol lam("lam"), y("y");
  const ex T = A.period;
  const GiNaC::numeric Tn = GiNaC::ex_to<GiNaC::numeric>(T.evalf());
  std::vector<GiNaC::numeric> g = A.pieces[0].c;
  g.resize(2, 0);
  const GiNaC::numeric J = g[0] - (g[0] + g[1] * GiNaC::ex_to<GiNaC::numeric>(T));
  const ex sig = sym::var_sigma();
  const GiNaC::numeric c1s = f.c1 * f.sgn;
  Derived dd = A2;  // period, one piece: the plan's inputs
  dd.ak = (lam * A.ak + f.c2 * A2.ak + c1s * sig * sig * 2 * J / T).expand();
  dd.bk = (lam * A.bk + f.c2 * A2.bk).expand();
  dd.a0 = (lam * A.a0 + f.c2 * A2.a0 + c1s * sig * sig * (g[1] + J / T)).expand();
  const double lamb = std::fabs(f.c0.to_double()) + std::fabs(f.c1.to_double());
  const double c2b = std::fabs(f.c2.to_double());
  dd.coef_bound = lamb * A.coef_bound + c2b * A2.coef_bound +
                  std::fabs(c1s.to_double()) * 2 * std::fabs(J.to_double()) * 4 * Tn.to_double();
  dd.fmax = lamb * A.fmax + c2b * A2.fmax;
  // h's piece: lam g + c2 g^2 (coefficients printed as runtime expressions).
  std::vector<ex> hc(8, ex(0));
  for (size_t k = 0; k < A.pieces[0].c.size(); ++k) hc[k] += lam * A.pieces[0].c[k];
  for (size_t k = 0; k < A2.pieces[0].c.size(); ++k) hc[k] += f.c2 * A2.pieces[0].c[k];
  std::string coeffs;
  for (int k = 0; k < 8; ++k) coeffs += (k ? ", " : "") + s.ex(hc[k].expand());
  std::string out;
  out += s.decl("y", f.sgn < 0 ? "-x" : "x");
  out += s.decl("lam", s.ex(f.c0 + c1s * y));
  out += s.decl("period", s.ex(T));
  std::string table;
  if (s.cpp())
    table = "  const detail::Piece<T> p[1] = {{" + s.bound(A.pieces[0].lo) + ", " + s.bound(A.pieces[0].hi) +
            ", {" + coeffs + "}}};\n";
  else
    table = "  BlPiece p[4] = BlPiece[4](BlPiece(" + s.bound(A.pieces[0].lo) + ", " +
            s.bound(A.pieces[0].hi) + ", float[8](" + coeffs +
            ")), BlPiece(0.0, 0.0, float[8](0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)), "
            "BlPiece(0.0, 0.0, float[8](0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)), BlPiece(0.0, 0.0, "
            "float[8](0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)));\n";
  const std::string lead = rest.empty() ? "" : rest + " + ";
  std::string fast;
  if (GiNaC::is_a<GiNaC::numeric>(T) && GiNaC::is_a<GiNaC::numeric>(A.pieces[0].lo.value)) {
    GaussPeriodicSpec sp;
    sp.period = GiNaC::ex_to<GiNaC::numeric>(T);
    sp.lo = {GiNaC::ex_to<GiNaC::numeric>(A.pieces[0].lo.value)};
    sp.c = {hc};
    sp.a0 = dd.a0, sp.ak = dd.ak, sp.bk = dd.bk, sp.coef_bound = dd.coef_bound;
    sp.delta = c1s * J * sig;  // theta's sum of phi_sigma at the breaks, times c1s J sigma^2
    sp.break_extra = c1s * g[1] * sig * sig;
    sp.y = "y";
    sp.lead = lead;
    fast = s.cpp() ? gauss_periodic_fast_cpp(sp) : gauss_periodic_fast_glsl(sp);
  }
  // The straight-line regimes before the piece table, which only the generic code reads (a GPU
  // keeps such an array in local memory, a CPU builds it on the stack on every call). GLSL: the
  // straight-line block takes every sigma > 0 (gauss_periodic_fast), so sigma = 0 is left: h itself
  // in straight lines, no table and no generic code.
  if (!s.cpp() && !fast.empty() && A.pieces[0].lo.value.is_zero()) {
    return out + fast + "  // sigma == 0\n" +
           periodic_straight(T, {{A.pieces[0].hi.value, poly_in_x(hc).expand()}}, s.lang, true, "y", lead);
  }
  out += fast + table;
  out += fourier_branch(dd, s, 0, s.ex(dd.a0),
                        "damp * (" + s.ex(dd.ak) + " * cos(th) + " + s.ex(dd.bk) + " * sin(th))",
                        lead + "acc", "y");
  // Image regime: h's image sum plus theta's exps within R = z sigma (z = image_z(1, tol): the
  // neglected exps sum to < tol/(sqrt(2 pi)) relative to theta's scale 1/sigma).
  const std::string tol = s.cpp() ? "detail::series_tol<T>()" : "BL_SERIES_TOL";
  out += s.decl("yr", s.helper("reduce_signed") + "(y, period)");
  out += s.decl("R", s.helper("image_z") + "(" + s.dbl(1) + ", " + tol + ") * sigma");
  out += "  " + s.T() + " th = " + s.dbl(0) + ";\n";
  out += "  if (sigma > " + s.dbl(0) + ") {\n";
  out += "    for (" + s.T() +
         " m = floor((yr - R) / period); m <= floor((yr + R) / period); m += " + s.dbl(1) + ") {\n";
  out += "    " + s.decl("t", "(yr - m * period) / sigma");
  out += "      th += exp(" + s.dbl(-0.5) + " * t * t);\n    }\n  }\n";
  const double inv_sqrt_2pi = 0.3989422804014327;
  out += "  return " + lead + s.helper("gauss_periodic_image") + "(y, sigma, period, " +
         pieces_arg(s, "p", 1) + ", " + s.dbl(dd.fmax) + ") + " + s.ex(c1s * g[1]) + " * sigma * sigma + " +
         s.ex(c1s * J) + " * " + s.dbl(inv_sqrt_2pi) + " * sigma * th;\n";
  return out;
}

// Gaussian combinations whose piecewise terms (step, x step, A step) break only inside [bmin, bmax]
// (trunc, trunc^2: at 0): for x - R >= bmax (x + R < bmin) each such term is the smoothing of its
// outer polynomial piece, a polynomial in x and sigma, and A_right(x - b) is A~(x) (0), up to
// sum |c| Phic(z) + sigma phi(z) terms, R = z sigma, z = image_z(sum |c|, tol): the entry is then
// the periodic terms alone (fused when they are several). Returns the two guarded branches, or ""
// when a term does not fit (a non-polynomial outer piece, degree > 2, another periodic atomic).
std::string far_sides(const Derived& d, const Syntax& s, const std::vector<Derived>* ds,
                      const FusedTerms& fz0, const FusablePair& pr) {
  using Kind = sym::CombinationTerm::Kind;
  if (d.kernel != Kernel::Gaussian || !ds) return "";
  const GiNaC::ex x = sym::var_x(), sig = sym::var_sigma();
  auto smooth_poly = [&](const std::vector<GiNaC::numeric>& c) -> std::optional<GiNaC::ex> {
    if (c.size() > 3) return std::nullopt;  // E[(x+U)^k], k <= 2
    const GiNaC::ex m[3] = {1, x, x * x + sig * sig};
    GiNaC::ex r = 0;
    for (size_t k = 0; k < c.size(); ++k) r += c[k] * m[k];
    return r;
  };
  std::optional<double> bmin, bmax;
  double csum = 0;
  GiNaC::ex polyR = d.closed, polyL = d.closed;
  FusedTerms fR = fz0, fL = fz0;
  std::string periodic;                     // the atomic of the periodic terms
  std::vector<std::string> otherR, otherL;  // periodic terms outside the fused group
  auto note_break = [&](double b) {
    bmin = bmin ? std::min(*bmin, b) : b;
    bmax = bmax ? std::max(*bmax, b) : b;
  };
  for (size_t i = 0; i < d.terms.size(); ++i) {
    const auto& t = d.terms[i];
    const bool fused = std::find(fz0.idx.begin(), fz0.idx.end(), i) != fz0.idx.end();
    const std::vector<PolyPiece>* ps = nullptr;
    if (t.kind == Kind::Pieces) ps = &t.pieces;
    if (t.kind == Kind::Smoothed && t.xpow == 0) {
      for (const Derived& e : *ds)
        if (e.kernel == Kernel::Gaussian && e.atomic_name == t.atomic && e.squared == t.squared &&
            e.body == sym::Body::PiecewiseTable && e.rule != "moment")
          ps = &e.pieces;
    }
    if (ps) {
      if (ps->empty() || ps->front().lo.finite() || ps->back().hi.finite()) return "";
      for (size_t j = 0; j + 1 < ps->size(); ++j) note_break((*ps)[j].hi.to_double());
      const auto l = smooth_poly(ps->front().c), r = smooth_poly(ps->back().c);
      if (!l || !r) return "";
      polyL += t.coeff * *l;
      polyR += t.coeff * *r;
      csum += std::fabs(t.coeff.to_double());
      continue;
    }
    if (fused) continue;
    if (t.kind == Kind::HalfLines) {
      // A (full + sum rc 1{x >= b}): right of every b all of it, left of them the full part.
      if (!pr.a || t.atomic != fz0.atomic || t.arg_sign != 1) return "";
      GiNaC::numeric all = t.full;
      for (const auto& [rc, b] : t.right) {
        if (!GiNaC::is_a<GiNaC::numeric>(b.evalf())) return "";
        note_break(GiNaC::ex_to<GiNaC::numeric>(b.evalf()).to_double());
        all += rc;
        csum += std::fabs(rc.to_double());
      }
      fR.c0 += t.coeff * all;
      fL.c0 += t.coeff * t.full;
      continue;
    }
    // A periodic term outside the group (Smoothed of a periodic atomic): the same on both sides.
    if (t.kind != Kind::Smoothed || t.xpow != 0) return "";
    Derived other;
    other.atomic_name = t.atomic;
    other.kernel = d.kernel;
    other.squared = t.squared;
    const std::string A =
        s.num(t.coeff) + " * " + s.fn(impl_name(other)) + "(" + (t.arg_sign < 0 ? "-x" : "x") + ", sigma)";
    if (!pr.a || t.atomic != fz0.atomic || t.arg_sign != fz0.sgn || t.squared) {
      otherR.push_back(A);
      otherL.push_back(A);
    } else {
      fR.c0 += t.coeff;
      fL.c0 += t.coeff;
    }
  }
  if (!bmin || csum == 0) return "";
  const std::string tol = s.cpp() ? "detail::series_tol<T>()" : "BL_SERIES_TOL";
  std::string out = s.decl("Rf", s.helper("image_z") + "(" + s.dbl(csum) + ", " + tol + ") * sigma");
  auto side = [&](const std::string& cond, const GiNaC::ex& poly, const FusedTerms& f,
                  const std::vector<std::string>& others) {
    std::string rest = s.ex(poly.expand());
    for (const auto& o : others) rest += " + " + o;
    std::string b = "  if (" + cond + ") {\n";
    const bool one = f.c1.is_zero() && f.c2.is_zero();
    if (!pr.a || (one && f.c0.is_zero())) {
      b += "  return " + rest + ";\n";
    } else if (one) {
      Derived a;
      a.atomic_name = f.atomic;
      a.kernel = d.kernel;
      b += "  return " + rest + " + " + s.num(f.c0) + " * " + s.fn(impl_name(a)) + "(" +
           (f.sgn < 0 ? "-x" : "x") + ", sigma);\n";
    } else {
      b += s.decl("rest", rest) + fused_periodic(d, f, pr, s, "rest");
    }
    return b + "  }\n";
  };
  out += side("x - Rf >= " + s.dbl(*bmax), polyR, fR, otherR);
  out += side("x + Rf < " + s.dbl(*bmin), polyL, fL, otherL);
  return out;
}

std::string body_combination(const Derived& d, const Syntax& s, const std::vector<Derived>* ds,
                             const std::string& between) {
  using Kind = sym::CombinationTerm::Kind;
  // Gaussian: fuse the terms A(y), A(y)^2, x A(y) of one periodic atomic (see fused_periodic).
  FusedTerms fz;
  FusablePair pr;
  if (d.kernel == Kernel::Gaussian) {
    for (size_t i = 0; i < d.terms.size(); ++i) {
      const auto& t = d.terms[i];
      const bool plain = t.kind == Kind::Smoothed && t.xpow == 0;
      const bool first = t.kind == Kind::FirstMoment && t.xpow == 1 && !t.squared;
      if (!plain && !first) continue;
      if (fz.idx.empty()) {
        pr = fusable_pair(t.atomic, ds);
        if (!pr.a) continue;
        fz.atomic = t.atomic;
        fz.sgn = t.arg_sign;
      }
      if (t.atomic != fz.atomic || t.arg_sign != fz.sgn) continue;
      if (first)
        fz.c1 += t.coeff;
      else if (t.squared)
        fz.c2 += t.coeff;
      else
        fz.c0 += t.coeff;
      fz.idx.push_back(i);
    }
    // Worth it when the fused terms would call more than one entry (floor, ceil call one).
    if (fz.idx.size() < 2 && fz.c1.is_zero()) fz = FusedTerms{};
  }
  // Gaussian: the piecewise terms (step, step^2, x step of trunc^2) with the same breaks are one
  // table of summed pieces, smoothed by one gauss_pw call (one erfc and exp per break, not one per
  // term).
  std::vector<PolyPiece> merged;
  std::vector<size_t> merged_idx;
  if (d.kernel == Kernel::Gaussian && ds) {
    for (size_t i = 0; i < d.terms.size(); ++i) {
      const auto& t = d.terms[i];
      const std::vector<PolyPiece>* ps = nullptr;
      if (t.kind == Kind::Pieces) ps = &t.pieces;
      if (t.kind == Kind::Smoothed && t.xpow == 0 && t.arg_sign == 1)
        for (const Derived& e : *ds)
          if (e.kernel == Kernel::Gaussian && e.atomic_name == t.atomic && e.squared == t.squared &&
              e.body == sym::Body::PiecewiseTable && e.rule != "moment")
            ps = &e.pieces;
      if (!ps) continue;
      auto same_breaks = [&] {
        if (merged.size() != ps->size()) return false;
        for (size_t j = 0; j + 1 < ps->size(); ++j)
          if (!(merged[j].hi.value - (*ps)[j].hi.value).is_zero() || merged[j].hi.inf != (*ps)[j].hi.inf)
            return false;
        return true;
      };
      if (merged.empty()) {
        merged = *ps;
        for (auto& pc : merged)
          for (auto& c : pc.c) c = c * t.coeff;
      } else if (same_breaks()) {
        for (size_t j = 0; j < ps->size(); ++j) {
          auto& mc = merged[j].c;
          if (mc.size() < (*ps)[j].c.size()) mc.resize((*ps)[j].c.size(), 0);
          for (size_t k = 0; k < (*ps)[j].c.size(); ++k) mc[k] += t.coeff * (*ps)[j].c[k];
        }
      } else {
        continue;
      }
      merged_idx.push_back(i);
    }
    if (merged_idx.size() < 2) merged_idx.clear();
  }
  std::string tables;
  std::string out = fz.idx.empty() ? "  return " + s.ex(d.closed) : s.ex(d.closed);
  if (!merged_idx.empty()) {
    if (!(s.cpp() && merged.size() == 2)) tables += piece_table(s, "pm", merged);
    if (s.cpp() && merged.size() == 2) {
      // One break: body_gauss_pw's straight-line form as an immediately invoked lambda (the generic
      // gauss_pw loops cost trunc^2 ~20 ns per call near 0).
      Derived dm;
      dm.kernel = Kernel::Gaussian;
      dm.pieces = merged;
      out += " + [&]() -> T {\n" + body_gauss_pw(dm, s) + "  }()";
    } else {
      out += " + " + s.helper("gauss_pw") + "(x, sigma, " + pieces_arg(s, "pm", merged.size()) + ")";
    }
  }
  for (size_t i = 0; i < d.terms.size(); ++i) {
    if (std::find(fz.idx.begin(), fz.idx.end(), i) != fz.idx.end()) continue;
    if (std::find(merged_idx.begin(), merged_idx.end(), i) != merged_idx.end()) continue;
    const auto& t = d.terms[i];
    Derived other;
    other.atomic_name = t.atomic;
    other.kernel = d.kernel;
    other.squared = t.squared;
    const std::string arg = t.arg_sign < 0 ? "-x" : "x";
    const std::string A = s.fn(impl_name(other)) + "(" + arg + ", sigma)";
    out += " + " + s.num(t.coeff) + " * ";
    if (t.kind == Kind::Pieces) {
      // x^n A(x)^d with A piecewise: the product's pieces, smoothed like a piecewise atomic.
      const std::string name = "pt" + std::to_string(i);
      tables += piece_table(s, name, t.pieces);
      const std::string call = d.kernel == Kernel::Gaussian ? "gauss_pw"
                               : d.kernel == Kernel::Box    ? "box_pw"
                                                            : "tent_pw";
      out += s.helper(call) + "(x, sigma, " + pieces_arg(s, name, t.pieces.size()) + ")";
    } else if (t.kind == Kind::HalfLines) {
      // A(x) B(x), B piecewise constant: A~ and A's half-line companion at the breaks of B.
      std::string parts;
      if (!t.full.is_zero()) parts = s.num(t.full) + " * " + A;
      for (const auto& [rc, b] : t.right) {
        const std::string shifted = b.is_zero() ? std::string("x") : "x - " + s.ex(b);
        parts += (parts.empty() ? "" : " + ") + s.num(rc) + " * " + s.fn(impl_name(other) + "_right") + "(" +
                 shifted + ", sigma)";
      }
      out += "(" + (parts.empty() ? s.dbl(0) : parts) + ")";
    } else if (t.xpow == 1) {
      // E[(x+U) A(x+U)] = x A~(x) + E[U A(x+U)]; for A(-x) the first moment flips sign.
      const std::string Au = s.fn(impl_name(other) + "_u") + "(" + arg + ", sigma)";
      out += "(x * " + A + (t.arg_sign < 0 ? " - " : " + ") + Au + ")";
    } else {
      out += A;
    }
  }
  const std::string near =
      fz.idx.empty() ? out + ";\n" : s.decl("rest", out) + fused_periodic(d, fz, pr, s, "rest");
  return tables + guard_sigma(s) + far_sides(d, s, ds, fz, pr) + between + near;
}

// Common subexpressions g(x) of the Taylor coefficients become locals u0, u1, ...
GiNaC::ex cse_calls(const GiNaC::ex& e, std::map<std::string, std::pair<GiNaC::symbol, GiNaC::ex>>& calls) {
  if (is_a<function>(e) && e.nops() == 1 && e.op(0).is_equal(sym::var_x())) {
    std::ostringstream k;
    k << ex_to<function>(e).get_name();
    auto it = calls.find(k.str());
    if (it == calls.end())
      it = calls.emplace(k.str(), std::make_pair(GiNaC::symbol("u_" + k.str()), e)).first;
    return it->second.first;
  }
  struct Recurse : GiNaC::map_function {
    std::map<std::string, std::pair<GiNaC::symbol, GiNaC::ex>>& calls;
    explicit Recurse(std::map<std::string, std::pair<GiNaC::symbol, GiNaC::ex>>& c) : calls(c) {}
    GiNaC::ex operator()(const GiNaC::ex& sub) override { return cse_calls(sub, calls); }
  } recurse(calls);
  return e.map(recurse);
}

// A non-periodic atomic whose only singularity is 0 (log, sqrt, inv, inv2): its compact series is
// evaluated in t = hh/x (series_body), and GLSL takes that series at tiny x (body_antiderivative).
bool singular_only_at_zero(const sym::Atomic& a) {
  return !a.period && a.singular.size() == 1 && a.singular[0].is_zero();
}

// The first neglected order of the scaled series (series_body) at float's reach t = hh/x = 0.35,
// relative to its leading term, is about t^2 = 0.12 times the last kept term (at x = 2, where
// log x != 0): where that term is below 5e-6 the float path may take the series to float's reach
// (inv2^2's x^-4 has growing coefficients, 1.2e-4 and 1.7e-5 for box and tent: those keep running
// in double).
bool float_series_reach_ok(const Derived& d) {
  if (d.series.size() < 2) return false;
  const GiNaC::symbol& x = sym::var_x();
  const int n = static_cast<int>(d.series.size()) - 1;
  const GiNaC::ex first = (d.series[0]).subs(x == 2).evalf();
  const GiNaC::ex last = (d.series[n] * GiNaC::pow(x, 2 * n)).subs(x == 2).evalf();
  if (!is_a<numeric>(first) || !is_a<numeric>(last) || ex_to<numeric>(first).is_zero()) return false;
  const double ratio = std::fabs(ex_to<numeric>(last).to_double() / ex_to<numeric>(first).to_double());
  return ratio * std::pow(0.35, 2 * n) < 5e-6;
}

std::string body_antiderivative(const Derived& d, const Syntax& s) {
  const sym::Atomic& a = *d.atomic;
  const symbol& x = sym::var_x();
  const GiNaC::ex hh = sym::var_hh();
  std::string out = guard_sigma(s);
  if (s.cpp() && singular_only_at_zero(a) && float_series_reach_ok(d))
    // Singular at 0 only: r = |x| is exact in float, and the difference quotient of F's
    // non-polynomial part (x^k log|x| terms, differenced at hh >= 0.35 |x|) loses about
    // 3 |log|x|| (|x|/hh)^2 <= 3 * 4.2 * 8 roundings for 1/64 <= |x| <= 64: float stays in float
    // there (< 3e-6 relative, measured by blverify), and runs in double outside.
    out +=
        "  if constexpr (sizeof(T) < sizeof(double)) {\n    if (!(abs(x) >= T(0.015625) && abs(x) <= "
        "T(64))) return T(" +
        impl_name(d) + "<double>(double(x), double(sigma)));\n  }\n";
  else if (s.cpp() && !a.singular.empty())
    // Next to a singularity the distance r (and x +- hh) needs more digits than a float has: a float
    // input 4e-8 from pi/2 is 0 from the float pi/2. Float entries of compact rules run in double
    // (GLSL stays in float: see docs/derivations.md).
    out += "  if constexpr (sizeof(T) < sizeof(double)) return T(" + impl_name(d) +
           "<double>(double(x), double(sigma)));\n";
  // Parity: the body runs on |x| and an odd entry multiplies its result by the sign of x. Done in
  // place (no reflected self-call): GLSL forbids recursion and Mesa refuses it at link time.
  bool odd = false;
  if (a.parity != 0) {
    odd = a.parity < 0 && !d.squared;
    if (odd) out += s.decl("sx", "x < " + s.dbl(0) + " ? " + s.dbl(-1) + " : " + s.dbl(1));
    out += std::string("  x = abs(x);  // ") + (odd ? "odd: f(-x) = -f(x)" : "even") + "\n";
  }
  auto ret = [odd](const std::string& v) { return "return " + (odd ? "sx * (" + v + ")" : v) + ";"; };
  if (a.domain_lo.finite())
    out += "  if (x < " + s.ex(a.domain_lo.value) + ") return " + s.nan() + ";  // outside the domain\n";
  if (a.domain_hi.finite())
    out += "  if (x > " + s.ex(a.domain_hi.value) + ") return " + s.nan() + ";  // outside the domain\n";
  const std::string width = s.ex(sym::half_width(d.kernel));
  bool has_r = !a.singular.empty();
  if (has_r) {
    // Distance to the nearest singularity (repeating with the period when there is one).
    std::string r;
    if (a.period) {
      out += s.decl("period", s.ex(*a.period));
      out += s.decl("xr", "x - period * floor(x / period)");
      for (size_t i = 0; i < a.singular.size(); ++i) {
        const std::string di = "abs(xr - " + s.ex(a.singular[i]) + ")";
        const std::string ri = s.min(di, "period - " + di);
        r = r.empty() ? ri : s.min(r, ri);
      }
    } else {
      for (size_t i = 0; i < a.singular.size(); ++i) {
        const std::string ri = "abs(x - " + s.ex(a.singular[i]) + ")";
        r = r.empty() ? ri : s.min(r, ri);
      }
    }
    out += s.decl("r", r);

    out += s.decl("hh", s.min(width, s.dbl(d.lambda) + " * r"));  // compact kernel
  } else {
    out += s.decl("hh", width);
  }
  if (a.flat) {
    const double l = d.squared ? a.flat->left * a.flat->left : a.flat->left;
    const double rr = d.squared ? a.flat->right * a.flat->right : a.flat->right;
    out += "  if (x - hh > " + s.dbl(a.flat->beyond) + ") " + ret(s.dbl(rr)) +
           "  // flat to machine precision\n";
    out += "  if (x + hh < " + s.dbl(-a.flat->beyond) + ") " + ret(s.dbl(l)) + "\n";
  }
  std::string rho;
  if (has_r) rho = "r";
  if (a.scale) rho = rho.empty() ? s.ex(*a.scale) : s.min(rho, s.ex(*a.scale));
  // Taylor series where the difference quotient would cancel (reach: emit_helpers.hpp), in its own
  // function (series_body): C++ evaluates it in a wider type for float, because the coefficients
  // f^(2j)(x) overflow float near a singularity (log: 11!/x^12 at x = 1e-3).
  // GLSL has no wider type: below x ~ 1e-18 the difference quotient's (x +- hh)^2 and hh^2
  // underflow float (0/0), so a singularity-at-0 atomic takes the scaled series there too
  // (hh <= x/2, t^2 <= 1/4: the 7 terms leave < 1e-5 relative, inv2 box ~8e-5).
  const bool tiny_series = !s.cpp() && singular_only_at_zero(a);
  out += "  if (hh <= " + s.helper(s.cpp() ? "series_reach<T>" : "series_reach") + "() * " + rho +
         (tiny_series ? " || x < 1e-18" : "") + ") {\n";
  if (s.cpp())
    out += "    using W = detail::wide_t<T>;\n    " + ret("T(" + impl_name(d) + "_series<W>(W(x), W(hh)))") +
           "\n  }\n";
  else
    out += "    " + ret(s.fn(impl_name(d) + "_series") + "(x, hh)") + "\n  }\n";
  // The difference quotient, in its own function (diff_body). Next to a periodic pole its argument
  // (pi - 2x for tan) loses digits: C++ evaluates it there in long double (11 more bits on x86),
  // with hh as computed above, so the compact half-width is the same in every precision.
  if (s.cpp() && a.period && has_r)
    out += "  if constexpr (sizeof(T) == sizeof(double)) {\n    if (r < T(1e-3)) " +
           ret("T(" + impl_name(d) + "_diff<long double>((long double)x, (long double)hh))") + "\n  }\n";
  // A tent's second difference of F2 (~ x^2 growth) over hh^2 overflows float once hh^2 does
  // (sigma ~ 1e19), and a box's F may square its argument (atan's log(1 + x^2) at |x| ~ 1e19): C++
  // takes the difference in double there.
  if (s.cpp() && (d.kernel == Kernel::Tent || d.kernel == Kernel::Box))
    out += "  if constexpr (sizeof(T) < sizeof(double)) {\n    if (hh > T(1e15)) " +
           ret("T(" + impl_name(d) + "_diff<double>(double(x), double(hh)))") + "\n  }\n";
  out += "  " + ret(s.fn(impl_name(d) + "_diff") + "(x, hh)") + "\n";

  return out;
}

// E[U g(x+U)] for a periodic g: Stein's identity sigma^2 E[g'(x+U)] on the termwise-differentiated
// Fourier series when sigma/T is large, the runtime's image sums otherwise.
std::string body_first_moment(const Derived& d, const Syntax& s) {
  const size_t n = d.pieces.size();
  std::string out = piece_table(s, "p", d.pieces) + s.decl("period", s.ex(d.period)) + guard_sigma(s);
  out += "  if (sigma == " + s.dbl(0) + ") return " + s.dbl(0) + ";\n";
  if (d.kernel == Kernel::Box || d.kernel == Kernel::Tent) {
    const std::string fn = d.kernel == Kernel::Box ? "box_periodic_u" : "tent_periodic_u";
    if (!s.cpp())
      return out + "  return " + s.helper(fn) + "(x, sigma, period, " + pieces_arg(s, "p", n) + ");\n";
    // C++: the period data (mean removal, moments) once per entry, not per call.
    return out + "  static const detail::UPeriodData<T, " + std::to_string(n) +
           "> data = detail::u_period_data(period, p);\n  return " + s.helper(fn) +
           "(x, sigma, period, data);\n";
  }
  // Stein: sigma^2 E[g'(x+U)], g' from the termwise-differentiated series; +2 terms for its k factor.
  std::string terms;
  if (!d.bk.is_zero()) terms = s.ex(d.bk) + " * cos(th)";
  if (!d.ak.is_zero()) terms += (terms.empty() ? "-" : " - ") + s.ex(d.ak) + " * sin(th)";
  out += fourier_branch(d, s, 2, s.dbl(0), "damp * w * (" + (terms.empty() ? s.dbl(0) : terms) + ")",
                        "sigma * sigma * acc");
  const std::string fm = s.dbl(d.fmax);
  return out + "  return " + s.helper("gauss_periodic_u_image") + "(x, sigma, period, " +
         pieces_arg(s, "p", n) + ", " + fm + ");\n";
}

// The half-line companion E[f(x+U) 1{x+U >= 0}] of a periodic entry (not squared): 0 where the
// kernel lies left of 0, the entry itself where it lies right of 0 (Gaussian: beyond the image-sum
// window, whose neglected mass is below the tolerance), else the runtime's *_periodic_right.
std::string body_right(const Derived& d, const Syntax& s) {
  const size_t n = d.pieces.size();
  std::string out = piece_table(s, "p", d.pieces);
  if (d.kernel != Kernel::Gaussian) out += piece_table(s, "p1", d.P1);
  if (d.kernel == Kernel::Tent) out += piece_table(s, "p2", d.P2);
  out += s.decl("period", s.ex(d.period));
  out += guard_sigma(s);
  out += "  if (sigma == " + s.dbl(0) + ") return x < " + s.dbl(0) + " ? " + s.dbl(0) + " : " +
         s.helper("periodic_eval") + "(x, period, " + pieces_arg(s, "p", n) + ");\n";
  const std::string whole = s.fn(impl_name(d)) + "(x, sigma)";
  if (d.kernel == Kernel::Gaussian) {
    const std::string tol = s.cpp() ? "detail::series_tol<T>()" : "BL_SERIES_TOL";
    out += s.decl("R", s.helper("image_z") + "(" + s.dbl(d.fmax) + ", " + tol + ") * sigma");
    out += "  if (x - R >= " + s.dbl(0) + ") return " + whole + ";\n";
    out += "  if (x + R < " + s.dbl(0) + ") return " + s.dbl(0) + ";\n";
    // Boundary-series coefficients scaled to O(1): half_series[m] (2 pi / T)^(m+1).
    std::string cs;
    const GiNaC::ex scale = 2 * GiNaC::Pi / d.period;
    for (size_t m = 0; m < d.half_series.size(); ++m) {
      const double v =
          GiNaC::ex_to<GiNaC::numeric>((d.half_series[m] * pow(scale, static_cast<int>(m + 1))).evalf())
              .to_double();
      cs += (m ? ", " : "") + s.dbl(v);
    }
    const std::string nc = std::to_string(d.half_series.size());
    out += s.cpp() ? "  const T cs[" + nc + "] = {" + cs + "};\n"
                   : "  float cs[" + nc + "] = float[" + nc + "](" + cs + ");\n";
    return out + "  return " + s.helper("gauss_periodic_right") + "(x, sigma, period, " +
           pieces_arg(s, "p", n) + ", " + s.dbl(d.fmax) + ", " + s.dbl(d.coef_bound) + ", " + s.ex(d.a0) +
           ", " + (s.cpp() ? "cs" : nc + ", cs") + ");\n";
  }
  const bool box = d.kernel == Kernel::Box;
  out += s.decl("hw", (box ? (s.cpp() ? "detail::k_sqrt3<T>()" : "BL_SQRT3")
                           : (s.cpp() ? "detail::k_sqrt6<T>()" : "BL_SQRT6")) +
                          std::string(" * sigma"));
  out += "  if (x - hw >= " + s.dbl(0) + ") return " + whole + ";\n";
  out += "  if (x + hw <= " + s.dbl(0) + ") return " + s.dbl(0) + ";\n";
  return out + "  return " + s.helper(box ? "box_periodic_right" : "tent_periodic_right") +
         "(x, hw, period, " + pieces_arg(s, "p", n) + ", p1" + (box ? "" : ", p2") + ");\n";
}

}  // namespace

std::string body_half_line(const Derived& d, Lang lang) {
  const Syntax s{lang};
  return (s.cpp() ? "  BL_MATH_USING\n" : "") + body_right(d, s);
}

std::string diff_body(const Derived& d, Lang lang) {
  const Syntax s{lang};
  const symbol& x = sym::var_x();
  const GiNaC::ex hh = sym::var_hh();
  std::string out = s.cpp() ? "  BL_MATH_USING\n" : "";
  // The polynomial part P of F has an exact difference quotient (expanded symbolically, nothing
  // cancels at run time); only the rest R is differenced numerically.
  GiNaC::ex P = 0, R = 0;
  const GiNaC::ex Fx = d.F_any.expand();
  const GiNaC::ex Fterms = is_a<GiNaC::add>(Fx) ? Fx : GiNaC::ex(GiNaC::lst{Fx});
  for (size_t i = 0; i < Fterms.nops(); ++i) {
    const GiNaC::ex t = Fterms.op(i);
    if (t.is_polynomial(x))
      P += t;
    else
      R += t;
  }
  GiNaC::ex dP;
  if (d.kernel == Kernel::Box)
    dP = ((P.subs(x == x + hh) - P.subs(x == x - hh)) / (2 * hh)).expand().normal().expand();
  else
    dP = ((P.subs(x == x + hh) - 2 * P + P.subs(x == x - hh)) / (hh * hh)).expand().normal().expand();
  std::string rest;
  if (!R.is_zero()) {
    const GiNaC::ex Rp = R.subs(x == x + hh), Rm = R.subs(x == x - hh);
    if (d.kernel == Kernel::Box)
      rest = "(" + s.ex(Rp) + " - " + s.ex(Rm) + ") / (" + s.dbl(2) + " * hh)";
    else
      rest = "(" + s.ex(Rp) + " - " + s.dbl(2) + " * " + s.ex(R) + " + " + s.ex(Rm) + ") / (hh * hh)";
  }
  std::string value = dP.is_zero() ? std::string() : s.ex(dP);
  if (!rest.empty()) value += (value.empty() ? "" : " + ") + rest;
  if (value.empty()) value = s.dbl(0);
  out += "  return " + value + ";\n";
  return out;
}

std::string series_body(const Derived& d, Lang lang) {
  const Syntax s{lang};
  std::map<std::string, std::pair<GiNaC::symbol, GiNaC::ex>> calls;
  std::vector<GiNaC::ex> terms;
  // A non-periodic atomic whose only singularity is 0 (log, sqrt, inv, inv2; x >= 0 here after the
  // parity and domain reductions): f^(2j)(x) hh^2j = [f^(2j)(x) x^2j] (hh/x)^2j, and the bracket
  // simplifies to a bounded expression (c sqrt(x), c, c/x, ...). Evaluating the series in t = hh/x
  // keeps float in range: the unscaled coefficients overflow float near 0 (1/x^12 at x = 1e-4) and
  // their products with hh^12 underflow, giving inf * 0 = NaN in GLSL (which has no wider type).
  const sym::Atomic* a = d.atomic;
  const bool scaled = a && singular_only_at_zero(*a);
  const GiNaC::symbol& x = sym::var_x();
  for (std::size_t j = 0; j < d.series.size(); ++j) {
    const GiNaC::ex t =
        scaled ? (d.series[j] * GiNaC::pow(x, 2 * static_cast<int>(j))).expand() : d.series[j];
    terms.push_back(cse_calls(t, calls));
  }
  std::string out = s.cpp() ? "  BL_MATH_USING\n" : "";
  out += "  if (hh == " + s.dbl(0) + ") return " + s.ex(d.f_here) + ";  // no smoothing: f(x)\n";
  for (auto& [name, sc] : calls) out += s.decl(sc.first.get_name(), s.ex(sc.second));
  out += s.decl("q", scaled ? "(hh / x) * (hh / x)" : "hh * hh");
  std::string horner = s.ex(terms.back());
  for (int j = static_cast<int>(terms.size()) - 2; j >= 0; --j)
    horner = s.ex(terms[j]) + " + q * (" + horner + ")";
  return out + "  return " + horner + ";\n";
}

std::string body_u(const Derived& d, Lang lang) {
  const Syntax s{lang};
  return (s.cpp() ? "  BL_MATH_USING\n" : "") + body_first_moment(d, s);
}

std::string range_clamp(const Derived& d, Lang lang) {
  const Syntax s{lang};
  if (d.rule != "convolution" || !d.atomic) return "";
  const sym::Atomic& a = *d.atomic;
  std::optional<GiNaC::ex> lo, hi;
  if (a.range_lo.finite()) lo = a.range_lo.value;
  if (a.range_hi.finite()) hi = a.range_hi.value;
  if (d.squared) {
    auto num = [](const GiNaC::ex& e) { return GiNaC::ex_to<GiNaC::numeric>(e.evalf()).to_double(); };
    const bool nonneg = lo && num(*lo) >= 0, nonpos = hi && num(*hi) <= 0;
    std::optional<GiNaC::ex> l2, h2;
    if (nonneg) {
      l2 = GiNaC::pow(*lo, 2);
      if (hi) h2 = GiNaC::pow(*hi, 2);
    } else if (nonpos) {
      l2 = GiNaC::pow(*hi, 2);
      if (lo) h2 = GiNaC::pow(*lo, 2);
    } else {
      l2 = GiNaC::ex(0);
      if (lo && hi) {
        const GiNaC::ex l = GiNaC::pow(*lo, 2), h = GiNaC::pow(*hi, 2);
        h2 = GiNaC::ex_to<GiNaC::numeric>(l.evalf()) > GiNaC::ex_to<GiNaC::numeric>(h.evalf()) ? l : h;
      }
    }
    lo = l2;
    hi = h2;
  }
  if (!lo && !hi) return "";
  // A bound that is not a number (-exp(-1) for x e^x) is a static constant in C++: compilers do
  // not fold expf/exp of a constant here, and the call cost 15% of tent/xexp.
  std::string out;
  auto bound = [&](const GiNaC::ex& e, const char* name) {
    if (!s.cpp() || GiNaC::is_a<GiNaC::numeric>(e)) return s.ex(e);
    out += std::string("  static const T ") + name + " = " + s.ex(e) + ";\n";
    return std::string(name);
  };
  const std::string lo_s = lo ? bound(*lo, "lo") : "", hi_s = hi ? bound(*hi, "hi") : "";
  if (s.cpp()) {  // one expression: compilers make it min/max (NaN passes), the early returns a branch
    std::string v = hi ? "(v > " + hi_s + " ? " + hi_s + " : v)" : "v";
    if (lo) v = "v < " + lo_s + " ? " + lo_s + " : " + v;
    return out + "  return " + v + ";\n";
  }
  if (lo) out += "  if (v < " + lo_s + ") return " + lo_s + ";\n";
  if (hi) out += "  if (v > " + hi_s + ") return " + hi_s + ";\n";
  return out + "  return v;\n";
}

std::string body(const Derived& d, Lang lang, const std::vector<Derived>* ds) {
  const Syntax s{lang};
  std::string b;
  switch (d.body) {
    case Body::Closed:
      b = body_closed(d, s);
      break;
    case Body::PiecewiseTable:
      b = box_tent_piecewise_narrow(d, lang) + body_piecewise(d, s);
      break;
    case Body::PeriodicTable:
      b = box_tent_periodic_body(d, lang);  // "" where the break form does not apply
      if (b.empty()) b = body_periodic(d, s);
      break;
    case Body::Combination:
      // sigma = 0 is the plain function: the built-in where the catalog names one, since the identity
      // below is off on a measure-zero set (trunc at negative integers) the kernels never see.
      if (d.atomic && !d.atomic->builtin.empty()) {
        const std::string p = s.fn(plain_impl_name(d.atomic->name)) + "(x)";
        b = "  if (sigma == " + s.dbl(0) + ") return " + (d.squared ? p + " * " + p : p) + ";\n";
      }
      // gauss_staircase_near goes where the far sides (the periodic terms alone) do not apply.
      b += box_tent_staircase_narrow(d, lang, ds) + gauss_staircase_narrow(d, lang, ds) +
           body_combination(d, s, ds, gauss_staircase_near(d, lang, ds));
      break;
    case Body::Antiderivative:
      b = body_antiderivative(d, s);
      break;
    case Body::ExpPieceTable:
      b = body_exp_table(d, s);
      break;
  }
  return (s.cpp() ? "  BL_MATH_USING\n" : "") + b;
}

std::string piece_chain(const std::vector<PolyPiece>& ps, const std::string& v, Lang lang) {
  const Syntax s{lang};
  std::string out;
  for (size_t i = 0; i < ps.size(); ++i) {
    std::vector<std::string> cs;
    for (const auto& x : ps[i].c) cs.push_back(x.is_zero() ? std::string() : "(" + s.ex(x) + ")");
    const std::string p = horner(s, cs, v);
    if (i + 1 < ps.size())
      out += "(" + v + " < " + s.bound(ps[i].hi) + " ? " + p + " : ";
    else
      out += p + std::string(ps.size() - 1, ')');
  }
  return out;
}

// f(x - P floor(x/P)) piece by piece on the exact signed remainder r (as periodic_eval: a negative r
// picks its piece against hi - P, so a jump just below a period boundary stays on its side). C++
// reduces without fmod when P is a power of two (exact there).
std::string periodic_straight(const GiNaC::ex& P, const std::vector<std::pair<GiNaC::ex, GiNaC::ex>>& pieces,
                              Lang lang, bool nan_guard, const std::string& arg, const std::string& lead) {
  const Syntax s{lang};
  const GiNaC::symbol r("r"), t("t");
  bool pow2 = false;
  if (GiNaC::is_a<GiNaC::numeric>(P)) {
    const double pd = GiNaC::ex_to<GiNaC::numeric>(P).to_double();
    int e = 0;
    pow2 = pd > 0 && std::frexp(pd, &e) == 0.5;
  }
  const std::string T = s.cpp() ? "const T" : "float";  // GLSL ES: const needs a constant
  const std::string reduce = s.cpp() && pow2 ? s.helper("reduce_signed_pow2") : s.helper("reduce_signed");
  std::string out = "  " + T + " r = " + reduce + "(" + arg + ", " + s.ex(P) + ");\n";
  if (nan_guard) out += "  if (r != r) return r;\n";
  auto f_at = [&](size_t i, const GiNaC::symbol& v) {
    return s.ex(pieces[i].second.subs(sym::var_x() == v));
  };
  out += "  if (!(r < " + s.dbl(0) + ")) {\n";
  for (size_t i = 0; i + 1 < pieces.size(); ++i)
    out += "    if (r < " + s.ex(pieces[i].first) + ") return " + lead + f_at(i, r) + ";\n";
  out += "    return " + lead + f_at(pieces.size() - 1, r) + ";\n  }\n";
  bool uses_x = false;
  for (const auto& pc : pieces) uses_x = uses_x || pc.second.has(sym::var_x());
  if (uses_x) out += "  " + T + " t = r + " + s.ex(P) + ";\n";
  for (size_t i = 0; i + 1 < pieces.size(); ++i)
    out += "  if (r < " + s.ex(pieces[i].first - P) + ") return " + lead + f_at(i, t) + ";\n";
  return out + "  return " + lead + f_at(pieces.size() - 1, t) + ";\n";
}

// A periodic plain function as straight-line code: the plain function is the baseline every ratio
// and MSAA time divides by.
std::string plain_periodic_straight(const sym::Atomic& a, const Syntax& s) {
  std::vector<std::pair<GiNaC::ex, GiNaC::ex>> pieces;
  for (const auto& pc : a.pieces) pieces.emplace_back(pc.hi.value, pc.f);
  return periodic_straight(*a.period, pieces, s.lang, false);
}

std::string plain_body(const sym::Atomic& a, const std::vector<Derived>& ds, Lang lang) {
  const Syntax s{lang};
  std::string pre = s.cpp() ? "  BL_MATH_USING\n" : "";
  switch (a.cls) {
    case sym::AtomicClass::Entire:
    case sym::AtomicClass::Antiderivative:
      return pre + "  return " + s.ex(a.f) + ";\n";
    case sym::AtomicClass::Piecewise: {
      // Straight-line pieces at their own degree (right-continuous at the breaks, as pw_eval):
      // the plain function is the baseline every ratio and MSAA time divides by, so it must cost
      // what a hand-written shader's would, not a generic table walk.
      std::string out = pre;
      for (size_t i = 0; i + 1 < a.pieces.size(); ++i)
        out += "  if (x < " + s.ex(a.pieces[i].hi.value) + ") return " + s.ex(a.pieces[i].f) + ";\n";
      return out + "  return " + s.ex(a.pieces.back().f) + ";\n";
    }
    case sym::AtomicClass::Periodic: {
      const std::vector<PolyPiece> ps = sym::polynomial_pieces(a, false);
      auto call = [&](const std::string& y, const std::string& t) {
        return s.helper("periodic_eval") + "(" + y + ", period, " + pieces_arg(s, t, ps.size()) + ")";
      };
      std::string near;  // at a break float cannot hold: its exact side (see origin_dispatch)
      for (const Derived& d : ds)
        if (d.atomic == &a && !d.squared) {
          near = origin_dispatch(d, s, 0, call);
          break;
        }
      if (near.empty()) return pre + plain_periodic_straight(a, s);
      return pre + piece_table(s, "p", ps) + s.decl("period", s.ex(*a.period)) + near + "  return " +
             call("x", "p") + ";\n";
    }
    case sym::AtomicClass::Combination: {
      // The built-in where the catalog names one (its identity holds only almost everywhere);
      // otherwise the same identity as the smoothed form, with the plain atomics.
      if (!a.builtin.empty())  // C++: std:: for float and double, found by ADL for other types
        return (s.cpp() ? "  using std::" + a.builtin + ";\n" : std::string()) + "  return " + a.builtin +
               "(x);\n";
      for (const Derived& d : ds) {
        if (d.atomic != &a) continue;
        std::string out = pre + "  return " + s.ex(d.poly);
        for (const auto& t : d.terms)
          out += " + " + s.num(t.coeff) + " * " + s.fn(plain_impl_name(t.atomic)) + "(" +
                 (t.arg_sign < 0 ? "-x" : "x") + ")";
        return out + ";\n";
      }
      throw std::runtime_error("combination " + a.name + " was not derived");
    }
  }
  return pre + "  return " + s.nan() + ";\n";
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_file(const std::string& path, const std::string& content) {
  namespace fs = std::filesystem;
  if (fs::exists(path)) {
    try {
      if (read_file(path) == content) return;
    } catch (...) {
    }
  }
  fs::create_directories(fs::path(path).parent_path());
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw std::runtime_error("cannot write " + tmp);
    out << content;
    if (!out) throw std::runtime_error("write failed: " + tmp);
  }
  fs::rename(tmp, path);  // never leave a half-written file
}

}  // namespace bl::rulegen
