// Box and tent entries by the break decomposition, printed as straight-line C++ or GLSL.
//
// With q_j the polynomial of the piece containing x and, for each break b, e_k the Taylor
// coefficients about b of the jump q_right - q_left (exact here), d = b - x:
//   E f(x+U) = E q_j(x+U) + sum_b J_b,
//   E q_j(x+U) = sum over even k of g_k m_k (g: q_j about x), m_k = E U^k: box h^k/(k+1) (h =
//     sqrt3 sigma), tent 2 w^k/((k+1)(k+2)) (w = sqrt6 sigma); printed as a polynomial in x and
//     sigma^2 with exact coefficients;
//   box:  J_b = (u/2h) P(u),         P(u) = sum_k e_k u^k/(k+1),
//   tent: J_b = (u/w)(|u|/w) Q(u),   Q(u) = sum_k e_k u^k/((k+1)(k+2)),
// u = +L for b right of x (d > 0), -L for b left of it (d <= 0), L = max(halfwidth - |d|, 0) the
// length of the support beyond b: (1/2h) int_b^{x+h} D = (1/2h) sum e_k L^{k+1}/(k+1) on the right,
// -(1/2h) int_{x-h}^b D = -(1/2h) sum e_k (-L)^{k+1}/(-(k+1)) on the left, and the tent's weight
// (w - |t - x|)/w^2 gives the (k+1)(k+2) the same way. Nothing is truncated (compact kernels), L is
// formed from the exact offset d (no difference of rounded ends is divided by the width), so tiny
// sigma is exact to rounding; the terms stay O(max|f|) while the polynomial extension of q_j over the
// support stays O(max|f|), which bounds the width this form is used for.
#include "emit_box_tent_breaks.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "emit_common.hpp"
#include "emit_gauss_periodic.hpp"
#include "emit_syntax.hpp"

namespace bl::rulegen {
namespace {

using GiNaC::numeric;
using sym::Kernel;
using sym::PolyPiece;

// The largest growth of the pieces' polynomial extensions over the support (in units of max|f|) the
// break sum is used for: its terms, and so its rounding, scale with it (float: 32 * 1e-7 << 2e-5).
constexpr double kMaxGrowth = 32;

// Half-width (in periods) up to which a periodic break sum takes only the breaks it can reach.
constexpr double kNearReach = 0.45;

// The break sum's divisor of a jump coefficient e_j: box (j + 1), tent (j + 1)(j + 2).
long jump_den(Kernel k, size_t j) {
  const long a = static_cast<long>(j) + 1;
  return k == Kernel::Box ? a : a * (a + 1);
}

// A kernel's mass past the nearest break at offset d (one break in reach): L, l = max(L, 0) and v =
// l/2h (box) or l/w (tent), the box's mass being v and the tent's v^2/2. `in`: the indent.
std::string nearest_mass(const Syntax& s, bool box, const std::string& in) {
  return in + s.decl("L", "hw - abs(d)") + in + s.decl("l", "L > " + s.dbl(0) + " ? L : " + s.dbl(0)) + in +
         s.decl("v", "l * (" + s.dbl(1) + " / (" + (box ? s.dbl(2) + " * hw" : std::string("hw")) + "))");
}

std::string coef(const Syntax& s, const GiNaC::ex& v) {
  return v.is_zero() ? std::string() : "(" + s.ex(v) + ")";
}

// E[U^(2j)] / sigma^(2j): box 3^j/(2j+1), tent 2 6^j/((2j+1)(2j+2)).
numeric even_moment(Kernel k, int j) {
  const numeric a = k == Kernel::Box ? numeric(3) : numeric(6);
  numeric m = j == 0 ? numeric(1) : a.power(j);
  if (k == Kernel::Box) return m / numeric(2 * j + 1);
  return numeric(2) * m / numeric((2 * j + 1) * (2 * j + 2));
}

// E q(v + U) = sum_n v^n sum_j C(n+2j, 2j) c_{n+2j} m_{2j} s2^j, Horner in v and s2 = sigma^2.
template <class C>
std::string kernel_mean(const Syntax& s, Kernel k, const std::vector<C>& c, const std::string& v) {
  std::vector<std::string> cx;
  for (size_t n = 0; n < c.size(); ++n) {
    std::vector<std::string> cs;
    for (size_t j = 0; n + 2 * j < c.size(); ++j)
      cs.push_back(
          coef(s, (GiNaC::binomial(numeric(static_cast<long>(n + 2 * j)), numeric(static_cast<long>(2 * j))) *
                   GiNaC::ex(c[n + 2 * j]) * even_moment(k, static_cast<int>(j)))
                      .expand()));
    const std::string h = horner(s, cs, "s2");
    cx.push_back(h == s.dbl(0) ? "" : "(" + h + ")");
  }
  return horner(s, cx, v);
}

// Coefficients of p(t + a) from those of p(t), exact.
std::vector<numeric> shifted(const std::vector<numeric>& c, const numeric& a) {
  std::vector<numeric> r(c.size(), 0);
  for (size_t k = 0; k < c.size(); ++k)  // c_k (t + a)^k = c_k sum_m C(k, m) t^m a^(k-m)
    for (size_t m = 0; m <= k; ++m)
      r[m] += c[k] * GiNaC::binomial(numeric(static_cast<long>(k)), numeric(static_cast<long>(m))) *
              (k == m ? numeric(1) : a.power(static_cast<long>(k - m)));
  return r;
}

std::vector<numeric> minus(std::vector<numeric> a, const std::vector<numeric>& b) {
  if (a.size() < b.size()) a.resize(b.size(), 0);
  for (size_t k = 0; k < b.size(); ++k) a[k] -= b[k];
  while (!a.empty() && a.back().is_zero()) a.pop_back();
  return a;
}

double polyval(const std::vector<numeric>& c, double t) {
  double r = 0;
  for (size_t k = c.size(); k-- > 0;) r = r * t + c[k].to_double();
  return r;
}

// The exact value of a double, as a rational.
numeric exact_value(double v) {
  if (v == 0) return 0;
  int e = 0;
  const double m = std::frexp(v, &e);
  const numeric mi(static_cast<long>(std::ldexp(m, 53)));
  return mi * GiNaC::pow(numeric(2), numeric(e - 53));
}

// b = hi + lo in T: hi the rounded value, lo the rest rounded (float's split for float, double's for
// double and wider types); lo is "" when b is exact in both.
std::pair<std::string, std::string> split_text(const Syntax& s, const numeric& b) {
  const double hd = b.to_double(), ld = (b - exact_value(hd)).to_double();
  const double hf = static_cast<float>(hd), lf = static_cast<float>((b - exact_value(hf)).to_double());
  if (ld == 0 && lf == 0) return {s.dbl(hd), ""};
  if (!s.cpp()) return {s.dbl(hf), s.dbl(lf)};
  auto pick = [&](double vf, double vd) {
    return "(sizeof(T) < sizeof(double) ? " + s.dbl(vf) + " : " + s.dbl(vd) + ")";
  };
  return {pick(hf, hd), pick(lf, ld)};
}

// One break of the sum: position B in the reduced coordinate (for r >= 0; B - shift for r < 0),
// on which side of the point it always lies (-1 left, +1 right, 0 decided at run time), and its jump
// polynomial's Taylor coefficients about B.
struct Candidate {
  numeric B;
  int side = 0;
  std::vector<numeric> e;
};

// The statements "const T d<i> = B - r" (exact offset, from B's two-part split; the shifted
// constant when neg).
std::string offset_decl(const Syntax& s, const std::string& name, const numeric& B, const numeric& shift) {
  const auto [h0, l0] = split_text(s, B);
  if (shift.is_zero()) return s.decl(name, l0.empty() ? h0 + " - r" : "(" + h0 + " - r) + " + l0);
  const auto [h1, l1] = split_text(s, B - shift);
  std::string v = "(neg ? " + h1 + " : " + h0 + ") - r";
  if (!l0.empty() || !l1.empty())
    v = "(" + v + ") + (neg ? " + (l1.empty() ? s.dbl(0) : l1) + " : " + (l0.empty() ? s.dbl(0) : l0) + ")";
  return s.decl(name, v);
}

// The jump terms of the candidates: acc += J_b (see the file comment). `hw`: the half-width h or w,
// `ik`: 1/(2h sc) or 1/(w sc), `sc` an exact power of two that keeps ik finite for tiny kernels.
std::string jump_terms(const Syntax& s, Kernel k, const std::vector<Candidate>& cs, const numeric& shift) {
  std::string out;
  for (size_t i = 0; i < cs.size(); ++i) {
    const auto& c = cs[i];
    const std::string n = std::to_string(i);
    std::ostringstream bt;
    bt << c.B;
    out += "  {  // break at " + bt.str() + (shift.is_zero() ? "" : " (r >= 0)") + "\n";
    out += "  " + offset_decl(s, "d", c.B, shift);
    const std::string L = c.side < 0 ? "hw + d" : (c.side > 0 ? "hw - d" : "hw - abs(d)");
    out += "  " + s.decl("L", L);
    out += "  " + s.decl("l", "L > " + s.dbl(0) + " ? L : " + s.dbl(0));
    std::string u = c.side < 0 ? "-l" : (c.side > 0 ? "l" : "(d > " + s.dbl(0) + " ? l : -l)");
    if (c.e.size() > 1) out += "  " + s.decl("u", u);
    std::vector<std::string> pc;
    for (size_t j = 0; j < c.e.size(); ++j) pc.push_back(coef(s, c.e[j] / numeric(jump_den(k, j))));
    const std::string P = horner(s, pc, "u");
    // v = l/(2h) or l/w; the box's u/(2h) = +-v, the tent's (u/w)(l/w) = +-v^2.
    out += "  " + s.decl("v", "l * sc * ik");
    const std::string vk = k == Kernel::Box ? "" : " * v";
    if (c.side != 0)
      out += std::string("    acc ") + (c.side < 0 ? "-" : "+") + "= v" + vk + " * (" + P + ");\n";
    else
      out += "    acc += (d > " + s.dbl(0) + " ? v : -v)" + vk + " * (" + P + ");\n";
    out += "  }\n";
  }
  return out;
}

bool is_pow2(const numeric& T) {
  const double pd = T.to_double();
  int e = 0;
  return pd > 0 && std::frexp(pd, &e) == 0.5 && exact_value(pd) == T;
}

// Wide kernels (support more than ~K periods): Appendix C, the differences of the periodic
// antiderivatives on the reduced argument (support.hpp box_periodic/tent_periodic (b), straight-line
// here). Every term is O(max|f|) or O(A w / T) (A = F_p(T)), so the division by the width loses
// nothing; the rounding of t +- h (eps h) and of the reductions (at most eps T) is divided by 2h.
// by_floor (C++, power-of-two T): n = floor(y / T) and r = y - n T without reduce_period_pow2's fix-up
// of r rounded up to T: at r = T the last piece's antiderivatives give n A + F_p(T) = (n + 1) A + F_p(0)
// (and the same for the second antiderivative), the value the fix-up would give.
std::string wide_regime(const sym::Derived& d, const Syntax& s, bool by_floor = false) {
  const bool box = d.kernel == Kernel::Box;
  std::string out;
  // Power-of-two periods: no fmod (reduce_period_pow2; its rounding for -T < y < 0 is eps T, here
  // divided by a width above K periods).
  const std::string fn =
      is_pow2(GiNaC::ex_to<numeric>(d.period)) ? "detail::reduce_period_pow2" : "detail::reduce_period";
  const std::string iT = s.num(numeric(1) / GiNaC::ex_to<numeric>(d.period));
  auto reduce = [&](const std::string& r, const std::string& q, const std::string& y) {
    if (by_floor)
      return "    const T " + q + " = floor((" + y + ") * " + iT + ");\n    const T " + r + " = (" + y +
             ") - " + q + " * period;\n";
    if (s.cpp())
      return "    T " + q + ";\n    const T " + r + " = " + fn + "(" + y + ", period, " + q + ");\n";
    return "    vec2 " + r + "_q = bl_reduce_period(" + y + ", period);\n    float " + r + " = " + r +
           "_q.x;\n    float " + q + " = " + r + "_q.y;\n";
  };
  out += reduce("r1", "n1", "t - hw") + reduce("r2", "n2", "t + hw");
  const numeric T = GiNaC::ex_to<numeric>(d.period);
  auto at_T = [&](const std::vector<PolyPiece>& P) {
    numeric v = 0, tk = 1;
    for (const auto& c : P.back().c) {
      v += c * tk;
      tk *= T;
    }
    return v;
  };
  if (box) {
    out += "    return ((n2 - n1) * " + s.num(at_T(d.P1)) + " + (" + piece_chain(d.P1, "r2", s.lang) + " - " +
           piece_chain(d.P1, "r1", s.lang) + ")) / (" + s.dbl(2) + " * hw);\n";
    return out;
  }
  // Tent: every term divided by w^2 as it is formed (q^2 and w^2 overflow float past w ~ 1e19).
  out += "  " + s.decl("iw", s.dbl(1) + " / hw");
  out += "  " + s.decl("s1", "n1 * iw") + "  " + s.decl("s2w", "n2 * iw");
  out += "  " + s.decl("g1", "period * s1 * ((n1 - " + s.dbl(1) + ") * iw) * " + s.dbl(0.5));
  out += "  " + s.decl("g2", "period * s2w * ((n2 - " + s.dbl(1) + ") * iw) * " + s.dbl(0.5));
  out += "    return " + s.num(at_T(d.P1)) + " * ((g2 + g1) + (r2 * iw * s2w + r1 * iw * s1)) + " +
         s.num(at_T(d.P2)) + " * iw * (s2w + s1) + ((" + piece_chain(d.P2, "r2", s.lang) + " + " +
         piece_chain(d.P2, "r1", s.lang) + ") - " + s.dbl(2) + " * " + piece_chain(d.P2, "t", s.lang) +
         ") * iw * iw;\n";
  return out;
}

// Kernels past `from` (half-widths, in x units) take the wide regime first, before the general body's
// signed reduction (C++, power-of-two T): t = x - T floor(x / T) in [0, T] and the antiderivatives'
// differences with floor reductions (wide_regime by_floor). Box square and fract, float, sigma ~ 0.3:
// calibrated 3.3 -> 2.4 and 3.2 -> 1.8 ns per call. Rounding: that of t -+ h (eps h) and of the terms,
// divided by 2h (box) or h^2 (tent), h >= from: a few eps for from >= T / 4.
std::string wide_first(const sym::Derived& d, const Syntax& s, const numeric& from) {
  if (!s.cpp() || !GiNaC::is_a<numeric>(d.period) || !is_pow2(GiNaC::ex_to<numeric>(d.period))) return "";
  const std::string k = d.kernel == Kernel::Box ? "detail::k_sqrt3<T>()" : "detail::k_sqrt6<T>()";
  std::string out = "  if (" + k + " * sigma > " + s.num(from) + " && " + k + " * sigma <= " + s.dbl(1e30) +
                    " && abs(x) <= " + s.dbl(1e30) + ") {  // wide, without the signed reduction\n";
  out += "  " + s.decl("hw", k + " * sigma");
  out += "  " +
         s.decl("t", "x - period * floor(x * " + s.num(numeric(1) / GiNaC::ex_to<numeric>(d.period)) + ")");
  return out + wide_regime(d, s, true) + "  }\n";
}

int max_degree(const std::vector<PolyPiece>& ps) {
  int maxdeg = 0;
  for (const auto& p : ps) maxdeg = std::max(maxdeg, static_cast<int>(p.c.size()) - 1);
  return maxdeg;
}

// The piece spacing g = T / m of an entry box_tent_periodic_hot takes (m = 1 or 2 pieces per period,
// starting at the multiples of g, T and g powers of two, a jump at every piece start: else the pieces
// would not alternate with the nearest break's parity), with the jump polynomials about each break
// (q_i(b_i + u) - q_{i-1}(b_i + u), q_{-1}(t) = q_{m-1}(T + t)) in *jumps; nullopt for every other entry.
std::optional<numeric> hot_spacing(const sym::Derived& d,
                                   std::vector<std::vector<numeric>>* jumps = nullptr) {
  if (!GiNaC::is_a<numeric>(d.period)) return std::nullopt;
  const auto& ps = d.pieces;
  const size_t m = ps.size();
  if (m < 1 || m > 2) return std::nullopt;
  const numeric T = GiNaC::ex_to<numeric>(d.period);
  const numeric g = T / numeric(static_cast<long>(m));
  if (!is_pow2(T) || !is_pow2(g)) return std::nullopt;
  for (size_t i = 0; i < m; ++i) {
    if (!GiNaC::is_a<numeric>(ps[i].lo.value) || !GiNaC::is_a<numeric>(ps[i].hi.value)) return std::nullopt;
    if (GiNaC::ex_to<numeric>(ps[i].lo.value) != g * numeric(static_cast<long>(i))) return std::nullopt;
  }
  std::vector<std::vector<numeric>> e(m);
  for (size_t i = 0; i < m; ++i) {
    const numeric b = g * numeric(static_cast<long>(i));
    e[i] = minus(shifted(ps[i].c, b), shifted(ps[i == 0 ? m - 1 : i - 1].c, i == 0 ? T : b));
    if (e[i].empty()) return std::nullopt;
  }
  if (jumps) *jumps = std::move(e);
  return g;
}

// Of those, the two shapes whose pixel-sized path needs no floor: a pulse train (two constant pieces;
// one constant piece has no jump) or one linear piece.
bool floor_free(const sym::Derived& d) {
  const int maxdeg = max_degree(d.pieces);
  return maxdeg == 0 || (d.pieces.size() == 1 && maxdeg == 1);
}

}  // namespace

// Periodic f, pieces q_i on [0, T). The point is reduced to the exact signed remainder r = fmod(x, T)
// in (-T, T) and t = r (r >= 0) or r + T (r < 0) in [0, T] (the rounding of r + T only moves the
// argument of a polynomial, by eps T). The breaks b_i + m T that a support of half-width up to K T
// can meet lie in (-K T, T + K T) (shifted by -T when r < 0): those left of 0 are always left of the
// point, those from T on always right, the interior ones (0 < b_i < T) compared at run time; their
// offsets d = b - r come from b's exact two-part split (a break float cannot hold, 3/10, is still seen
// where it is by a kernel narrower than its rounding) and the same comparisons pick q_j, so the
// piece and the side of every break always agree. Error: absolute, about (number of active terms +
// degree) G max|f| eps, G the growth of the pieces' extensions over K periods (<= kMaxGrowth).
// Wider kernels: wide_regime.
std::string box_tent_periodic_body(const sym::Derived& d, sym::Lang lang) {
  if (d.kernel == Kernel::Gaussian || d.body != sym::Body::PeriodicTable || d.pieces.empty()) return "";
  const Syntax s{lang};
  const auto& ps = d.pieces;
  const size_t N = ps.size();
  if (!GiNaC::is_a<numeric>(d.period)) return "";
  const numeric T = GiNaC::ex_to<numeric>(d.period);
  const double Td = T.to_double();
  for (const auto& p : ps)
    if (!p.lo.finite() || !p.hi.finite() || !GiNaC::is_a<numeric>(p.lo.value.evalf())) return "";
  auto lo_of = [&](size_t i) { return GiNaC::ex_to<numeric>(ps[i].lo.value); };
  auto hi_of = [&](size_t i) { return GiNaC::ex_to<numeric>(ps[i].hi.value); };
  for (size_t i = 0; i < N; ++i)
    if (!GiNaC::is_a<numeric>(ps[i].lo.value) || !GiNaC::is_a<numeric>(ps[i].hi.value)) return "";

  // K: the widest support (in periods, each side) whose polynomial extension grows at most
  // kMaxGrowth times max|f| (fract^2 over [-2, 3]: 9).
  const double fmax = d.fmax > 0 ? d.fmax : 1;
  double K = 0;
  for (double k : {2.0, 1.0, 0.5, 0.25}) {
    double g = 0;
    for (size_t i = 0; i < N; ++i) {
      const double a = lo_of(i).to_double() - k * Td, b = hi_of(i).to_double() + k * Td;
      for (int j = 0; j <= 256; ++j) g = std::max(g, std::fabs(polyval(ps[i].c, a + (b - a) * j / 256.0)));
    }
    if (g <= kMaxGrowth * fmax) {
      K = k;
      break;
    }
  }
  if (K == 0) return "";
  // Each extra period costs a compare and a term per break: no more than needed for half-widths up
  // to 2 (sigma up to 1.15 box, 0.82 tent), the wide regime beyond (triangle, T = 2: K = 1).
  while (K > 0.25 && 0.5 * K * Td >= 2) K *= 0.5;

  // The jumps: at b_0 = 0 between q_{N-1}(T + u) and q_0(u), at b_i = lo_i between q_{i-1} and q_i,
  // each expanded about its break.
  std::vector<std::pair<numeric, std::vector<numeric>>> jumps;  // (b, e)
  for (size_t i = 0; i < N; ++i) {
    const numeric b = i == 0 ? numeric(0) : lo_of(i);
    const std::vector<numeric> right = shifted(ps[i].c, b);
    const std::vector<numeric> left = shifted(ps[i == 0 ? N - 1 : i - 1].c, i == 0 ? T : b);
    const std::vector<numeric> e = minus(right, left);
    if (!e.empty()) jumps.push_back({b, e});
  }
  std::vector<Candidate> cands;
  const numeric Kn = exact_value(K);
  for (long m = -static_cast<long>(std::ceil(K)) - 1; m <= static_cast<long>(std::ceil(K)) + 1; ++m)
    for (const auto& [b, e] : jumps) {
      const numeric B = b + m * T;
      if (!(B > -Kn * T) || !(B < T + Kn * T)) continue;
      cands.push_back({B, B <= 0 ? -1 : (B >= T ? 1 : 0), e});
    }
  std::sort(cands.begin(), cands.end(), [](const Candidate& a, const Candidate& b) { return a.B < b.B; });

  const bool box = d.kernel == Kernel::Box;
  // A pulse train: f constant on each piece, two values (square, pulse30).
  std::vector<numeric> vals;
  bool constant = true;
  for (const auto& p : ps) {
    if (p.c.size() > 1) constant = false;
    const numeric v = p.c.empty() ? numeric(0) : p.c[0];
    if (std::find(vals.begin(), vals.end(), v) == vals.end()) vals.push_back(v);
  }
  const bool pulse_train = constant && vals.size() == 2;
  // A box pulse train past the near reach takes the antiderivatives' difference: its pieces are
  // constants, so the wide regime is a few compares where the break sum up to K periods takes every
  // break (box square: 9; calibrated float at sigma 0.1-1, 9.1 ns against 6.3 for the wide regime),
  // and its rounding, eps (h + T) / 2h, is at most ~2 eps there.
  const double wide_from = box && pulse_train ? std::min(K, kNearReach) : K;

  std::string out;
  out += s.decl("period", s.num(T));
  out += "  if (!(sigma >= " + s.dbl(0) + ")) return " + s.nan() + ";  // sigma < 0 or NaN\n";
  // C++: wide kernels first, without the signed reduction below: from the pixel-sized path's reach
  // where the entry has one (box_tent_periodic_hot), else from the wide regime's start.
  const std::optional<numeric> g_hot = hot_spacing(d);
  out += wide_first(d, s, g_hot && floor_free(d) ? *g_hot / 2 : exact_value(wide_from) * T);
  const std::string reduce =
      s.cpp() && is_pow2(T) ? s.helper("reduce_signed_pow2") : s.helper("reduce_signed");
  out += s.decl("r", reduce + "(x, period)");
  out += std::string("  ") + (s.cpp() ? "const bool" : "bool") + " neg = r < " + s.dbl(0) + ";\n";
  out += s.decl("t", "neg ? r + period : r");
  out += s.decl("hw", (box ? (s.cpp() ? "detail::k_sqrt3<T>()" : "BL_SQRT3")
                           : (s.cpp() ? "detail::k_sqrt6<T>()" : "BL_SQRT6")) +
                          std::string(" * sigma"));
  out += "  if (!(hw <= " + s.dbl(wide_from * Td) + ")) {  // support wider than " +
         std::to_string(wide_from).substr(0, 4) + " periods each side\n" + wide_regime(d, s) + "  }\n";

  // The base: q_j(t + U) in mean, j picked by the interior breaks' offsets.
  const int maxdeg = max_degree(ps);
  if (maxdeg >= 2) out += s.decl("s2", "sigma * sigma");
  std::string base;
  size_t opened = 0;
  for (size_t i = 0; i < N; ++i) {
    const std::string m = kernel_mean(s, d.kernel, ps[i].c, "t");
    if (i + 1 < N) {
      const std::string di = "db" + std::to_string(i + 1);
      out += offset_decl(s, di, lo_of(i + 1), T);
      base += "(" + di + " > " + s.dbl(0) + " ? " + m + " : ";
      ++opened;
    } else {
      base += m + std::string(opened, ')');
    }
  }
  out += "  " + s.T() + " acc = " + base + ";\n";
  out += "  if (sigma == " + s.dbl(0) + ") return acc;\n";
  // Tiny kernels: an exact power-of-two rescale of the offsets keeps 1/(width) finite.
  out += s.decl("sc", "hw < " + s.dbl(1e-30) + " ? " + s.dbl(std::ldexp(1.0, 100)) + " : " + s.dbl(1));
  out += s.decl("ik", s.dbl(1) + " / (" + (box ? s.dbl(2) + " * hw" : std::string("hw")) + " * sc)");
  // Pixel-sized kernels (half-width up to 0.45 periods: box sigma <= 0.26 T, tent 0.18 T) reach only
  // the breaks within (-0.45 T, 1.45 T) of t in [0, T); every other term has L <= -0.05 T, so l = 0 and
  // it adds exactly 0: skipping them changes no value (box square: 3 breaks instead of 9, fract 2 of 5).
  const numeric reach = exact_value(kNearReach) * T;
  std::vector<Candidate> near;
  for (const Candidate& c : cands)
    if (c.B > -reach && c.B < T + reach) near.push_back(c);
  // A pulse train (f constant on each piece, two values a and b: square, pulse30) under a kernel
  // narrower than half the smallest gap between its breaks: at most one break is in reach, the
  // nearest, and past it f takes its other value a + b - acc, so mean = acc + (a + b - 2 acc) F with F
  // the kernel's mass past that break (box l / 2h, tent l^2 / 2w^2, l = max(h - |d|, 0), d its exact
  // offset). One term where the break sum takes every near break (box square: 3); on
  // checkerboard_none's two box squares the compiled frame went 13.9 -> 12.2 ns/px.
  if (pulse_train && near.size() >= 3 && !jumps.empty()) {
    std::vector<double> at;
    for (const auto& j : jumps) at.push_back(j.first.to_double());
    std::sort(at.begin(), at.end());
    double gap = Td - at.back() + at.front();
    for (size_t j = 0; j + 1 < at.size(); ++j) gap = std::min(gap, at[j + 1] - at[j]);
    const double one_reach = std::min(0.5 * gap, kNearReach * Td);
    out += "  if (hw <= " + s.dbl(one_reach) + ") {  // one break in reach, the nearest: a pulse train\n";
    std::string dmin;
    for (size_t j = 0; j < near.size(); ++j) {
      const std::string o = "o" + std::to_string(j);
      out += "  " + offset_decl(s, o, near[j].B, T);
      dmin = j == 0 ? "abs(" + o + ")" : s.min(dmin, "abs(" + o + ")");
    }
    out += "  " + s.decl("ln", "hw - " + dmin);
    out += "  " + s.decl("vn", "(ln > " + s.dbl(0) + " ? ln : " + s.dbl(0) + ") * sc * ik");
    const std::string F = box ? "vn" : "vn * vn * " + s.dbl(0.5);
    out += "    return acc + (" + s.num(vals[0] + vals[1]) + " - " + s.dbl(2) + " * acc) * " + F + ";\n  }\n";
  }
  if (wide_from <= kNearReach) return out + jump_terms(s, d.kernel, near, T) + "  return acc;\n";
  if (near.size() < cands.size() && kNearReach < K)
    out += "  if (hw <= " + s.dbl(kNearReach * Td) + ") {  // only the breaks it reaches\n" +
           jump_terms(s, d.kernel, near, T) + "    return acc;\n  }\n";
  return out + jump_terms(s, d.kernel, cands, T) + "  return acc;\n";
}

// Pixel-sized kernels on a periodic f whose breaks are m = 1 or 2 per period, g = T/m apart with g
// a power of two (fract, square, triangle and their squares): with half-width at most g/2 only the
// nearest break, j g with j = rint(x/g), is in reach, and x = j g + d with d = x - j g exact (x/g
// and j g are exact, Sterbenz for the difference), so the piece and the side of the break come from
// d's sign without a reduction by the period (the general body's fabs, divide, floor and copysign,
// and its compares against every near break). The mean is then the break sum with one term, exact
// like the general body; its rounding is that of l = h - |d| and of the piece's polynomial at
// t = b + d (rounded by eps T for the piece left of b = 0). C++ only: the entry keeps the general
// body out of line (BL_NOINLINE) so this path inlines into the shader; the GLSL keeps one body.
std::string box_tent_periodic_hot(const sym::Derived& d, const std::string& general, const std::string& clamp,
                                  bool* in_range) {
  if (d.kernel == Kernel::Gaussian || d.body != sym::Body::PeriodicTable || d.pieces.empty()) return "";
  const Syntax s{sym::Lang::Cpp};
  const auto& ps = d.pieces;
  const size_t m = ps.size();
  std::vector<std::vector<numeric>> e;  // jump polynomials about each break
  const std::optional<numeric> spacing = hot_spacing(d, &e);
  if (!spacing) return "";
  const numeric T = GiNaC::ex_to<numeric>(d.period), g = *spacing;
  const bool box = d.kernel == Kernel::Box;
  std::string out;
  out += s.decl("hw", std::string(box ? "detail::k_sqrt3<T>()" : "detail::k_sqrt6<T>()") + " * sigma");
  const int maxdeg = max_degree(ps);
  // Two shapes need neither x's piece nor the side of the break (the floor and the blends below):
  // - a pulse train (m = 2: piece 0 on [0, g), piece 1 on [g, T); square): e = x - T rint(x / T) is
  //   exact and in [-g, g]; piece 0 holds x iff e >= 0, the nearest break is dn = min(|e|, g - |e|)
  //   away (exact: g - |e| is Sterbenz when it is the smaller), and piece 0's mass is
  //   1/2 + copysign(1/2 - F, e), F the kernel's mass past that break. Calibrated float, |x| ~ 1,
  //   sigma ~ 0.003: box square 1.99 -> 1.07 ns per call, tent 2.23 -> 1.29. (The box's
  //   clamp(1/2 + copysign(dn, e) / 2h, 0, 1) has fewer operations but measured 1.20: a longer chain.)
  // - one linear piece q(t) = a + b t and one jump per period (fract): q's continuation from the break
  //   nearest x is a + b e everywhere right of it, and left of it the previous period adds b T:
  //   mean = a + b e + b T P(U < -e), for either sign of e (box: P = clamp(1/2 - e / 2h, 0, 1); tent:
  //   P = 1/2 - copysign(1/2 - F, e)). Box fract 1.34 -> 0.91 ns per call (tent: 1.18).
  if (floor_free(d)) {
    const bool pulse = maxdeg == 0;
    const bool scaled_T = T != 1;
    // NaN, sigma <= 0, tiny (1/width past float's range), wide, or x NaN or infinite: general.
    out += "  if (hw >= " + s.dbl(1e-30) + " && hw <= " + s.num(g / 2) + " && abs(x) <= " + s.dbl(1e30) +
           ") {  // one break in reach, the nearest\n";
    const std::string xt = scaled_T ? "x * " + s.num(numeric(1) / T) : "x";
    out += "  " + s.decl("e", scaled_T ? "(" + xt + " - rint(" + xt + ")) * " + s.num(T) : "x - rint(x)");
    std::string val;
    if (pulse) {
      out += "  " + s.decl("ea", "abs(e)");
      out += "  " + s.decl("L", "hw - detail::min2(ea, " + s.num(g) + " - ea)");
      out += "  " + s.decl("v", "detail::max0(L) * (" + s.dbl(1) + " / (" +
                                    (box ? s.dbl(2) + " * hw" : std::string("hw")) + "))");
      const std::string F = box ? "v" : "v * v * " + s.dbl(0.5);
      out += "  " + s.decl("p0", s.dbl(0.5) + " + copysign(" + s.dbl(0.5) + " - " + F + ", e)");
      const numeric c0 = ps[0].c.empty() ? numeric(0) : ps[0].c[0],
                    c1 = ps[1].c.empty() ? numeric(0) : ps[1].c[0];
      val = c0 - c1 == 1 ? std::string("p0") : s.num(c0 - c1) + " * p0";
      if (!c1.is_zero()) val = s.num(c1) + " + " + val;
      // p0 = 1/2 + copysign(1/2 - F, e) with F in [0, 1/2] rounds into [0, 1]: a 0/1 train is in range.
      *in_range = val == "p0";
    } else {
      const numeric a = ps[0].c.empty() ? numeric(0) : ps[0].c[0],
                    b = ps[0].c.size() > 1 ? ps[0].c[1] : numeric(0);
      if (box) {
        out += "  " + s.decl("q", s.dbl(0.5) + " - e * (" + s.dbl(1) + " / (" + s.dbl(2) + " * hw))");
        out += "  " + s.decl("P", "detail::min1(detail::max0(q))");
      } else {
        out += "  " + s.decl("L", "hw - abs(e)");
        out += "  " + s.decl("v", "detail::max0(L) * (" + s.dbl(1) + " / hw)");
        out += "  " +
               s.decl("P", s.dbl(0.5) + " - copysign(" + s.dbl(0.5) + " - v * v * " + s.dbl(0.5) + ", e)");
      }
      val = b == 1 ? std::string("e") : s.num(b) + " * e";
      if (!a.is_zero()) val = s.num(a) + " + " + val;
      val += b * T == 1 ? std::string(" + P") : " + " + s.num(b * T) + " * P";
      // fract: e + P lies in [0, 1] by construction (e >= 0: P <= 1/2 - e / 2h rounds to <= 1/2; e < 0:
      // P <= 1).
      *in_range = a.is_zero() && b == 1 && T == 1;
    }
    out += "    return " + val + ";\n  }\n";
    return out + general_call(general, *in_range ? clamp : "");
  }
  // NaN, sigma <= 0, tiny (1/width past float's range), wide, or |x| where x/g overflows: general.
  const bool scaled = g != 1;
  out += "  if (hw >= " + s.dbl(1e-30) + " && hw <= " + s.num(g / 2) +
         (scaled && g < 1 ? " && abs(x) <= " + s.dbl(1e30) : std::string()) +
         ") {  // one break in reach, the nearest\n";
  const std::string gs = s.num(g);
  // Two independent chains (the entry's latency is what a shader waits for): the piece holding x
  // from k = floor(u), the offset to the nearest break from j = rint(u). They agree: j = k when
  // d >= 0, k + 1 when d < 0.
  out += "  " + s.decl("u", scaled ? "x * " + s.num(numeric(1) / g) : "x");
  out += "  " + s.decl("k", "floor(u)");
  out += "  " + s.decl("j", "rint(u)");
  out += "  " + s.decl("d", scaled ? "(u - j) * " + gs : "u - j");
  out += nearest_mass(s, box, "  ");
  // F: the kernel's mass past the break (box l / 2h, tent l^2 / 2w^2).
  const std::string vk = box ? "" : " * v";
  if (m == 2)
    out += "  " + s.decl("par", "k - " + s.dbl(2) + " * floor(k * " + s.dbl(0.5) + ")");  // x's piece
  if (maxdeg >= 2) out += "  " + s.decl("s2", "sigma * sigma");
  out += "  " + s.decl("t", scaled ? "(u - k) * " + gs : "u - k");  // x's offset into its piece
  // +1: the break right of x (j = k + 1), -1: x at or right of it (j = k); arithmetic, not a compare
  // (a select on the side becomes a branch).
  out += "  " + s.decl("sg", s.dbl(2) + " * (j - k) - " + s.dbl(1));
  auto jump_poly = [&](size_t i) {
    std::vector<std::string> pc;
    for (size_t k = 0; k < e[i].size(); ++k) pc.push_back(coef(s, e[i][k] / numeric(jump_den(d.kernel, k))));
    return horner(s, pc, "w");
  };
  std::string base, P;
  if (m == 1) {
    base = kernel_mean(s, d.kernel, ps[0].c, "t");
    P = jump_poly(0);
  } else {
    // Piece 1 starts at g: its polynomial at g + t.
    out += "  " + s.decl("t1", gs + " + t");
    base = "(par * (" + kernel_mean(s, d.kernel, ps[1].c, "t1") + ") + (" + s.dbl(1) + " - par) * (" +
           kernel_mean(s, d.kernel, ps[0].c, "t") + "))";
    const std::string p0 = jump_poly(0), p1 = jump_poly(1);
    if (p0 == p1) {
      P = p0;
    } else {  // the break's parity: x's piece's own break (d >= 0) or the next one
      out += "  " + s.decl("pj", "par + (j - k) * (" + s.dbl(1) + " - " + s.dbl(2) + " * par)");
      P = "(pj * (" + p1 + ") + (" + s.dbl(1) + " - pj) * (" + p0 + "))";
    }
  }
  if (P.find('w') != std::string::npos) out += "  " + s.decl("w", "sg * l");
  out += "    return " + base + " + sg * v" + vk + " * (" + P + ");\n  }\n";
  return out + general_call(general, "");
}

namespace {

// The polynomial f(x) on [n, n+1) of a staircase combination (floor, ceil, trunc: poly(x) plus
// multiples of fract(+-x) and of piecewise atomics with integer breaks such as step) for the integers
// n of one region (regions: split by the piecewise atomics' breaks z, n < z or n >= z), as an
// expression in x and the symbol n; nullopt when a term is of another kind.
struct Staircase {
  std::vector<long> z;           // region boundaries, sorted
  std::vector<GiNaC::ex> piece;  // per region (z.size() + 1): f on [n, n+1)
};

std::optional<Staircase> staircase_of(const sym::Derived& lin, const std::vector<sym::Derived>& ds,
                                      const GiNaC::symbol& n, bool squared) {
  const GiNaC::ex x = sym::var_x();
  auto atomic = [&](const std::string& name) -> const sym::Atomic* {
    for (const auto& e : ds)
      if (e.atomic && e.atomic_name == name) return e.atomic;
    return nullptr;
  };
  Staircase st;
  for (const auto& t : lin.terms) {
    if (t.kind != sym::CombinationTerm::Kind::Smoothed || t.xpow != 0 || t.squared) return std::nullopt;
    const sym::Atomic* a = atomic(t.atomic);
    if (!a) return std::nullopt;
    if (a->cls == sym::AtomicClass::Piecewise) {
      if (t.arg_sign != 1) return std::nullopt;
      for (size_t i = 0; i + 1 < a->pieces.size(); ++i) {
        const GiNaC::ex b = a->pieces[i].hi.value;
        if (!GiNaC::is_a<numeric>(b) || !GiNaC::ex_to<numeric>(b).is_integer()) return std::nullopt;
        st.z.push_back(GiNaC::ex_to<numeric>(b).to_long());
      }
    } else if (a->cls == sym::AtomicClass::Periodic) {
      if (!a->period || !(*a->period - 1).is_zero() || a->pieces.size() != 1) return std::nullopt;
    } else {
      return std::nullopt;
    }
  }
  std::sort(st.z.begin(), st.z.end());
  st.z.erase(std::unique(st.z.begin(), st.z.end()), st.z.end());
  for (size_t r = 0; r <= st.z.size(); ++r) {
    const long rep = r == 0 ? (st.z.empty() ? 0 : st.z[0] - 1) : st.z[r - 1];  // an n of the region
    GiNaC::ex f = lin.poly;
    for (const auto& t : lin.terms) {
      const sym::Atomic* a = atomic(t.atomic);
      GiNaC::ex v;
      if (a->cls == sym::AtomicClass::Periodic) {
        // fract-like: A(x) = q(x - n) on [n, n+1); A(-x) = q(n + 1 - x) there (x not an integer).
        v = a->pieces[0].f.subs(x == (t.arg_sign > 0 ? x - n : n + 1 - x));
      } else {
        const double mid = rep + 0.5;
        for (const auto& pc : a->pieces)
          if ((!pc.lo.finite() || pc.lo.to_double() < mid) && (!pc.hi.finite() || mid < pc.hi.to_double()))
            v = pc.f;
      }
      f += t.coeff * v;
    }
    if (squared) f = f * f;
    st.piece.push_back(f.expand());
  }
  return st;
}

// The jump f(n+) - f(n-) at the integer n as a polynomial in u = x - n (coefficients in n), printed
// per region: "n < z0 ? e(region 0) : n == z0 ? e(at z0) : ...".
std::string region_chain(const Syntax& s, const Staircase& st, const GiNaC::symbol& n, size_t k) {
  const GiNaC::symbol u("u");
  const GiNaC::ex x = sym::var_x();
  auto coeff_of = [&](const GiNaC::ex& right, const GiNaC::ex& left) {
    const GiNaC::ex D = (right.subs(x == n + u) - left.subs(x == n + u)).expand();
    return D.coeff(u, static_cast<int>(k));
  };
  auto text = [&](const GiNaC::ex& e) { return e.is_zero() ? s.dbl(0) : "(" + s.ex(e) + ")"; };
  std::string out;
  for (size_t r = 0; r < st.z.size(); ++r) {
    const GiNaC::ex inside = coeff_of(st.piece[r], st.piece[r].subs(n == n - 1));
    const GiNaC::ex at = coeff_of(st.piece[r + 1], st.piece[r].subs(n == n - 1)).subs(n == st.z[r]);
    out += "(n < " + s.dbl(static_cast<double>(st.z[r])) + " ? " + text(inside) +
           " : n == " + s.dbl(static_cast<double>(st.z[r])) + " ? " + text(at) + " : ";
  }
  const GiNaC::ex last = coeff_of(st.piece.back(), st.piece.back().subs(n == n - 1));
  return out + text(last) + std::string(st.z.size(), ')');
}

// The combination entry of d's atomic itself (not squared) under d's kernel, whose terms define the
// staircase (floor = x - fract, ...); nullptr when the table has none.
const sym::Derived* linear_combination(const sym::Derived& d, const std::vector<sym::Derived>& ds) {
  const sym::Derived* lin = nullptr;
  for (const auto& e : ds)
    if (e.atomic == d.atomic && !e.squared && e.kernel == d.kernel && e.body == sym::Body::Combination)
      lin = &e;
  return lin;
}

}  // namespace

// Staircases (floor, ceil, trunc, their squares), sigma > 0 (sigma = 0 keeps the plain values at the
// integers, where ceil is not right-continuous). Centred on n0 = floor(x) (exact): the breaks n = n0 +
// j, j in (-K, 1 + K), lie left of x for j <= 0 and right for j >= 1, so no comparison picks a side;
// their offsets n - x are exact near x (y = x - n0 is not: -1e-9 - (-1) rounds to 1 in float, so y
// is only the base polynomial's argument, where its rounding moves the value by eps n0); the base is f's
// polynomial on [n0, n0+1) in y (coefficients in n0: floor^2 is n0^2 there) and each jump's coefficients are
// polynomials in n = n0 + j (floor^2: 2n - 1, trunc^2: 2n - sign(n)), per region of n. Nothing of size x^2 is
// formed as a difference: the result's terms are n0^p times O(1) staircase averages. Error: relative, about
// (K + degree) eps. Wider kernels fall through to the caller's combination of periodic entries.
std::string box_tent_staircase_narrow(const sym::Derived& d, sym::Lang lang,
                                      const std::vector<sym::Derived>* ds) {
  if (d.kernel == Kernel::Gaussian || d.body != sym::Body::Combination || !ds || !d.atomic ||
      !d.atomic->jumps_at_integers)
    return "";
  const sym::Derived* lin = linear_combination(d, *ds);
  if (!lin) return "";
  const GiNaC::symbol n("n"), n0("n0");
  const auto st = staircase_of(*lin, *ds, n, d.squared);
  if (!st) return "";
  const Syntax s{lang};
  const bool box = d.kernel == Kernel::Box;
  // Tent: 3 steps each side (w <= 3, sigma <= 1.22: the whole bench_table range stays here).
  const int K = box ? 2 : 3;
  const GiNaC::ex x = sym::var_x();
  const GiNaC::symbol v("v");
  std::string out = "  {  // narrow kernels: the break sum centred on n0 = floor(x)\n";
  out += "  " + s.decl("hw", (box ? (s.cpp() ? "detail::k_sqrt3<T>()" : "BL_SQRT3")
                                  : (s.cpp() ? "detail::k_sqrt6<T>()" : "BL_SQRT6")) +
                                 std::string(" * sigma"));
  // Base: f(n0 + v) on [n0, n0+1), coefficients in v.
  std::string base;
  bool s2 = false;
  for (size_t r = 0; r <= st->z.size(); ++r) {
    const GiNaC::ex f = st->piece[r].subs(GiNaC::lst{x == n0 + v, n == n0}).expand();
    std::vector<GiNaC::ex> c;
    for (int k = 0; k <= f.degree(v); ++k) c.push_back(f.coeff(v, k));
    s2 = s2 || c.size() > 2;
    const std::string m = kernel_mean(s, d.kernel, c, "y");
    if (r < st->z.size())
      base += "(n0 < " + s.dbl(static_cast<double>(st->z[r])) + " ? " + m + " : ";
    else
      base += m + std::string(st->z.size(), ')');
  }
  int maxdeg = 0;
  for (const auto& p : st->piece) maxdeg = std::max(maxdeg, p.degree(x));
  // P(u) of the break n (its region's jump coefficients, in the local n), Horner in u; the same text
  // for every break; uses_u when P reads u.
  bool uses_u = false;
  const std::string P = [&] {
    std::vector<std::string> pc;
    for (int k = 0; k <= maxdeg; ++k) {
      const std::string e = region_chain(s, *st, n, static_cast<size_t>(k));
      if (e == s.dbl(0)) {
        pc.push_back("");
        continue;
      }
      const long den = jump_den(d.kernel, static_cast<size_t>(k));
      pc.push_back(den == 1 ? e : e + " * " + s.num(numeric(1, den)));
    }
    for (size_t k = 1; k < pc.size(); ++k) uses_u = uses_u || !pc[k].empty();
    return horner(s, pc, "u");
  }();
  if (s.cpp()) {
    // Pixel-sized kernels (half-width <= 1/2): only the nearest integer n = rint(x) is in reach, at
    // the exact offset d = n - x; one term instead of 2K, and no scale for tiny widths (from 1e-30).
    out += "    if (hw >= " + s.dbl(1e-30) + " && hw <= " + s.dbl(0.5) +
           ") {  // one break in reach, the nearest\n";
    out += "    " + s.decl("n0", "floor(x)") + "    " + s.decl("y", "x - n0");
    if (s2) out += "    " + s.decl("s2", "sigma * sigma");
    out += "    " + s.decl("n", "rint(x)") + "    " + s.decl("d", "n - x");
    // +1: n right of x (n = n0 + 1), -1: x at or right of n (n = n0); arithmetic, not a branch.
    out += "    " + s.decl("sg", s.dbl(2) + " * (n - n0) - " + s.dbl(1));
    out += nearest_mass(s, box, "    ");
    if (uses_u) out += "    " + s.decl("u", "sg * l");
    out += "        return " + base + " + sg * " + (box ? "v" : "v * v") + " * (" + P + ");\n    }\n";
    // The general block below declares its own n0, y.
  }
  out += "    if (sigma > " + s.dbl(0) + " && hw <= " + s.dbl(K) + ") {\n";
  out += "    " + s.decl("n0", "floor(x)") + "    " + s.decl("y", "x - n0");
  if (s2) out += "    " + s.decl("s2", "sigma * sigma");
  out += "    " + s.T() + " acc = " + base + ";\n";
  out +=
      "    " + s.decl("sc", "hw < " + s.dbl(1e-30) + " ? " + s.dbl(std::ldexp(1.0, 100)) + " : " + s.dbl(1));
  out += "    " + s.decl("ik", s.dbl(1) + " / (" + (box ? s.dbl(2) + " * hw" : std::string("hw")) + " * sc)");
  for (int j = 1 - K; j <= K; ++j) {
    const std::string J = s.dbl(j);
    out += "      {  // break at n0 + " + std::to_string(j) + "\n";
    out += "      " + s.decl("n", "n0 + " + J) + "      " + s.decl("d", "n - x");
    out += "      " + s.decl("L", j <= 0 ? "hw + d" : "hw - d");
    out += "      " + s.decl("l", "L > " + s.dbl(0) + " ? L : " + s.dbl(0));
    if (uses_u) out += "      " + s.decl("u", j <= 0 ? "-l" : "l");
    // Static sides: u = +-l, the tent's (u/w)(l/w) = +-(l/w)^2.
    out += "      " + s.decl("v", "l * sc * ik");
    out += std::string("        acc ") + (j <= 0 ? "-" : "+") + "= " + (box ? "v" : "v * v") + " * (" + P +
           ");\n";
    out += "      }\n";
  }
  return out + "      return acc;\n    }\n  }\n";
}

// The dropped breaks of a Gaussian staircase break sum: those >= D from x (both sides) sum to <=
// sum_m 2 (Jb + Js (D + m + 1)) Phic((D + m)/sigma), Jb = max |J_n| over n in [-2, 3], Js the
// growth of |J_n| per step (f grows as fast, so the bound is absolute for |x| <= 1 and relative to f
// beyond). reach(D, tol): the largest sigma whose bound stays <= tol.
namespace {
// f on [m, m+1) of a staircase whose pieces are constants in x (NaN when not a number).
double staircase_at(const Staircase& st, const GiNaC::symbol& n, long m) {
  size_t r = 0;
  while (r < st.z.size() && m >= st.z[r]) ++r;
  const GiNaC::ex v = st.piece[r].subs(n == m).evalf();
  return GiNaC::is_a<numeric>(v) ? GiNaC::ex_to<numeric>(v).to_double() : NAN;
}

struct StaircaseTail {
  double Jb = 0, Js = 0;
  bool ok = true;
  StaircaseTail(const Staircase& st, const GiNaC::symbol& n) {
    auto f_at = [&](long m) { return staircase_at(st, n, m); };
    for (long m = -6; m <= 6; ++m) {
      const double J = f_at(m) - f_at(m - 1), Jp = f_at(m - 1) - f_at(m - 2);
      if (!std::isfinite(J) || !std::isfinite(Jp)) ok = false;
      if (m >= -2 && m <= 3) Jb = std::max(Jb, std::fabs(J));
      if (std::isfinite(J - Jp)) Js = std::max(Js, std::fabs(J - Jp));
    }
  }
  double tail(double sig, double D) const {
    double t = 0;
    for (int m = 0; m < 400; ++m) {
      const double term = 2 * (Jb + Js * (D + m + 1)) * 0.5 * std::erfc((D + m) / sig / std::sqrt(2.0));
      t += term;
      if (term < 1e-40) break;
    }
    return t;
  }
  double reach(double D, double tol) const {
    double lo = 1e-6, hi = 4.0;
    for (int it = 0; it < 80; ++it) {
      const double mid = 0.5 * (lo + hi);
      (tail(mid, D) <= tol ? lo : hi) = mid;
    }
    return lo;
  }
};

// The staircase of a Gaussian combination entry whose f is constant on every [n, n+1) (floor, ceil,
// trunc and their squares), in the symbol n; nullopt where the break sums do not apply.
std::optional<Staircase> gauss_constant_staircase(const sym::Derived& d, const std::vector<sym::Derived>* ds,
                                                  const GiNaC::symbol& n) {
  if (d.kernel != Kernel::Gaussian || d.body != sym::Body::Combination || !ds || !d.atomic ||
      !d.atomic->jumps_at_integers)
    return std::nullopt;
  const sym::Derived* lin = linear_combination(d, *ds);
  if (!lin) return std::nullopt;
  auto st = staircase_of(*lin, *ds, n, d.squared);
  if (!st) return std::nullopt;
  const GiNaC::ex x = sym::var_x();
  for (const auto& p : st->piece)
    if (p.degree(x) != 0) return std::nullopt;
  return st;
}

// f on [n0, n0 + 1) (n0 = floor(x)) per region of n0, as a chain of selects.
std::string staircase_base(const Syntax& s, const Staircase& st, const GiNaC::symbol& n,
                           const GiNaC::symbol& n0) {
  std::string base;
  for (size_t r = 0; r <= st.z.size(); ++r) {
    const std::string m = "(" + s.ex(st.piece[r].subs(n == n0).expand()) + ")";
    if (r < st.z.size())
      base += "(n0 < " + s.dbl(static_cast<double>(st.z[r])) + " ? " + m + " : ";
    else
      base += m + std::string(st.z.size(), ')');
  }
  return base;
}

// The break n = n0 + j's term J_n Phic(|n - x| / sigma) into `acc` (left of x for j <= 0).
std::string staircase_break(const Syntax& s, int j, const std::string& J, const std::string& acc) {
  std::string out = "        {  // break at n0 + " + std::to_string(j) + "\n";
  out += "          const T n = n0 + " + s.dbl(j) + ";\n";
  out += "          const T t = detail::min2((" + std::string(j <= 0 ? "x - n" : "n - x") +
         ") * inv, detail::tail_cut<T>());\n";
  out += "          " + acc + (j <= 0 ? " -" : " +") + "= " + J + " * detail::normal_Phic(t);\n";
  return out + "        }\n";
}

// An even staircase f that equals another Gaussian staircase entry g on [0, inf) (trunc^2 = floor^2
// there): E f(x+U) = E f(|x|+U) = g~(|x|) + E h(|x|+U), h = f - g, which is 0 on [0, inf), so all
// its breaks n <= 0 lie left of |x| and E h(|x|+U) = -sum_{n <= 0} J^h_n Phic((|x| - n)/sigma).
struct EvenMirror {
  std::string g_impl;  // g~'s implementation name (impl_name)
  Staircase h;         // f - g
};

std::optional<EvenMirror> even_mirror(const sym::Derived& d, const Staircase& st,
                                      const std::vector<sym::Derived>& ds, const GiNaC::symbol& n) {
  auto at = [&](const Staircase& s, long m) { return staircase_at(s, n, m); };
  for (long m = -8; m <= 8; ++m)  // f on [m, m+1) = f on [-m-1, -m)
    if (!(at(st, m) == at(st, -m - 1))) return std::nullopt;
  for (const auto& e : ds) {
    if (&e == &d || e.kernel != Kernel::Gaussian || e.squared != d.squared || e.atomic == d.atomic) continue;
    const auto g = gauss_constant_staircase(e, &ds, n);
    if (!g || !g->z.empty() || !(g->piece[0] - st.piece.back()).expand().is_zero()) continue;
    EvenMirror mr{impl_name(e), st};
    for (auto& p : mr.h.piece) p = (p - g->piece[0]).expand();
    bool zero_right = true;
    for (long m = 0; m <= 8; ++m) zero_right = zero_right && at(mr.h, m) == 0;
    if (zero_right) return mr;
  }
  return std::nullopt;
}
}  // namespace

// Gaussian staircases whose combination has a half-line term (trunc^2: f constant on each [n, n+1), its jump
// J_n a constant per region of n, trunc^2: 2n - sign(n)), near 0 where the caller's combination would
// take the generic half-line series (gaussian_fract_right; the caller places this block after its
// far sides): E f(x+U) = f(n0) + sum_{n > x} J_n
// Phic((n - x)/sigma) - sum_{n <= x} J_n Phic((x - n)/sigma), n0 = floor(x), over the breaks n0 + j,
// j in (-K, K]; each Phic is one row of the normal table and the offsets n - x are exact. The dropped
// breaks lie >= K from x: StaircaseTail bounds them (absolute for |x| <= 1, relative to f beyond) and
// gives each tier's sigma bound at the type's tolerance (float 1e-7, double 1e-13). Offsets past
// tail_cut sd are taken at tail_cut (no subnormal exp). Tiny sigma (below 1e-30 float, 1e-300 double,
// where 1/sigma could overflow), wider sigma and wider types fall through to the combination. GLSL:
// the float tiers, respelled (glsl_spelling).
std::string gauss_staircase_near(const sym::Derived& d, sym::Lang lang, const std::vector<sym::Derived>* ds) {
  const GiNaC::symbol n("n"), n0("n0");
  const auto st = gauss_constant_staircase(d, ds, n);
  if (!st || st->z.empty()) return "";
  // Only where the combination takes a half-line series (trunc^2): trunc's own near branch is cheaper.
  bool half_lines = false;
  for (const auto& t : d.terms) half_lines = half_lines || t.kind == sym::CombinationTerm::Kind::HalfLines;
  if (!half_lines) return "";
  const Syntax s{sym::Lang::Cpp};  // GLSL: the float text respelled
  const bool glsl = lang != sym::Lang::Cpp;
  const std::string base = staircase_base(s, *st, n, n0);
  const std::string J = region_chain(s, *st, n, 0);
  auto block = [&](int K, double smax, const char* tiny) {
    std::string out =
        "      if (sigma >= " + s.dbl(std::atof(tiny)) + " && sigma <= " + s.dbl(smax) + ") {\n";
    out += "        const T n0 = floor(x);\n        const T inv = T(1) / sigma;\n";
    out += "        T acc = " + base + ";\n";
    for (int j = 1 - K; j <= K; ++j) out += staircase_break(s, j, J, "acc");
    return out + "        return acc;\n      }\n";
  };
  // Placed after the combination's far sides (x - Rf >= bmax, x + Rf < bmin: the periodic terms
  // alone), so it runs exactly where they do not apply and the generic half-line series would.
  std::string out = "  {  // near 0: the break sum (see the emitter's comment)\n";
  const StaircaseTail tails(*st, n);
  if (!tails.ok) return "";
  // Even f with f = g on [0, inf) (trunc^2, g = floor^2): g~(|x|) and h = f - g's breaks n <= 0 only,
  // from sigma kMirrorLo to kMirrorHi. Measured (float, x within 6 sd of 0, this machine): trunc^2
  // 25.0 -> 20.2 ns at sigma 0.3, 45.3 -> 20.1 at 1, 55.7 -> 28.3 at 2 (double 36.0 -> 33.5, 90.7 ->
  // 38.9, 115 -> 61.8); below 0.25 g's Fourier regime has 5 terms and the two cost the same, at 4
  // the loop's ~25 breaks cost as much as the generic half-line series (48 vs 47 ns).
  constexpr double kMirrorLo = 0.25, kMirrorHi = 3.0;
  const auto mirror = even_mirror(d, *st, *ds, n);
  std::optional<StaircaseTail> htails;
  if (mirror) htails.emplace(mirror->h, n);
  const bool mirrored = mirror && htails->ok;
  // The loop stops at the first break beyond c sd: the dropped ones (J^h_n <= Jb + Js (|n| + 2), |n|
  // >= |x| + c sigma; the |x| part is relative to f ~ x^2 beyond |x| = 1, as in StaircaseTail) sum
  // to <= sum_j (Jb + Js (c sigma + j + 2)) Phic(c + j / sigma) <= tol over the sigma range.
  auto mirror_cut = [&](double tol) {
    auto bound = [&](double c) {
      double worst = 0;
      for (double sg = kMirrorLo; sg <= kMirrorHi * 1.0001; sg += 0.05) {
        double b = 0;
        for (int j = 0; j < 4000; ++j) {
          const double term =
              (htails->Jb + htails->Js * (c * sg + j + 2)) * 0.5 * std::erfc((c + j / sg) / std::sqrt(2.0));
          b += term;
          if (term < 1e-40) break;
        }
        worst = std::max(worst, b);
      }
      return worst;
    };
    double lo = 1, hi = 12;
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (bound(mid) <= tol ? hi : lo) = mid;
    }
    return hi;
  };
  // The loop runs at most c kMirrorHi + 2 times (a NaN t leaves at once).
  auto mirror_block = [&](double tol) {
    const double c = mirror_cut(tol);
    std::string o = "      if (sigma >= " + s.dbl(kMirrorLo) + " && sigma <= " + s.dbl(kMirrorHi) +
                    ") {  // even f: g~(|x|) + h's breaks n = 0, -1, ... (all left of |x|)\n";
    o += "        const T ax = abs(x);\n        const T inv = T(1) / sigma;\n";
    o += "        T acc = " + (glsl ? "bl_" + mirror->g_impl : mirror->g_impl + "<T>") + "(ax, sigma);\n";
    o += "        for (T n = T(0); n > " + s.dbl(-std::ceil(c * kMirrorHi + 2)) + "; n -= T(1)) {\n";
    o += "          const T t = (ax - n) * inv;\n";
    o += "          if (!(t <= " + s.dbl(c) + ")) break;\n";
    o += "          acc -= " + region_chain(s, mirror->h, n, 0) + " * detail::normal_Phic(t);\n";
    return o + "        }\n        return acc;\n      }\n";
  };
  // Tiers per type (after the mirrored form, which takes sigma >= kMirrorLo): K breaks per side up
  // to reach(K) (StaircaseTail at the type's tolerance, float 1e-7, double 1e-13), K = 3, 4, 5, ...
  // until kMirrorLo (else sigma ~ 1: 12-18 breaks there instead of the generic half-line series,
  // ~4x dearer); one more break per tier costs one Phic.
  auto tiers = [&](double tol, double smax, const char* tiny) {
    std::string o = mirrored ? mirror_block(tol) : "";
    if (mirrored) smax = kMirrorLo;
    for (int K = 3; K <= 12; ++K) {
      const double r = tails.reach(K, tol);
      o += block(K, r, tiny);
      if (r >= smax) break;
    }
    return o;
  };
  if (glsl) return out + glsl_spelling(tiers(1e-7, 1.0, "1e-30")) + "  }\n";
  out += "    if constexpr (std::is_same<T, float>::value) {\n" + tiers(1e-7, 1.0, "1e-30") + "    }\n";
  out += "    if constexpr (std::is_same<T, double>::value) {\n" + tiers(1e-13, 1.05, "1e-300") + "    }\n";
  return out + "  }\n";
}

// Gaussian staircases (floor, ceil, trunc and their squares), narrow kernels, any x: f is constant on
// [n, n+1), so E f(x+U) = f(n0) + sum_{n > x} J_n Phic((n - x)/sigma) - sum_{n <= x} J_n Phic((x - n)/sigma)
// (gauss_staircase_near's sum) over the K nearest breaks on each side, one Phic (one Horner chain of
// the normal table) per break; below the nearest-only bound the nearer of n0, n0 + 1 alone (no
// branch: sd = +-1 picks it). The combination's fused periodic form needs phi and Phic per break and
// forms x^2 - 2 x E[..] differences. Tiers: the dropped breaks lie >= D (0.5 nearest-only, K else) from
// x, their tails sum to <= sum_m 2 (Jb + Js (D + m + 1)) Phic((D + m)/sigma) with Jb = max |J_n| over
// n in [-2, 3] and Js its growth per step: <= tol (float 1e-7, double 1e-13) absolute for |x| <= 1,
// relative to f (which grows as fast as J) beyond. Wider kernels fall through. GLSL: the float tiers,
// respelled (glsl_spelling).
std::string gauss_staircase_narrow(const sym::Derived& d, sym::Lang lang,
                                   const std::vector<sym::Derived>* ds) {
  const GiNaC::symbol n("n"), n0("n0");
  const auto st = gauss_constant_staircase(d, ds, n);
  if (!st) return "";
  const StaircaseTail tails(*st, n);
  if (!tails.ok) return "";
  const Syntax s{sym::Lang::Cpp};  // GLSL: the float text respelled
  const std::string base = staircase_base(s, *st, n, n0);
  const std::string J = region_chain(s, *st, n, 0);
  // One break per side at most: measured on floor^2 (float, x86-64 baseline), the nearest alone
  // costs 8-10 ns, a pair 11 ns, two pairs 19.5 ns, as dear as the fused form's Fourier regime there
  // (19.6 ns with 5 terms at sigma 0.18-0.25, 15 ns with 3 beyond).
  const int Kmax = 1;
  auto tiers = [&](double tol, const char* tiny) {
    const double s0 = tails.reach(0.5, tol);
    std::string out = "    if (sigma >= " + s.dbl(std::atof(tiny)) + " && sigma < " +
                      s.dbl(tails.reach(Kmax, tol)) + ") {\n";
    out += "      const T n0 = floor(x);\n      const T inv = T(1) / sigma;\n";
    out += "      const T acc = " + base + ";\n";
    out += "      if (sigma < " + s.dbl(s0) + ") {  // the nearest break alone\n";
    out += "        const T dl = x - n0, dr = (n0 + T(1)) - x;  // exact near the breaks\n";
    out += "        const T sd = std::copysign(T(1), dl - dr);  // +1: n0 + 1 is nearer\n";
    out += "        const T n = n0 + T(0.5) * (sd + T(1));\n";
    out += "        const T t = detail::min2(detail::min2(dl, dr) * inv, detail::tail_cut<T>());\n";
    out += "        return acc + sd * " + J + " * detail::normal_Phic(t);\n      }\n";
    for (int K = 1; K <= Kmax; ++K) {
      const bool last = K == Kmax;
      out += std::string("      ") + (last ? "{" : "if (sigma < " + s.dbl(tails.reach(K, tol)) + ") {") +
             "  // " + std::to_string(K) + " break(s) on each side\n        T a = acc;\n";
      for (int j = 1 - K; j <= K; ++j) out += staircase_break(s, j, J, "a");
      out += "        return a;\n      }\n";
    }
    return out + "    }\n";
  };
  std::string out = "  // Narrow kernels: the nearest breaks' Phic sum (rulegen: gauss_staircase_narrow).\n";
  if (lang != sym::Lang::Cpp) return out + glsl_spelling(tiers(1e-7, "1e-30"));
  out += "  if constexpr (std::is_same<T, float>::value) {\n" + tiers(1e-7, "1e-30") + "  }\n";
  out += "  if constexpr (std::is_same<T, double>::value) {\n" + tiers(1e-13, "1e-300") + "  }\n";
  return out;
}

// Whole-line piecewise polynomials (abs, sign, step, saturate, smoothstep and their squares): the
// same break sum on x itself, every finite break compared at run time (its offset d = b - x from b's
// two-part split also picks q_j, so piece and sides agree). No reduction is needed: E q_j(x+U) is a
// polynomial in x and sigma^2, and for |x| >> h the terms vanish. With one break nothing cancels at
// any width (abs: the result is ~max(|x|, h/2)); with bounded pieces (saturate) the jump terms grow
// like h/W (W the narrowest bounded piece) and cancel, so the form is used for h <= K W (K from the
// pieces' growth as for periodic atomics), the generic per-piece box_pw/tent_pw beyond. sigma = 0
// and NaN fall through too. Error: absolute, about (breaks + degree) G max|f| eps (G <= kMaxGrowth),
// relative to |q_j(x)| for large |x|.
std::string box_tent_piecewise_narrow(const sym::Derived& d, sym::Lang lang) {
  if (d.kernel == Kernel::Gaussian || d.body != sym::Body::PiecewiseTable || d.pieces.size() < 2) return "";
  const auto& ps = d.pieces;
  const size_t N = ps.size();
  for (size_t i = 0; i + 1 < N; ++i)
    if (!ps[i].hi.finite() || !GiNaC::is_a<numeric>(ps[i].hi.value)) return "";
  auto b_of = [&](size_t i) { return GiNaC::ex_to<numeric>(ps[i].hi.value); };
  double W = HUGE_VAL, fmax = 0;
  for (size_t i = 1; i + 1 < N; ++i) W = std::min(W, (b_of(i) - b_of(i - 1)).to_double());
  double limit = 1e18;  // one break: any width (bounded so that l^2 and 1/width stay finite)
  if (N > 2) {
    // max|f| over the bounded pieces, and the growth of their extensions over K W each side.
    for (size_t i = 1; i + 1 < N; ++i) {
      const double a = b_of(i - 1).to_double(), b = b_of(i).to_double();
      for (int j = 0; j <= 256; ++j)
        fmax = std::max(fmax, std::fabs(polyval(ps[i].c, a + (b - a) * j / 256.0)));
    }
    if (fmax == 0) fmax = 1;
    double K = 0;
    for (double k : {2.0, 1.0, 0.5, 0.25}) {
      double g = 0;
      for (size_t i = 0; i < N; ++i) {
        const double lo = i == 0 ? b_of(0).to_double() - 2 * k * W : b_of(i - 1).to_double() - k * W;
        const double hi = i + 1 == N ? b_of(N - 2).to_double() + 2 * k * W : b_of(i).to_double() + k * W;
        for (int j = 0; j <= 256; ++j)
          g = std::max(g, std::fabs(polyval(ps[i].c, lo + (hi - lo) * j / 256.0)));
      }
      if (g <= kMaxGrowth * fmax) {
        K = k;
        break;
      }
    }
    if (K == 0) return "";
    limit = K * W;
  }
  std::vector<Candidate> cands;
  for (size_t i = 0; i + 1 < N; ++i) {
    const std::vector<numeric> e = minus(shifted(ps[i + 1].c, b_of(i)), shifted(ps[i].c, b_of(i)));
    if (!e.empty()) cands.push_back({b_of(i), 0, e});
  }
  const Syntax s{lang};
  const bool box = d.kernel == Kernel::Box;
  std::string out = "  {  // the break sum (narrow enough kernels; see emit_box_tent_breaks.cpp)\n";
  out += "  " + s.decl("hw", (box ? (s.cpp() ? "detail::k_sqrt3<T>()" : "BL_SQRT3")
                                  : (s.cpp() ? "detail::k_sqrt6<T>()" : "BL_SQRT6")) +
                                 std::string(" * sigma"));
  out += "    if (sigma > " + s.dbl(0) + " && hw <= " + s.dbl(limit) + ") {\n";
  out += "    " + s.decl("r", "x");
  const int maxdeg = max_degree(ps);
  if (maxdeg >= 2) out += "    " + s.decl("s2", "sigma * sigma");
  std::string base;
  for (size_t i = 0; i < N; ++i) {
    const std::string m = kernel_mean(s, d.kernel, ps[i].c, "r");
    if (i + 1 < N) {
      const std::string di = "db" + std::to_string(i);
      out += "  " + offset_decl(s, di, b_of(i), 0);
      base += "(" + di + " > " + s.dbl(0) + " ? " + m + " : ";
    } else {
      base += m + std::string(N - 1, ')');
    }
  }
  out += "    " + s.T() + " acc = " + base + ";\n";
  out +=
      "    " + s.decl("sc", "hw < " + s.dbl(1e-30) + " ? " + s.dbl(std::ldexp(1.0, 100)) + " : " + s.dbl(1));
  out += "    " + s.decl("ik", s.dbl(1) + " / (" + (box ? s.dbl(2) + " * hw" : std::string("hw")) + " * sc)");
  std::string terms = jump_terms(s, d.kernel, cands, 0);
  for (size_t at = 0; (at = terms.find("\n  ", at)) != std::string::npos; at += 3) terms.insert(at + 1, "  ");
  return out + "  " + terms + "      return acc;\n    }\n  }\n";
}

}  // namespace bl::rulegen
