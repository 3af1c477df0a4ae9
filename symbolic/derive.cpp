#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "derived.hpp"
#include "exp_poly.hpp"
#include "functions.hpp"
#include "printer.hpp"

namespace bl::sym {
using namespace GiNaC;

const symbol& var_k() {
  static const realsymbol k("kf");
  return k;
}
const symbol& var_pk() {
  static const realsymbol pk("pk");
  return pk;
}
const symbol& var_phase(long p, long q, bool cosine) {
  static std::map<std::tuple<long, long, bool>, realsymbol> cache;
  auto key = std::make_tuple(p, q, cosine);
  auto it = cache.find(key);
  if (it == cache.end())
    it = cache
             .emplace(key, realsymbol(std::string(cosine ? "cph" : "sph") + std::to_string(p) + "_" +
                                      std::to_string(q)))
             .first;
  return it->second;
}
const symbol& var_hh() {
  static const symbol hh("hh");
  return hh;
}

std::string Derived::fn_suffix() const {
  if (rule == "moment") return "moment";
  return atomic_name + (squared ? "_sq" : "");
}
std::string Derived::cpp_name() const {
  return std::string("bl::") + to_string(kernel) + "::" + fn_suffix();
}
std::string Derived::glsl_name() const {
  return std::string("bl_") + to_string(kernel) + "_" + fn_suffix();
}

namespace {

[[noreturn]] void fail(const Atomic& a, const std::string& field, const std::string& msg) {
  throw CatalogError("catalog entry '" + a.name + "', field '" + field + "': " + msg);
}

std::vector<numeric> coefficients(const ex& poly) {
  const symbol& x = var_x();
  const ex p = poly.expand();
  std::vector<numeric> c;
  for (int k = 0; k <= p.degree(x); ++k) {
    const ex ck = p.coeff(x, k);
    if (!is_a<numeric>(ck)) throw std::invalid_argument("non-numeric polynomial coefficient");
    c.push_back(ex_to<numeric>(ck));
  }
  return c;
}

// t^n with t^0 = 1 also for t = 0 (GiNaC leaves 0^0 undefined).
ex ipow(const ex& t, int n) { return n == 0 ? ex(1) : pow(t, n); }

ex from_coefficients(const std::vector<numeric>& c, const ex& t) {
  ex r = 0;
  for (size_t k = 0; k < c.size(); ++k) r += c[k] * ipow(t, static_cast<int>(k));
  return r;
}

// Antiderivative G of q with G(anchor) = value.
std::vector<numeric> integrate(const std::vector<numeric>& q, const ex& anchor, const ex& value) {
  std::vector<numeric> g(q.size() + 1, 0);
  for (size_t k = 0; k < q.size(); ++k) g[k + 1] = q[k] / numeric(static_cast<long>(k + 1));
  const ex at = from_coefficients(g, anchor);
  g[0] = ex_to<numeric>((value - at).expand().evalf().is_zero() ? ex(0) : (value - at).expand());
  return g;
}

}  // namespace

std::vector<PolyPiece> polynomial_pieces(const Atomic& a, bool squared) {
  std::vector<PolyPiece> out;
  for (const Piece& p : a.pieces) {
    const ex f = squared ? pow(p.f, 2).expand() : p.f;
    out.push_back({p.lo, p.hi, coefficients(f)});
  }
  return out;
}

bool has_exp_pieces(const Atomic& a) {
  if (a.cls != AtomicClass::Piecewise) return false;
  for (const Piece& p : a.pieces)
    if (!p.f.expand().is_polynomial(var_x())) return true;
  return false;
}

namespace {

// Terms of one exp-polynomial g on [lo, hi): per rate a, the polynomial q_a with g = sum q_a(x) e^{a x},
// rewritten in s = x - ref as e^{a s} [e^{a ref} q_a(ref + s)].
void append_terms(const ex& g, const Bound& lo, const Bound& hi, std::vector<ExpTermSpec>& out) {
  const symbol& x = var_x();
  const ExpPoly e = ExpPoly::from(g.expand());
  std::map<numeric, ex, std::function<bool(const numeric&, const numeric&)>> by_rate(
      [](const numeric& u, const numeric& v) { return u < v; });
  for (const auto& [k, c] : e.terms()) {
    if (!k.a.is_real() || !c.is_real())
      throw std::invalid_argument("complex exp-polynomial term on an interval");
    auto it = by_rate.find(k.a);
    if (it == by_rate.end()) it = by_rate.emplace(k.a, ex(0)).first;
    it->second += c * pow(x, k.n);
  }
  const ex ref = lo.finite() ? lo.value : (hi.finite() ? hi.value : ex(0));
  const symbol s("s");
  for (const auto& [a, q] : by_rate) {
    const ex qs = (q.subs(x == ref + s) * exp(a * ref)).expand();
    ExpTermSpec t{lo, hi, a, ref, {}};
    for (int k = 0; k <= qs.degree(s); ++k) {
      ex ck = qs.coeff(s, k);
      if (!is_a<numeric>(ck)) ck = ck.evalf();  // e^{a ref}: a float constant
      t.c.push_back(ck);
    }
    out.push_back(t);
  }
}

}  // namespace

std::vector<ExpTermSpec> exp_terms(const Atomic& a, bool squared) {
  std::vector<ExpTermSpec> out;
  for (const Piece& p : a.pieces) append_terms(squared ? pow(p.f, 2) : p.f, p.lo, p.hi, out);
  return out;
}

std::vector<ExpTermSpec> exp_terms_whole_line(const ex& f) {
  std::vector<ExpTermSpec> out;
  Bound lo, hi;
  lo.inf = -1;
  hi.inf = 1;
  append_terms(f, lo, hi, out);
  return out;
}

namespace {

// Continuous antiderivative of whole-line pieces, 0 at the first finite break (Heckbert's
// repeated integration).
std::vector<PolyPiece> integrate_pieces(const std::vector<PolyPiece>& ps) {
  std::vector<PolyPiece> out;
  ex value = 0;
  for (const PolyPiece& p : ps) {
    const ex anchor = p.lo.finite() ? p.lo.value : p.hi.value;
    const ex start = p.lo.finite() ? value : ex(0);
    out.push_back({p.lo, p.hi, integrate(p.c, anchor, start)});
    if (p.hi.finite()) value = from_coefficients(out.back().c, p.hi.value).expand();
  }
  return out;
}

std::string text(const ex& e) { return print(e, Lang::Text); }

std::string bound_text(const Bound& b) { return b.inf ? (b.inf > 0 ? "inf" : "-inf") : text(b.value); }

std::string pieces_text(const std::vector<PolyPiece>& ps, const std::string& var) {
  const symbol t(var);
  std::string s = "{";
  for (size_t i = 0; i < ps.size(); ++i)
    s += (i ? "; " : "") + text(from_coefficients(ps[i].c, t)) + " on [" + bound_text(ps[i].lo) +
         ", " + bound_text(ps[i].hi) + ")";
  return s + "}";
}

// Closed form of the Gaussian convolution of polynomial pieces: with t = x + sigma z,
// q(x + sigma z) = sum_k d_k z^k and  int z^k phi = A_k Phi(z) + B_k(z) phi(z)  by
// J_0 = Phi, J_1 = -phi, J_k = -z^{k-1} phi + (k-1) J_{k-2}.
ex gaussian_closed_form(const std::vector<PolyPiece>& ps) {
  const symbol& x = var_x();
  const ex sig = var_sigma();
  const symbol z("z");
  ex result = 0;
  for (const PolyPiece& p : ps) {
    const ex q = from_coefficients(p.c, x + sig * z).expand();
    const int deg = q.degree(z);
    std::vector<ex> A(deg + 1), B(deg + 1);  // J_k = A_k Phi + B_k phi
    for (int k = 0; k <= deg; ++k) {
      if (k == 0) { A[0] = 1; B[0] = 0; }
      else if (k == 1) { A[1] = 0; B[1] = -1; }
      else { A[k] = (k - 1) * A[k - 2]; B[k] = -pow(z, k - 1) + (k - 1) * B[k - 2]; }
    }
    auto J = [&](const Bound& b) -> ex {
      ex r = 0;
      for (int k = 0; k <= deg; ++k) {
        const ex d = q.coeff(z, k);
        if (b.inf == 1) r += d * A[k];  // Phi(inf) = 1, phi(inf) z^m = 0
        else if (b.inf == -1) continue;
        else {
          const ex zb = (b.value - x) / sig;
          r += d * (A[k] * Phi(zb) + B[k].subs(z == zb) * phi(zb));
        }
      }
      return r;
    };
    result += J(p.hi) - J(p.lo);
  }
  return result;
}

// The exp-polynomial terms as text, for the manifest.
std::string eterms_text(const std::vector<ExpTermSpec>& ts) {
  const symbol s("s");
  std::string out = "{";
  for (size_t i = 0; i < ts.size(); ++i) {
    ex q = 0;
    for (size_t k = 0; k < ts[i].c.size(); ++k) q += ts[i].c[k] * ipow(s, static_cast<int>(k));
    out += (i ? "; " : "") + text(q) + (ts[i].a.is_zero() ? "" : " * exp(" + text(ts[i].a * s) + ")") +
           ", s = x - " + text(ts[i].ref) + " on [" + bound_text(ts[i].lo) + ", " + bound_text(ts[i].hi) +
           ")";
  }
  return out + "}";
}

void derive_exp_table(Kernel k, Derived& d) {
  d.body = Body::ExpPieceTable;
  std::string how;
  switch (k) {
    case Kernel::Gaussian:
      how =
          "sum over terms of e^(a (x - ref) + a^2 sigma^2/2) int q(s) phi((s - s_mu)/sigma)/sigma ds over "
          "the "
          "term's interval, s_mu = x - ref + a sigma^2 (completing the square; truncated-normal moments in "
          "erfcx-scaled form, Laplace tail integrals V_k from the piece ends when s_mu is >= 2 sigma "
          "outside)";
      break;
    case Kernel::Box:
      how =
          "sum over terms of (1/2h) int q(s) e^(a s) ds over the term's interval cap [x-h, x+h], h = sqrt(3) "
          "sigma (incomplete gamma moments from the end where e^(a s) is largest)";
      break;
    case Kernel::Tent:
      how =
          "sum over terms of int q(s) e^(a s) (w - |t - x|)/w^2 over the term's interval cap [x-w, x+w], w = "
          "sqrt(6) sigma (each half by incomplete gamma moments)";
      break;
  }
  d.formula = how + "; terms " + eterms_text(d.eterms);
}

void derive_piecewise(const Atomic& a, Kernel k, bool sq, Derived& d) {
  if (has_exp_pieces(a)) {
    d.eterms = exp_terms(a, sq);
    derive_exp_table(k, d);
    return;
  }
  d.body = Body::PiecewiseTable;
  // Adjacent pieces with the same polynomial merge (abs^2 = x^2, sign^2 = 1 on the whole line).
  for (const PolyPiece& p : polynomial_pieces(a, sq)) {
    if (!d.pieces.empty() && d.pieces.back().c.size() == p.c.size() &&
        std::equal(p.c.begin(), p.c.end(), d.pieces.back().c.begin(),
                   [](const numeric& u, const numeric& v) { return u == v; }))
      d.pieces.back().hi = p.hi;
    else
      d.pieces.push_back(p);
  }
  if (d.pieces.size() == 1) {  // one polynomial on the whole line: an exp-polynomial closed form
    d.body = Body::Closed;
    d.closed = ExpPoly::from(from_coefficients(d.pieces.front().c, var_x())).convolve(k);
    d.formula = text(d.closed);
    d.pieces.clear();
    return;
  }
  if (k == Kernel::Gaussian) {
    d.closed = gaussian_closed_form(d.pieces).expand();
    d.formula = text(d.closed) +
                "  [Phi, phi: standard normal CDF and density]";
    return;
  }
  // Box/tent by repeated integration of the pieces (Heckbert).
  const std::vector<PolyPiece> F = integrate_pieces(d.pieces), F2 = integrate_pieces(F);
  if (k == Kernel::Box)
    d.formula = "(F(x+h) - F(x-h))/(2h), h = sqrt(3) sigma, F = " + pieces_text(F, "t");
  else
    d.formula = "(F2(x+w) - 2 F2(x) + F2(x-w))/w^2, w = sqrt(6) sigma, F2 = " + pieces_text(F2, "t");
}

// e^{-2 pi i k r} for a piece boundary r T, r = p/q rational: 1 (r integer), (-1)^k (r = 1/2), else
// cos(2 pi k p/q) - i sin(2 pi k p/q) through two symbols the Fourier loop defines from the exact
// integer residue (k p) mod q (no large angle is formed), recorded in d.phases.
ex boundary_phase(const Atomic& a, const ex& t, Derived& d) {
  const ex r = (t / *a.period).normal();
  if (!is_a<numeric>(r) || !ex_to<numeric>(r).is_rational())
    fail(a, "pieces",
         "periodic piece boundaries must be rational multiples of the period (for the Fourier form)");
  const numeric rr = ex_to<numeric>(r);
  if (rr.is_integer()) return 1;
  if ((2 * rr).is_integer()) return var_pk();
  const long q = rr.denom().to_long();
  long p = rr.numer().to_long() % q;
  if (p < 0) p += q;
  if (std::find(d.phases.begin(), d.phases.end(), FourierPhase{p, q}) == d.phases.end())
    d.phases.push_back({p, q});
  return var_phase(p, q, true) - I * var_phase(p, q, false);
}

// Continuous antiderivative of one period's pieces, 0 at t = 0.
std::vector<PolyPiece> integrate_period(const std::vector<PolyPiece>& ps) {
  std::vector<PolyPiece> out;
  ex v = 0;
  for (const PolyPiece& p : ps) {
    out.push_back({p.lo, p.hi, integrate(p.c, p.lo.value, v)});
    v = from_coefficients(out.back().c, p.hi.value).expand();
  }
  return out;
}

// The boundary series of the half-line companion f_right(x) = E[f(x+U) 1{x+U >= 0}] (Gaussian):
// with S_1 = f - a0 and S_{j+1} the periodic, mean-free antiderivative of S_j, repeated
// integration by parts of int_0^inf S_1(t) phi_sigma(t - x) dt at t = 0 gives
//   f_right = a0 Phi(z) + sum_{j>=2} (-1)^(j+1) S_j(0) sigma^(1-j) He_{j-2}(z) phi(z),  z = x/sigma
// (the smoothing paper's repeated integration, Appendix C, on a half line). Returns
// (-1)^(m+1) S_{m+2}(0), m = 0..kHalfSeriesTerms-1, exactly (rational pieces).
constexpr int kHalfSeriesTerms = 40;
std::vector<numeric> half_line_series(const std::vector<PolyPiece>& pieces, const ex& T) {
  auto mean_of = [&T](const std::vector<PolyPiece>& ps) {
    const std::vector<PolyPiece> I = integrate_period(ps);
    return (from_coefficients(I.back().c, I.back().hi.value) / T).expand();
  };
  std::vector<PolyPiece> S = pieces;
  const ex a0 = mean_of(S);
  for (PolyPiece& p : S) p.c[0] = ex_to<numeric>((p.c[0] - a0).expand());
  std::vector<numeric> out;
  for (int j = 2; j < 2 + kHalfSeriesTerms; ++j) {
    S = integrate_period(S);
    const ex m = mean_of(S);
    for (PolyPiece& p : S) p.c[0] = ex_to<numeric>((p.c[0] - m).expand());
    const numeric sj0 = S.front().c[0];  // the first piece starts at t = 0
    out.push_back(j % 2 == 1 ? sj0 : -sj0);
  }
  return out;
}

std::string phases_text(const Derived& d) {
  std::string out;
  for (const auto& ph : d.phases) {
    const std::string pq = std::to_string(ph.p) + "_" + std::to_string(ph.q);
    const std::string arg =
        "2 pi ((k " + std::to_string(ph.p) + ") mod " + std::to_string(ph.q) + ")/" + std::to_string(ph.q);
    out += ", cph" + pq + " = cos(" + arg + "), sph" + pq + " = sin(" + arg + ")";
  }
  return out;
}

// First and second integrals over one period, 0 at t = 0 (smoothing paper, Appendix C).
void period_integrals(const std::vector<PolyPiece>& ps, std::vector<PolyPiece>& P1, std::vector<PolyPiece>& P2) {
  ex v1 = 0, v2 = 0;
  for (const PolyPiece& p : ps) {
    auto g1 = integrate(p.c, p.lo.value, v1);
    auto g2 = integrate(g1, p.lo.value, v2);
    P1.push_back({p.lo, p.hi, g1});
    P2.push_back({p.lo, p.hi, g2});
    v1 = from_coefficients(g1, p.hi.value).expand();
    v2 = from_coefficients(g2, p.hi.value).expand();
  }
}

// True when the rational v is exactly a float (24-bit significand, normal exponent range).
bool float_exact(const numeric& v) {
  if (v.is_zero()) return true;
  numeric m = abs(v);
  const numeric two(2);
  int e = 0;
  while (m < numeric(1 << 23) && e < 200) m *= two, ++e;
  while (m >= numeric(1 << 24) && e > -200) m /= two, --e;
  return m.is_integer();
}

// Break origins (Derived::origins): the period's pieces rotated so that inner break j sits at 0.
void break_origins(Derived& d) {
  const ex T = d.period;
  if (!is_a<numeric>(T) || !ex_to<numeric>(T).is_rational()) return;
  const numeric Tn = ex_to<numeric>(T);
  const size_t n = d.pieces.size();
  std::vector<numeric> br;
  for (const PolyPiece& p : d.pieces) {
    if (!is_a<numeric>(p.lo.value) || !ex_to<numeric>(p.lo.value).is_rational()) return;
    br.push_back(ex_to<numeric>(p.lo.value));
  }
  for (size_t j = 1; j < n; ++j) {
    if (float_exact(br[j])) continue;
    Derived::BreakOrigin o;
    o.b = br[j];
    const numeric left = br[j] - br[j - 1], right = (j + 1 < n ? br[j + 1] : Tn) - br[j];
    o.gap = (left < right ? left : right) / 2;
    const symbol& x = var_x();
    for (size_t i = 0; i < n; ++i) {
      const size_t src = (j + i) % n;
      const numeric shift = src >= j ? -br[j] : Tn - br[j];  // new coordinate = old + shift
      const PolyPiece& p = d.pieces[src];
      const numeric hi = src + 1 < n ? br[src + 1] : Tn;
      o.pieces.push_back({Bound{0, br[src] + shift}, Bound{0, hi + shift},
                          coefficients(from_coefficients(p.c, x - shift).expand())});
    }
    period_integrals(o.pieces, o.P1, o.P2);
    d.origins.push_back(std::move(o));
  }
}

void derive_periodic(const Atomic& a, Kernel k, bool sq, Derived& d) {
  d.body = Body::PeriodicTable;
  d.period = *a.period;
  d.pieces = polynomial_pieces(a, sq);
  const ex T = *a.period;
  period_integrals(d.pieces, d.P1, d.P2);
  break_origins(d);
  const double rmax = std::max(std::abs(a.range_lo.to_double()), std::abs(a.range_hi.to_double()));
  if (!std::isfinite(rmax)) fail(a, "range", "a periodic atomic needs a finite range");
  d.fmax = sq ? rmax * rmax : rmax;
  d.coef_bound = 4 * d.fmax;  // |a_k|, |b_k| <= (2/T) int |f| <= 2 max|f|
  if (k == Kernel::Gaussian && !sq) d.half_series = half_line_series(d.pieces, T);
  if (k != Kernel::Gaussian) {
    d.formula = std::string(k == Kernel::Box ? "(F(x+h) - F(x-h))/(2h)" : "(F2(x+w) - 2F2(x) + F2(x-w))/w^2") +
                ", F(x) = q F_p(T) + F_p(x - qT), F2(x) = F_p(T)(T(q-1)q/2 + (x-qT)q) + F_p2(T) q + "
                "F_p2(x - qT), q = floor(x/T), T = " + text(T) + ", F_p = " + pieces_text(d.P1, "t") +
                ", F_p2 = " + pieces_text(d.P2, "t");
    return;
  }
  // Fourier coefficients: c_k = (1/T) int_0^T f e^{b t} dt, b = -2 pi i k / T, by parts:
  // int t^n e^{bt} = e^{bt} sum_j (-1)^j n!/(n-j)! t^{n-j} / b^{j+1}.
  const ex kk = var_k();
  const ex b = -2 * Pi * I * kk / T;
  ex ck = 0, c0 = 0;
  for (const PolyPiece& p : d.pieces) {
    const int n = static_cast<int>(p.c.size()) - 1;
    for (int m = 0; m <= n; ++m) {
      if (p.c[m].is_zero()) continue;
      ex prim_hi = 0, prim_lo = 0;
      for (int j = 0; j <= m; ++j) {
        const ex coef = pow(-1, j) * factorial(m) / factorial(m - j) / pow(b, j + 1);
        prim_hi += coef * ipow(p.hi.value, m - j);
        prim_lo += coef * ipow(p.lo.value, m - j);
      }
      ck +=
          p.c[m] * (boundary_phase(a, p.hi.value, d) * prim_hi - boundary_phase(a, p.lo.value, d) * prim_lo);
      c0 += p.c[m] * (ipow(p.hi.value, m + 1) - ipow(p.lo.value, m + 1)) / (m + 1);
    }
  }
  ck = (ck / T).expand();
  d.a0 = (c0 / T).normal();
  d.ak = (2 * ck.real_part()).normal();
  d.bk = (-2 * ck.imag_part()).normal();
  d.formula = text(d.a0) +
              " + sum_k exp(-2 pi^2 k^2 sigma^2 / T^2) (a_k cos(2 pi k x/T) + b_k sin(2 pi k x/T)), "
              "a_k = " +
              text(d.ak) + ", b_k = " + text(d.bk) + " (pk = (-1)^k" + phases_text(d) + "), T = " + text(T) +
              " [Fourier form for large sigma/T]; image sum over periods of the Gaussian integral of "
              "the pieces " +
              pieces_text(d.pieces, "t") + " [for small sigma/T]";
}

// A B with A periodic and B piecewise with constant pieces whose breaks are multiples of A's period:
// A(t) 1{t in [lo, hi)} = A_right(t - lo) - A_right(t - hi) (A_right = A on t >= 0), A shifted by a
// multiple of its period being A itself; a piece unbounded on both sides contributes A.
CombinationTerm half_lines_term(const numeric& c, int xpow,
                                const std::vector<std::pair<std::string, int>>& used,
                                std::map<std::string, std::pair<std::string, int>>& calls, const Catalog& cat,
                                const std::string& no_rule) {
  const Atomic* A = nullptr;
  const Atomic* B = nullptr;
  int degB = 0;
  for (const auto& [sym, deg] : used) {
    const Atomic* at = cat.find(calls[sym].first);
    if (calls[sym].second < 0) throw std::invalid_argument("the term " + no_rule);
    if (at->cls == AtomicClass::Periodic && deg == 1 && !A)
      A = at;
    else if (at->cls == AtomicClass::Piecewise && !B) {
      B = at;
      degB = deg;
    } else
      throw std::invalid_argument("the term " + no_rule);
  }
  if (!A || !B || xpow != 0) throw std::invalid_argument("the term " + no_rule);
  CombinationTerm term{c, A->name, 1, 0, false};
  term.kind = CombinationTerm::Kind::HalfLines;
  term.factor = B->name;
  std::map<std::string, std::pair<numeric, ex>> right;  // by the break's text (deterministic)
  for (const Piece& p : B->pieces) {
    const ex v = pow(p.f, degB).expand();
    if (!is_a<numeric>(v))
      throw std::invalid_argument("the term " + no_rule + " (" + B->name + " is not piecewise constant)");
    const numeric val = ex_to<numeric>(v);
    if (val.is_zero()) continue;
    for (const Bound* e : {&p.lo, &p.hi}) {
      if (!e->finite()) continue;
      const ex r = (e->value / *A->period).normal();
      if (!is_a<numeric>(r) || !ex_to<numeric>(r).is_integer())
        throw std::invalid_argument("the term " + no_rule + " (a break of " + B->name +
                                    " is not a multiple of the period)");
      auto& slot = right.emplace(text(e->value), std::make_pair(numeric(0), e->value)).first->second;
      slot.first += e == &p.lo ? val : -val;
    }
    if (!p.lo.finite()) term.full += val;  // (-inf, hi): A - A_right(. - hi)
  }
  for (auto& [key, cb] : right)
    if (!cb.first.is_zero()) term.right.push_back(cb);
  return term;
}

void derive_combination(const Atomic& a, Kernel k, bool sq, const Catalog& cat, Derived& d) {
  d.body = Body::Combination;
  // Replace atomic(x) / atomic(-x) by symbols, then require a linear combination of them.
  std::string s = a.of;
  std::map<std::string, std::pair<std::string, int>> calls;
  std::regex call("([a-z][a-z0-9_]*)\\(\\s*(-?)\\s*x\\s*\\)");
  std::smatch m;
  std::string rest = s, rebuilt;
  while (std::regex_search(rest, m, call)) {
    const std::string name = m[1];
    if (name == "sin" || name == "cos" || name == "exp") {  // GiNaC's own
      rebuilt += m.prefix().str() + m[0].str();
    } else {
      const Atomic* other = cat.find(name);
      if (!other) fail(a, "of", "unknown atomic '" + name + "'");
      if (other->cls == AtomicClass::Combination) fail(a, "of", "combinations of combinations are not supported");
      const std::string sym = "A_" + name + (m[2].length() ? "_neg" : "_pos");
      calls[sym] = {name, m[2].length() ? -1 : 1};
      rebuilt += m.prefix().str() + sym;
    }
    rest = m.suffix();
  }
  rebuilt += rest;
  symtab table;
  table["x"] = var_x();
  std::map<std::string, symbol> syms;
  for (auto& [n, c] : calls) {
    syms.emplace(n, symbol(n));
    table[n] = syms.at(n);
  }
  ex e;
  try {
    parser reader(table, true);
    e = reader(rebuilt).expand();
  } catch (const std::exception& ex_) {
    fail(a, "of", std::string("cannot parse: ") + ex_.what());
  }
  {  // a real identity: at an irrational point (atomics replaced by irrational values) it is real
    exmap at{{var_x(), sqrt(ex(2)) / 3}};
    for (auto& [n, sym] : syms) at[sym] = sqrt(ex(3)) / 5;
    const ex v = e.subs(at).evalf();
    if (!is_a<numeric>(v) || !ex_to<numeric>(v).is_real()) fail(a, "of", "not a real linear identity in x and atomics");
  }
  if (sq) e = pow(e, 2).expand();
  // Sort the monomials: polynomial part, c A(+-x), c x A(+-x) (A periodic), c A(+-x)^2.
  ex poly = 0;
  std::vector<std::pair<std::string, ex>> monomials;  // sorted by text: GiNaC's order varies by run
  if (is_a<GiNaC::add>(e))
    for (size_t i = 0; i < e.nops(); ++i) monomials.push_back({text(e.op(i)), e.op(i)});
  else
    monomials.push_back({text(e), e});
  std::sort(monomials.begin(), monomials.end(),
            [](const auto& p, const auto& q) { return p.first < q.first; });
  for (const auto& [key, t] : monomials) {
    std::vector<std::pair<std::string, int>> used;
    ex rest = t;
    for (auto& [n, sym] : syms) {
      const int deg = t.degree(sym);
      if (deg > 0) used.push_back({n, deg});
      rest = rest.subs(sym == 1);
    }
    if (used.empty()) {
      poly += t;
      continue;
    }
    const int xpow = rest.degree(var_x());
    const ex c = (rest / pow(var_x(), xpow)).expand();
    const std::string what = text(t);
    const std::string supported =
        " has no rule (supported: A, A^2, x A with A periodic, x^n A^d with A piecewise, A B with A periodic "
        "and B piecewise constant with breaks at multiples of the period)";
    if (!is_a<numeric>(c) || !rest.is_polynomial(var_x()) || (rest - c * pow(var_x(), xpow)).expand() != 0)
      throw std::invalid_argument("coefficient of " + what + " is not c x^n");
    if (used.size() > 2) throw std::invalid_argument("the product " + what + supported);
    if (used.size() == 2) {
      d.terms.push_back(half_lines_term(ex_to<numeric>(c), xpow, used, calls, cat, what + supported));
      continue;
    }
    const auto& [n, deg] = used.front();
    const Atomic* other = cat.find(calls[n].first);
    if (other->cls == AtomicClass::Piecewise && xpow > 0) {
      // x^n A(x)^d, A piecewise: again whole-line polynomial pieces.
      if (calls[n].second < 0) throw std::invalid_argument("the term " + what + supported);
      CombinationTerm term{ex_to<numeric>(c), calls[n].first, calls[n].second, xpow, false};
      term.kind = CombinationTerm::Kind::Pieces;
      for (const Piece& p : other->pieces) {
        const ex q = (pow(var_x(), xpow) * pow(p.f, deg)).expand();
        if (q.degree(var_x()) > 7)
          throw std::invalid_argument("the term " + what + " has degree > 7 on a piece");
        term.pieces.push_back({p.lo, p.hi, coefficients(q)});
      }
      d.terms.push_back(term);
      continue;
    }
    if (deg > 2 || (deg == 2 && xpow > 0) || xpow > 1 || (xpow == 1 && other->cls != AtomicClass::Periodic))
      throw std::invalid_argument("the term " + what + supported);
    d.terms.push_back({ex_to<numeric>(c), calls[n].first, calls[n].second, xpow, deg == 2});
    if (xpow == 1) d.terms.back().kind = CombinationTerm::Kind::FirstMoment;
  }
  // GiNaC's term order depends on the run: sort so the emitted code does not.
  std::sort(d.terms.begin(), d.terms.end(), [](const CombinationTerm& p, const CombinationTerm& q) {
    return std::make_tuple(p.atomic, p.factor, p.arg_sign, p.xpow, p.squared) <
           std::make_tuple(q.atomic, q.factor, q.arg_sign, q.xpow, q.squared);
  });
  d.poly = poly;
  try {
    d.closed = ExpPoly::from(poly).convolve(k);
  } catch (const std::exception& ex_) {
    fail(a, "of", ex_.what());
  }
  std::string f = text(d.closed);
  for (auto& t : d.terms) {
    const std::string arg = t.arg_sign < 0 ? "-x" : "x";
    f += " + " + text(t.coeff) + " * ";
    if (t.kind == CombinationTerm::Kind::Pieces) {
      f += "(" + std::string(t.xpow == 1 ? "x" : "x^" + std::to_string(t.xpow)) + " " + t.atomic +
           ")~(x) [pieces " + pieces_text(t.pieces, "t");
      if (k == Kernel::Gaussian) f += " = " + text(gaussian_closed_form(t.pieces).expand());
      f += "]";
    } else if (t.kind == CombinationTerm::Kind::HalfLines) {
      f += "(" + t.atomic + " " + t.factor + ")~(x) [=";
      std::string parts;
      if (!t.full.is_zero()) parts += " " + text(t.full) + " * " + t.atomic + "~(x)";
      for (const auto& [rc, b] : t.right)
        parts += std::string(parts.empty() ? " " : " + ") + text(rc) + " * " + t.atomic + "_right~(x - " +
                 text(b) + ")";
      f += parts + ", " + t.atomic + "_right(x) = " + t.atomic + "(x) 1{x >= 0}]";
    } else if (t.squared)
      f += "(" + t.atomic + "^2)~(" + arg + ")";
    else if (t.xpow == 1)
      f += "(x " + t.atomic + ")~(" + arg + ") [= x " + t.atomic + "~(" + arg + ")" + (t.arg_sign < 0 ? " - " : " + ") +
           "E[U " + t.atomic + "(" + arg + "+U)]]";
    else
      f += t.atomic + "~(" + arg + ")";
  }
  d.formula = f + "  [~: the same kernel's smoothed atomic]";
}

void derive_antiderivative(const Atomic& a, Kernel k, bool sq, Derived& d) {
  d.body = Body::Antiderivative;
  const symbol& x = var_x();
  const ex hh = var_hh();
  d.f_here = sq ? pow(a.f, 2) : a.f;
  d.F_any = k == Kernel::Box ? (sq ? a.F_sq : a.F) : (sq ? a.F2_sq : a.F2);
  // Taylor series in the half-width: E[f(x+U)] = sum_j f^(2j)(x) E[U^2j] / (2j)!, with
  // E[U^2j] = hh^2j/(2j+1) (box) and 2 hh^2j/((2j+1)(2j+2)) (tent).
  ex deriv = d.f_here;
  for (int j = 0; j <= 6; ++j) {
    const numeric mom = k == Kernel::Box ? numeric(1, 2 * j + 1) : numeric(2, (2 * j + 1) * (2 * j + 2));
    d.series.push_back((deriv * mom / factorial(2 * j)).normal());
    deriv = deriv.diff(x, 2);
  }
  const std::string F = text(d.F_any);
  if (k == Kernel::Box)
    d.formula = "(F(x+hh) - F(x-hh))/(2 hh), F = " + F;
  else
    d.formula = "(F2(x+hh) - 2 F2(x) + F2(x-hh))/hh^2, F2 = " + F;
  const std::string width = std::string(k == Kernel::Box ? "sqrt(3)" : "sqrt(6)") + " sigma";
  if (a.singular.empty())
    d.formula += ", hh = " + width;
  else
    d.formula += ", hh = min(" + width + ", r/2) with r the distance to the nearest singularity (compact kernel)";
  d.formula += "; Taylor series in hh (7 terms) where the difference cancels (hh <= scale/20 in double, 0.35 scale in float)";
  (void)hh;
}

}  // namespace

std::vector<Derived> derive_all(const Catalog& cat, int max_moment, std::vector<NotDerived>* not_derived) {
  std::vector<Derived> out;
  for (const Atomic& a : cat.atomics) {
    for (Kernel k : kAllKernels) {
      for (bool sq : {false, true}) {
        Derived d;
        d.atomic = &a;
        d.atomic_name = a.name;
        d.kernel = k;
        d.squared = sq;
        switch (a.cls) {
          case AtomicClass::Entire: {
            try {
              ExpPoly f = ExpPoly::from(a.f.expand());
              if (sq) f = f * f;
              // x^n e^{a x} (n > 0, a real != 0): the exp-polynomial terms on the whole line.
              bool power_times_exp = false, complex_rate = false;
              for (const auto& [key, c] : f.terms()) {
                if (key.n > 0 && !key.a.is_zero()) power_times_exp = true;
                if (!key.a.is_real()) complex_rate = true;
              }
              if (power_times_exp && !complex_rate) {
                d.eterms = exp_terms_whole_line(f.to_ex());
                derive_exp_table(k, d);
                break;
              }
              d.body = Body::Closed;
              d.closed = f.convolve(k);
            } catch (const std::invalid_argument& e) {
              fail(a, "f", e.what());
            }
            d.formula = text(d.closed);
            break;
          }
          case AtomicClass::Piecewise: derive_piecewise(a, k, sq, d); break;
          case AtomicClass::Periodic: derive_periodic(a, k, sq, d); break;
          case AtomicClass::Combination:
            try {
              derive_combination(a, k, sq, cat, d);
            } catch (const std::invalid_argument& e) {
              if (!sq) fail(a, "of", e.what());
              if (not_derived) not_derived->push_back({a.name, to_string(k), sq, e.what()});
              continue;
            }
            break;
          case AtomicClass::Antiderivative:
            if (k == Kernel::Gaussian) {
              if (not_derived)
                not_derived->push_back({a.name, to_string(k), sq,
                                        "no closed form: the Gaussian of this atomic comes from the rules "
                                        "(Rule 2 mode fit, Rule 3 Taylor, compact kernels)"});
              continue;
            }
            if (k == Kernel::Tent && (sq ? a.F2_sq : a.F2).is_zero()) {
              if (not_derived)
                not_derived->push_back({a.name, to_string(k), sq,
                                        "the catalog gives no second antiderivative F2 (not elementary)"});
              continue;
            }
            derive_antiderivative(a, k, sq, d);
            break;
        }
        out.push_back(std::move(d));
      }
    }
  }
  for (Kernel k : kAllKernels) {
    for (int n = 0; n <= max_moment; ++n) {
      Derived d;
      d.atomic_name = "moment";
      d.kernel = k;
      d.rule = "moment";
      d.order = n;
      d.body = Body::Closed;
      d.closed = ExpPoly::from(pow(var_x(), n)).convolve(k);
      d.formula = text(d.closed);
      out.push_back(std::move(d));
    }
  }
  return out;
}

}  // namespace bl::sym
