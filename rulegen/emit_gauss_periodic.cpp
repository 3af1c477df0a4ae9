// See emit_gauss_periodic.hpp.
#include "emit_gauss_periodic.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "derived.hpp"
#include "emit_common.hpp"
#include "emit_syntax.hpp"
#include "kernels.hpp"
#include "printer.hpp"

namespace bl::rulegen {
namespace {
using namespace GiNaC;

constexpr double kPi = 3.14159265358979323846;
// Truncation tolerance of the float regimes (dropped breaks, Fourier tail): float's own rounding of
// these sums is ~6e-8, and blverify's float bound is 2e-5, so 1e-7 keeps 200x of margin while it
// trims Fourier terms and widens the cheaper break regimes.
constexpr double kTolFloat = 1e-7;

// Shortest double text that reads back as v, as T(...).
std::string lit(double v) {
  return Syntax{Lang::Cpp}.dbl(v);
}

// A coefficient as text: a literal when numeric, else the printed expression; "" when zero.
std::string coef_text(const ex& e) {
  const ex v = e.expand();
  if (v.is_zero()) return "";
  const ex f = v.evalf();
  if (is_a<numeric>(f)) return lit(ex_to<numeric>(f).to_double());
  return "(" + sym::print(v, sym::Lang::Cpp) + ")";
}

// Upper bound on |e| with sigma = sig and every other symbol (lam) of magnitude at most 1.
double abs_bound(const ex& e, double sig) {
  const ex v = e.subs(sym::var_sigma() == sig).expand();
  auto mono = [](const ex& m) {
    exmap ones;
    for (const_preorder_iterator it = m.preorder_begin(); it != m.preorder_end(); ++it)
      if (is_a<symbol>(*it)) ones[*it] = 1;
    const ex f = m.subs(ones).evalf();
    return is_a<numeric>(f) ? std::fabs(ex_to<numeric>(f).to_double()) : HUGE_VAL;
  };
  if (is_a<add>(v)) {
    double s = 0;
    for (size_t i = 0; i < v.nops(); ++i) s += mono(v.op(i));
    return s;
  }
  return mono(v);
}

// Horner text of sum_k c[k] v^k ("" entries are zero).
std::string horner(const std::vector<std::string>& c, const std::string& v) {
  int top = static_cast<int>(c.size()) - 1;
  while (top >= 0 && c[top].empty()) --top;
  if (top < 0) return "T(0)";
  std::string r = c[top];
  for (int k = top - 1; k >= 0; --k) r = "(" + r + ") * " + v + (c[k].empty() ? "" : " + " + c[k]);
  return r;
}

// Whether `name` occurs in `text` as a whole identifier.
bool mentions(const std::string& text, const std::string& name) {
  auto id = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  for (size_t at = text.find(name); at != std::string::npos; at = text.find(name, at + 1)) {
    const bool before = at > 0 && id(text[at - 1]);
    const bool after = at + name.size() < text.size() && id(text[at + name.size()]);
    if (!before && !after) return true;
  }
  return false;
}

// Drops the one-declaration lines "const T name = ...;" whose name nothing else uses (the last
// links of the Chebyshev and damping chains when a parity has no further term), repeatedly.
std::string drop_unused(std::string code) {
  for (bool changed = true; changed;) {
    changed = false;
    size_t start = 0;
    while (start < code.size()) {
      const size_t end = code.find('\n', start);
      const std::string line = code.substr(start, end == std::string::npos ? std::string::npos : end - start);
      const size_t k = line.find("const T ");
      const size_t eq = line.find(" = ");
      int depth = 0;
      bool top_comma = false;  // "const T a = ..., b = ...;" declares two
      for (char c : line) {
        depth += c == '(' ? 1 : c == ')' ? -1 : 0;
        top_comma |= c == ',' && depth == 0;
      }
      if (k != std::string::npos && eq != std::string::npos && !top_comma &&
          line.find_first_not_of(' ') == k) {
        const std::string name = line.substr(k + 8, eq - k - 8);
        std::string rest = code;
        rest.erase(start, end == std::string::npos ? std::string::npos : end - start + 1);
        if (!mentions(rest, name)) {
          code = rest;
          changed = true;
          continue;
        }
      }
      if (end == std::string::npos) break;
      start = end + 1;
    }
  }
  return code;
}

bool dyadic(const numeric& v) {
  const numeric s = v * numeric(1 << 20);
  return s.is_integer() && std::fabs(v.to_double()) < 1e6;
}

// v an exact power of two (dyadic, mantissa 1/2).
bool power_of_two(const numeric& v) {
  int e = 0;
  return v > 0 && dyadic(v) && std::frexp(v.to_double(), &e) == 0.5;
}

struct Break {
  numeric pos;         // in [0, T)
  std::vector<ex> e;   // jump q_right - q_left about the break, coefficients of u^k
  bool delta = false;  // the spec's delta sits here (lo[0])
};

// E q(v + U), U ~ N(0, sigma^2) = sum_m v^m sum_i (2i-1)!! C(m+2i, 2i) c_{m+2i} sigma^{2i}: the
// coefficient texts of v^m (Horner in s2 = sigma^2; "" where zero).
std::vector<std::string> gauss_mean_coefs(const std::vector<ex>& c) {
  std::vector<std::string> cx;
  for (size_t m = 0; m < c.size(); ++m) {
    std::vector<std::string> cs;
    numeric df = 1;
    for (size_t i = 0; m + 2 * i < c.size(); ++i) {
      if (i > 0) df *= numeric(long(2 * i - 1));
      cs.push_back(coef_text(df * binomial(numeric(long(m + 2 * i)), numeric(long(2 * i))) * c[m + 2 * i]));
    }
    const std::string h = horner(cs, "s2");
    cx.push_back(h == "T(0)" ? "" : "(" + h + ")");
  }
  return cx;
}

// Break i of pieces c over sp's period and starts: its position and the jump q_i(lo_i + u) -
// q_{i-1}(lo_i + u) about it (q_{-1}(T + u) at i = 0) as coefficients of u^k, empty where the
// pieces join with every derivative.
Break break_of(const GaussPeriodicSpec& sp, const std::vector<std::vector<ex>>& c, size_t i) {
  static const symbol u("u");
  const size_t N = sp.lo.size(), pi = i == 0 ? N - 1 : i - 1;
  const ex at_prev = i == 0 ? ex(sp.period) + u : ex(sp.lo[i]) + u;
  ex jump = 0;
  for (size_t k = 0; k < c[i].size(); ++k) jump += c[i][k] * pow(sp.lo[i] + u, int(k));
  for (size_t k = 0; k < c[pi].size(); ++k) jump -= c[pi][k] * pow(at_prev, int(k));
  jump = jump.expand();
  Break b;
  b.pos = sp.lo[i];
  const int deg = jump.is_zero() ? -1 : jump.degree(u);
  for (int k = 0; k <= deg; ++k) b.e.push_back(jump.coeff(u, k));
  return b;
}

struct Plan {
  int nside = 1;       // break candidates on each side of x
  double sigma_b;      // break regime below, Fourier regime from here
  int K;               // Fourier terms
  double z;            // dropped breaks lie beyond z sigma
  double sigma_0 = 0;  // one piece, nside 1: below this the nearest break alone (0: none)
  double z0 = 0;
  std::vector<std::pair<double, int>> tiers;  // Fourier: from sigma on, K terms suffice (sigma decreasing)
};

// Tail bound of one dropped break at t sd: sum_k |e_k| sigma^k k! phi(t)/t^(k+1) (J_k(t) <=
// k! phi(t)/t^(k+1), phi(t + v) <= phi(t) e^{-t v}) plus |delta| phi(t).
double break_bound(const Break& b, const ex& delta, double sig, double t) {
  const double ph = std::exp(-0.5 * t * t) / std::sqrt(2 * kPi);
  double s = 0, fact = 1, sk = 1;
  for (size_t k = 0; k < b.e.size(); ++k) {
    if (k > 0) fact *= double(k), sk *= sig;
    s += abs_bound(b.e[k], sig) * sk * fact * ph / std::pow(t, double(k + 1));
  }
  if (b.delta) s += abs_bound(delta, sig) * ph;
  return s;
}

// Locals j0..j<ne-1> = J_k(t) = int_t^inf (z - t)^k phi(z) dz of one break, by J_1 = phi - t J_0,
// J_{k+1} = k J_{k-1} - t J_k: Phic alone (no exp in double) when neither J_1 nor phi (`ph`) is read.
std::string j_chain(size_t ne, bool needs_phi, const std::string& in = "        ", bool only_j1 = false) {
  // A kink (e_0 = 0, e_1 only): J_1 from its own table column, one Horner chain.
  if (ne == 2 && !needs_phi && only_j1) return in + "const T j1 = detail::normal_J1(t);\n";
  std::string o = ne <= 1 && !needs_phi ? in + "const T j0 = detail::normal_Phic(t);\n"
                                        : in + "T ph, j0;\n" + in + "detail::normal_phi_Phic(t, ph, j0);\n";
  for (size_t k = 1; k < ne; ++k) {
    const std::string prev =
        k == 1 ? "ph" : (k == 2 ? "j0" : lit(double(k - 1)) + " * j" + std::to_string(k - 2));
    o += in + "const T j" + std::to_string(k) + " = " + prev + " - t * j" + std::to_string(k - 1) + ";\n";
  }
  return o;
}

}  // namespace

// The C++ text of the float regimes (below) respelled as GLSL: the regime printer writes C++, and
// its vocabulary is closed (this file's own spellings and sym::print's C++ coefficients), so the
// respelling is a fixed map; anything outside it throws rather than reach a driver.
std::string glsl_spelling(std::string code) {
  auto replace_all = [&](const std::string& from, const std::string& to) {
    for (size_t at = code.find(from); at != std::string::npos; at = code.find(from, at + to.size()))
      code.replace(at, from.size(), to);
  };
  // round(v) instead of (v + 1.5 2^23) - 1.5 2^23: a GPU compiler may fold the latter to v.
  replace_all("v - ((v + T(12582912.0)) - T(12582912.0))", "v - round(v)");
  replace_all("std::copysign(T(1), ", "bl_copysign1(");
  replace_all("detail::normal_phi_Phic(", "bl_phi_Phic(");
  replace_all("detail::normal_Phic(", "bl_Phic(");
  replace_all("detail::normal_J1(", "bl_J1(");
  replace_all("detail::reduce_signed_pow2(", "bl_reduce_signed_pow2(");
  replace_all("detail::tail_cut<T>()", "BL_TAIL_CUT");
  replace_all("detail::min2(", "min(");
  replace_all("detail::at_least(", "max(");
  replace_all("detail::pi<T>()", "BL_PI");
  replace_all("const T ", "float ");
  replace_all("  T ph, j0;", "  float ph, j0;");
  replace_all("  T acc;", "  float acc;");
  replace_all("  T acc1;", "  float acc1;");
  replace_all("detail::make_stat(", "vec2(");
  replace_all(" T acc = ", " float acc = ");
  replace_all(" T a = ", " float a = ");
  replace_all("for (T ", "for (float ");
  // T(literal) -> a float literal.
  std::string out;
  for (size_t i = 0; i < code.size();) {
    const bool ident_before =
        i > 0 && (std::isalnum(static_cast<unsigned char>(code[i - 1])) || code[i - 1] == '_');
    if (!ident_before && code.compare(i, 2, "T(") == 0) {
      const size_t close = code.find(')', i + 2);
      const std::string lit_text = code.substr(i + 2, close - i - 2);
      if (close != std::string::npos && !lit_text.empty() &&
          lit_text.find_first_not_of("0123456789.e+-") == std::string::npos) {
        const bool is_float = lit_text.find_first_of(".e") != std::string::npos;
        out += "(" + lit_text + (is_float ? "" : ".0") + ")";
        i = close + 1;
        continue;
      }
    }
    out += code[i++];
  }
  for (const char* cpp_only : {"T(", "std::", "detail::", "<T>", "sizeof", "constexpr"}) {
    const size_t at = out.find(cpp_only);
    if (at != std::string::npos)
      throw std::logic_error(std::string("gauss periodic GLSL: no GLSL spelling for '") + cpp_only +
                             "' in: " + out.substr(at > 60 ? at - 60 : 0, 160));
  }
  return out;
}

std::string gauss_periodic_fast(const GaussPeriodicSpec& sp, Lang lang) {
  const size_t N = sp.lo.size();
  if (N == 0 || N != sp.c.size() || !dyadic(sp.period) || sp.lo[0] != 0) return "";
  // The outputs of the pass: sp itself, then sp.more (one piece only: the per-piece paths below
  // print every channel; the blended two- and three-piece forms print one).
  std::vector<const GaussPeriodicSpec*> chs{&sp};
  for (const GaussPeriodicSpec& m : sp.more) chs.push_back(&m);
  const size_t C = chs.size();
  if (C > 1 && (N != 1 || sp.finish.empty())) return "";
  for (const GaussPeriodicSpec* ch : chs)
    if (ch->c.size() != N) return "";
  auto accn = [](size_t ci) { return ci == 0 ? std::string("acc") : "acc" + std::to_string(ci); };
  double Pd = sp.period.to_double();
  if (!power_of_two(sp.period)) return "";  // exact reduction
  for (const auto& l : sp.lo)
    if (!dyadic(l)) return "";
  const numeric T = sp.period;
  auto hi_of = [&](size_t i) { return i + 1 < N ? sp.lo[i + 1] : T; };
  double wmin = HUGE_VAL;
  for (size_t i = 0; i < N; ++i) wmin = std::min(wmin, (hi_of(i) - sp.lo[i]).to_double());
  // Break types: i at lo[i], jump q_i(lo_i + u) - q_{i-1}(lo_i + u) (q_{-1}(T + u) at i = 0).
  std::vector<std::vector<Break>> brs(C, std::vector<Break>(N));  // per channel
  int maxdd = 0;
  for (size_t ci = 0; ci < C; ++ci)
    for (size_t i = 0; i < N; ++i) {
      Break& b = brs[ci][i] = break_of(sp, chs[ci]->c, i);
      b.delta = i == 0 && !chs[ci]->delta.is_zero();
      maxdd = std::max(maxdd, static_cast<int>(b.e.size()) - 1);
    }
  const std::vector<Break>& br = brs[0];  // positions (the same in every channel); channel 0's jumps
  // Distance beyond the nside nearest breaks on a side: the narrowest run of nside pieces.
  auto run_min = [&](int n) {
    if (n == 0) return 0.5 * wmin;  // nearest break only: the other one is at least wmin/2 away
    double m = HUGE_VAL;
    for (size_t j = 0; j < N; ++j) {
      numeric w = 0;
      for (int k = 0; k < n; ++k) {
        const size_t i = (j + k) % N;
        w += hi_of(i) - sp.lo[i];
      }
      m = std::min(m, w.to_double());
    }
    return m;
  };
  // The dropped breaks on one side sit at D, D + wmin, D + 2 wmin, ... or farther; both sides
  // together are bounded by twice that sum, with the largest bound over the break types.
  auto dropped = [&](double sig, int n) {
    const double D = run_min(n);
    double s = 0;
    for (int m = 0; m < 200; ++m) {
      const double t = (D + m * wmin) / sig;
      double b = 0;
      for (size_t ci = 0; ci < C; ++ci)
        for (const Break& x : brs[ci]) b = std::max(b, break_bound(x, chs[ci]->delta, sig, t));
      s += b;
      if (b < 1e-30) break;
    }
    return 2 * s;
  };
  double coef_bound = 0;
  for (const GaussPeriodicSpec* ch : chs) coef_bound = std::max(coef_bound, ch->coef_bound);
  auto fourier_K = [&](double s, double tol) {
    const double a = 2 * kPi * kPi * s * s;
    for (int K = 0; K < 1000; ++K) {
      const double uu = K + 1.0;
      if (coef_bound * std::exp(-a * uu * uu) / (-std::expm1(-2 * a * uu)) <= tol) return K;
    }
    return 1000;
  };
  auto plan_for = [&](double tol, int nside) {
    Plan p;
    p.nside = nside;
    double sig = Pd;
    while (sig > 1e-4 * Pd && !(dropped(sig, nside) <= tol)) sig *= 0.995;
    p.sigma_b = sig;
    p.z = run_min(nside) / sig;
    p.K = fourier_K(sig / Pd, tol);
    return p;
  };
  // Cost in float ns, measured on fract (x86-64 baseline: the FP ports bound it, ~0.3 ns per
  // operation): a pair of break candidates 17 (+10% per jump degree; one phi_Phic each), the
  // nearest-only form 12.8; the Fourier regime 7 (sincos polynomial, one exp) + 1.6 per nonzero term.
  // The plan minimises the dearer of the two regimes.
  auto choose = [&](double tol) {
    Plan best{};
    double best_cost = HUGE_VAL;
    for (int n = 0; n <= 3 && n <= int(2 * N); ++n) {
      if (n == 0 && N > 1 && !sp.delta.is_zero()) continue;  // nearest_block: one break type only
      const Plan p = plan_for(tol, n);
      int nnz = 0;  // nonzero Fourier terms
      for (int k = 1; k <= p.K; ++k) {
        const ex sg = (k % 2) ? -1 : 1;
        bool zero = true;
        for (const GaussPeriodicSpec* ch : chs)
          zero &= ch->ak.subs(lst{sym::var_k() == k, sym::var_pk() == sg}).expand().is_zero() &&
                  ch->bk.subs(lst{sym::var_k() == k, sym::var_pk() == sg}).expand().is_zero();
        nnz += !zero;
      }
      const double cb = (n ? 17.0 * n : 12.8) * (1 + 0.1 * maxdd), cf = 7.0 + 1.6 * nnz;
      const double c = std::max(cb, cf);
      if (c < best_cost) best = p, best_cost = c;
    }
    // Below the nearest-only sigma_b a third regime takes one phi_Phic instead of two (fract: 47% of
    // log-uniform sigma in [0.01, 1]; the extra branch costs less than it saves).
    if (best.nside == 1 && (N == 1 || (N <= 3 && sp.delta.is_zero()))) {
      const Plan p0 = plan_for(tol, 0);
      best.sigma_0 = p0.sigma_b, best.z0 = p0.z;
    }
    return best;
  };
  // Fourier tiers: the sigma from which K' < K terms meet tol (fourier_K decreases with sigma), for
  // K' in {1, 2, 3, 5, 8}; fewer tiers would leave most wide kernels summing terms below tol, more
  // add branches for little.
  auto add_tiers = [&](Plan& p, double tol) {
    for (int Kt : {1, 2, 3, 5, 8}) {
      if (Kt >= p.K) break;
      double lo = p.sigma_b, hi = p.sigma_b;
      while (fourier_K(hi / Pd, tol) > Kt) hi *= 2;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        (fourier_K(mid / Pd, tol) > Kt ? lo : hi) = mid;
      }
      p.tiers.push_back({hi, Kt});
    }
  };
  Plan pf = choose(kTolFloat), pd = choose(1e-13);
  if (pf.K >= 1000 || pd.K >= 1000) return "";
  add_tiers(pf, kTolFloat);
  add_tiers(pd, 1e-13);

  const ex kk = sym::var_k(), pk = sym::var_pk();
  // Nearest break only (nside 0): the left break lo_j or the right one hi_j, whichever is nearer,
  // chosen without a branch: sd = +1 (right) or -1 (left); the term is sd sum_k e_k (sd sigma)^k J_k
  // with e the chosen break's jump, blended as h e_right + (1 - h) e_left, h = (sd + 1)/2 in {0, 1}.
  auto nearest_block = [&](size_t j) {
    const numeric L = br[j].pos, R = j + 1 < N ? br[j + 1].pos : T;
    std::string o;
    o += "        const T dl = r - (" + lit(L.to_double()) + " + base), dr = (" + lit(R.to_double()) +
         " + base) - r;  // exact near the breaks\n";
    o += "        const T sd = std::copysign(T(1), dl - dr);  // +1: the right break is nearer\n";
    o += "        const T t = detail::min2(detail::min2(dl, dr) * inv, detail::tail_cut<T>());\n";
    size_t ne = 0;
    bool any_delta = false, blend = false, no_j0 = true;
    for (size_t ci = 0; ci < C; ++ci) {
      const Break &bl = brs[ci][j], &bR = brs[ci][(j + 1) % N];
      ne = std::max({ne, bl.e.size(), bR.e.size()});
      any_delta |= bl.delta || bR.delta;
    }
    std::string terms;  // per channel
    for (size_t ci = 0; ci < C; ++ci) {
      const Break &bl = brs[ci][j], &bR = brs[ci][(j + 1) % N];
      std::vector<std::string> et;
      for (size_t k = 0; k < ne; ++k) {
        const ex el = k < bl.e.size() ? bl.e[k] : ex(0), er = k < bR.e.size() ? bR.e[k] : ex(0);
        std::string c;
        if ((el - er).expand().is_zero()) {
          c = coef_text(el);
        } else {
          blend = true;
          const std::string a = coef_text(er), b = coef_text(el);
          c = "(hr * " + (a.empty() ? "T(0)" : a) + " + hl * " + (b.empty() ? "T(0)" : b) + ")";
        }
        et.push_back(c.empty() ? "" : c + " * j" + std::to_string(k));
      }
      no_j0 &= et.empty() || et[0].empty();
      const std::string term = horner(et, "(sd * sigma)");
      if (term != "T(0)") terms += "        " + accn(ci) + " += sd * (" + term + ");\n";
      if (bl.delta || bR.delta) {
        // theta's phi_sigma sum: the delta sits at lo[0]; for N = 1 both neighbours are such breaks.
        if (N == 1)
          terms += "        " + accn(ci) + " += " + coef_text(chs[ci]->delta) + " * ph;\n";
        else
          return std::string();  // not planned: a delta with several break types
      }
    }
    o += j_chain(ne, any_delta, "        ", no_j0);
    if (blend) o += "        const T hr = T(0.5) * (sd + T(1)), hl = T(1) - hr;\n";
    return o + terms;
  };
  // E q_j(rp + U): the coefficient texts of rp^m (gauss_mean_coefs).
  auto mean_coefs = [&](size_t j, size_t ci = 0) { return gauss_mean_coefs(chs[ci]->c[j]); };
  // The candidate break of piece j in slot (side, n): its type and its position relative to the period.
  auto slot = [&](size_t j, int side, int n) {
    long idx = side < 0 ? long(j) - n : long(j) + 1 + n;
    numeric shift = 0;
    while (idx < 0) idx += long(N), shift -= T;
    while (idx >= long(N)) idx -= long(N), shift += T;
    return std::make_pair(size_t(idx), br[idx].pos + shift);
  };
  // Two or three pieces: no branch on the piece of x (random x mispredicts it half the time). The
  // piece indicators w_j in {0, 1} (from exact sign tests r - (lo_i + base)) blend the emit-time
  // constants of each piece: the blend of exact constants with weights 0 and 1 is exact.
  auto blended_block = [&](const Plan& p, const std::string& ret) {
    std::string o;
    for (size_t i = 1; i < N; ++i)
      o += "      const T h" + std::to_string(i) + " = T(0.5) * (T(1) + std::copysign(T(1), r - (" +
           lit(sp.lo[i].to_double()) + " + base)));\n";
    for (size_t j = 0; j < N; ++j) {
      const std::string a = j == 0 ? "T(1)" : "h" + std::to_string(j);
      o += "      const T w" + std::to_string(j) + " = " + a +
           (j + 1 < N ? " - h" + std::to_string(j + 1) : "") + ";\n";
    }
    auto blend = [&](const std::vector<std::string>& v) {
      bool same = true;
      for (const auto& x : v) same &= x == v[0];
      if (same) return v[0];
      std::string r;
      for (size_t j = 0; j < v.size(); ++j)
        if (!v[j].empty())
          r += (r.empty() ? "" : " + ") + std::string("w") + std::to_string(j) + " * " + v[j];
      return r.empty() ? r : "(" + r + ")";
    };
    std::vector<std::vector<std::string>> cxs(N);
    size_t nm = 0;
    for (size_t j = 0; j < N; ++j) cxs[j] = mean_coefs(j), nm = std::max(nm, cxs[j].size());
    std::vector<std::string> cx(nm);
    for (size_t m = 0; m < nm; ++m) {
      std::vector<std::string> v(N);
      for (size_t j = 0; j < N; ++j) v[j] = m < cxs[j].size() ? cxs[j][m] : "";
      cx[m] = blend(v);
    }
    o += "      acc = " + horner(cx, "rp") + ";\n";
    if (p.sigma_0 > 0) {  // the nearest break alone (nearest_block, blended over the pieces)
      std::vector<std::string> Ls(N), Rs(N);
      size_t ne = 0;
      for (size_t j = 0; j < N; ++j) {
        Ls[j] = lit(br[j].pos.to_double());
        Rs[j] = lit((j + 1 < N ? br[j + 1].pos : T).to_double());
        ne = std::max(ne, br[j].e.size());
      }
      o += "      if (sigma < " + lit(p.sigma_0) + ") {  // the nearest break alone\n";
      o += "        const T dl = r - (" + blend(Ls) + " + base), dr = (" + blend(Rs) +
           " + base) - r;  // exact near the breaks\n";
      o += "        const T sd = std::copysign(T(1), dl - dr);  // +1: the right break is nearer\n";
      o += "        const T t = detail::min2(detail::min2(dl, dr) * inv, detail::tail_cut<T>());\n";
      const size_t chain_at = o.size();
      bool two = false;
      std::vector<std::string> et(ne);
      for (size_t k = 0; k < ne; ++k) {
        std::vector<std::string> lv(N), rv(N);
        for (size_t j = 0; j < N; ++j) {
          const Break &bl = br[j], &bR = br[(j + 1) % N];
          lv[j] = k < bl.e.size() ? coef_text(bl.e[k]) : "";
          rv[j] = k < bR.e.size() ? coef_text(bR.e[k]) : "";
        }
        const std::string L = blend(lv), R = blend(rv);
        std::string c = L;
        if (L != R) {
          two = true;
          c = "(hr * " + (R.empty() ? std::string("T(0)") : R) + " + hl * " +
              (L.empty() ? std::string("T(0)") : L) + ")";
        }
        et[k] = c.empty() ? "" : c + " * j" + std::to_string(k);
      }
      o.insert(chain_at, j_chain(ne, false, "        ", !et.empty() && et[0].empty()));
      if (two) o += "        const T hr = T(0.5) * (sd + T(1)), hl = T(1) - hr;\n";
      const std::string term = horner(et, "(sd * sigma)");
      if (term != "T(0)") o += "        acc += sd * (" + term + ");\n";
      o += "  " + ret + "      }\n";
    }
    for (int side = -1; side <= 1; side += 2)
      for (int n = 0; n < p.nside; ++n) {
        std::vector<std::string> pos(N), del(N);
        size_t ne = 0;
        for (size_t j = 0; j < N; ++j) {
          const auto [idx, P] = slot(j, side, n);
          pos[j] = lit(P.to_double());
          del[j] = br[idx].delta ? coef_text(sp.delta) : "";
          ne = std::max(ne, br[idx].e.size());
        }
        std::vector<std::string> et(ne);
        for (size_t k = 0; k < ne; ++k) {
          std::vector<std::string> v(N);
          for (size_t j = 0; j < N; ++j) {
            const Break& b = br[slot(j, side, n).first];
            v[j] = k < b.e.size() ? coef_text(b.e[k]) : "";
          }
          const std::string c = blend(v);
          et[k] = c.empty() ? "" : c + " * j" + std::to_string(k);
        }
        const std::string dl = blend(del);
        o += "      {\n        const T d = (" + blend(pos) + " + base) - r;  // exact near the break\n";
        o += std::string("        const T t = detail::min2(") + (side > 0 ? "d" : "-d") +
             " * inv, detail::tail_cut<T>());\n";
        o += j_chain(ne, !dl.empty(), "        ", !et.empty() && et[0].empty());
        const std::string term = horner(et, side > 0 ? "sigma" : "(-sigma)");
        if (term != "T(0)") o += std::string("        acc ") + (side > 0 ? "+" : "-") + "= " + term + ";\n";
        if (!dl.empty()) o += "        acc += " + dl + " * ph;\n";
        o += "      }\n";
      }
    return o;
  };
  // The returned expression from the channels' values: lead + value, or finish with @i replaced.
  auto result = [&](const std::vector<std::string>& vals) {
    if (C == 1) return sp.lead + vals[0];
    std::string f = sp.finish;
    for (size_t ci = C; ci-- > 0;) {  // @1 before @10 cannot clash: at most 9 channels
      const std::string at = "@" + std::to_string(ci);
      for (size_t k = f.find(at); k != std::string::npos; k = f.find(at, k + 1))
        f.replace(k, at.size(), "(" + vals[ci] + ")");
    }
    return f;
  };
  auto regimes = [&](const Plan& p, bool is_float) {
    std::string o;
    o += "    const T r = detail::reduce_signed_pow2(" + sp.y + ", period);  // exact, in (-T, T)\n";
    o += "    if (sigma < " + lit(p.sigma_b) + ") {\n";
    std::string pcs;  // the per-piece blocks
    const bool blended = p.nside >= 1 && N >= 2 && N <= 3;
    // The break regime's value of each channel: acc plus its break_extra.
    std::vector<std::string> vals(C);
    for (size_t ci = 0; ci < C; ++ci) {
      const std::string extra = coef_text(chs[ci]->break_extra);
      vals[ci] = extra.empty() ? accn(ci) : accn(ci) + " + " + extra;
    }
    const std::string ret = "      return " + result(vals) + ";\n";
    if (blended) pcs = blended_block(p, ret);
    // E q_j(rp + U) in powers of rp, for every channel.
    auto means = [&](size_t j) {
      std::string m;
      for (size_t ci = 0; ci < C; ++ci)
        m += "        " + accn(ci) + " = " + horner(mean_coefs(j, ci), "rp") + ";\n";
      return m;
    };
    if (p.sigma_0 > 0 && N == 1) {
      pcs += "      if (sigma < " + lit(p.sigma_0) + ") {  // the nearest break alone\n";
      pcs += means(0) + nearest_block(0) + "  " + ret + "      }\n";
    }
    for (size_t j = 0; j < N && !blended; ++j) {
      std::string blk = means(j);
      if (p.nside == 0) blk += nearest_block(j);
      // Candidates: left breaks lo_j, lo_{j-1}, ...; right breaks hi_j, ...
      for (int side = -1; side <= 1 && p.nside > 0; side += 2) {
        for (int n = 0; n < p.nside; ++n) {
          const auto [idx, P] = slot(j, side, n);  // break type and position relative to this period
          size_t ne = 0;
          bool any_delta = false, no_j0 = true;
          std::string terms;
          for (size_t ci = 0; ci < C; ++ci) {
            const Break& b = brs[ci][idx];
            ne = std::max(ne, b.e.size());
            any_delta |= b.delta;
            std::vector<std::string> et;
            for (size_t k = 0; k < b.e.size(); ++k) {
              const std::string t = coef_text(b.e[k]);
              et.push_back(t.empty() ? "" : t + " * j" + std::to_string(k));
            }
            no_j0 &= et.empty() || et[0].empty();
            std::string term = horner(et, side > 0 ? "sigma" : "(-sigma)");
            if (term != "T(0)")
              terms += "          " + accn(ci) + (side > 0 ? " += " : " -= ") + term + ";\n";
            if (b.delta) terms += "          " + accn(ci) + " += " + coef_text(chs[ci]->delta) + " * ph;\n";
          }
          if (ne == 0 && !any_delta) continue;
          blk += "        {  // break at " + sym::print(P, sym::Lang::Text) + "\n";
          blk += "          const T d = (" + lit(P.to_double()) + " + base) - r;  // exact near the break\n";
          blk += std::string("          const T t = detail::min2(") + (side > 0 ? "d" : "-d") +
                 " * inv, detail::tail_cut<T>());\n";
          blk += j_chain(ne, any_delta, "          ", no_j0) + terms;
          blk += "        }\n";
        }
      }
      if (N == 1) {
        pcs += "      {\n" + blk + "      }\n";
      } else if (j + 1 < N) {
        pcs += std::string(j ? "      else if" : "      if") + " (r < " + lit(hi_of(j).to_double()) +
               " + base) {\n" + blk + "      }\n";
      } else {
        pcs += "      else {\n" + blk + "      }\n";
      }
    }
    auto uses = [&](const std::string& name) {
      for (size_t at = pcs.find(name); at != std::string::npos; at = pcs.find(name, at + 1)) {
        const char a = at ? pcs[at - 1] : ' ',
                   b = at + name.size() < pcs.size() ? pcs[at + name.size()] : ' ';
        if (!std::isalnum(static_cast<unsigned char>(a)) && a != '_' &&
            !std::isalnum(static_cast<unsigned char>(b)) && b != '_')
          return true;
      }
      return false;
    };
    o += "      const T base = (std::copysign(T(1), r) - T(1)) * (T(0.5) * period);  // -T for r < 0, else "
         "0\n";
    if (uses("rp")) o += "      const T rp = r - base;  // in [0, T]; distances below use the exact r\n";
    if (uses("inv")) o += "      const T inv = T(1) / sigma;\n";
    if (uses("s2")) o += "      const T s2 = sigma * sigma;\n";
    for (size_t ci = 0; ci < C; ++ci) o += "      T " + accn(ci) + ";\n";
    o += pcs;
    o += ret + "    }\n";
    // Fourier regime.
    const size_t fourier_at = o.size();
    const std::string M = is_float ? "T(12582912.0)" : "T(6755399441055744.0)";  // 1.5 * 2^(p-1)
    o += "    const T v = r / period;  // exact (T a power of two), in (-1, 1)\n";
    o += "    const T uf = v - ((v + " + M + ") - " + M + ");  // v - round(v), in [-1/2, 1/2]\n";
    // sin and cos of ph = pi uf / 2 in [-pi/4, pi/4] by Taylor polynomials, then two doublings.
    // Remainders: float through ph^9 / ph^10: < 1.8e-9, 1.2e-10; double through ph^15 / ph^16:
    // < 4.5e-17, 2e-18 (each doubling at most doubles the error, plus rounding).
    o += "    const T ph = T(0.5) * detail::pi<T>() * uf, p2 = ph * ph;\n";
    const int ds = is_float ? 9 : 15, dc = is_float ? 10 : 16;
    {
      std::vector<std::string> cs, cc;
      double f = 1;
      for (int n = 0; n <= dc || n <= ds; ++n) {
        if (n > 0) f *= n;
        const double sg = ((n / 2) % 2) ? -1 : 1;
        if (n % 2 == 1 && n <= ds) cs.push_back(lit(sg / f));
        if (n % 2 == 0 && n <= dc) cc.push_back(lit(sg / f));
      }
      o += "    const T sh = ph * (" + horner(cs, "p2") + ");\n";
      o += "    const T ch = " + horner(cc, "p2") + ";\n";
    }
    o += "    const T sp = T(2) * sh * ch, cp = T(1) - T(2) * sh * sh;  // sin, cos of pi uf\n";
    o += "    const T c1 = T(1) - T(2) * sp * sp;\n    const T s1 = T(2) * sp * cp;\n";
    const double tiny = is_float ? std::ldexp(1.0, -60) : std::ldexp(1.0, -500);
    const std::string TN = lit(tiny);
    o += "    const T q0 = exp(" + lit(-2 * kPi * kPi / (Pd * Pd)) + " * sigma * sigma);\n";
    o += "    const T q = detail::at_least(q0, " + TN + ");\n";
    // Sum of the first K harmonics and the return, as one block of declarations. Two interleaved
    // chains (odd and even k) halve the serial latency: with C2 = 2 cos(2 theta), f_k = C2 f_{k-2} -
    // f_{k-4} for f = cos(k theta), sin(k theta) (from f_{-1}, f_1 and f_0, f_2), and damp_k =
    // q^(k^2) = damp_{k-2} r_{k-2}, r_k = q^(4k+4) = r_{k-2} q^8.
    auto harmonics = [&](int K, const std::string& in) {
      std::vector<std::vector<std::pair<std::string, std::string>>> abs(
          C, std::vector<std::pair<std::string, std::string>>(K + 1));
      int lastC = 0, lastS = 0;
      for (size_t ci = 0; ci < C; ++ci)
        for (int k = 1; k <= K; ++k) {
          const ex sgn = (k % 2) ? -1 : 1;
          auto& ab = abs[ci];
          ab[k].first = coef_text(chs[ci]->ak.subs(lst{kk == k, pk == sgn}));
          ab[k].second = coef_text(chs[ci]->bk.subs(lst{kk == k, pk == sgn}));
          if (!ab[k].first.empty()) lastC = std::max(lastC, k);
          if (!ab[k].second.empty()) lastS = std::max(lastS, k);
        }
      const int last = std::max(lastC, lastS);
      std::string b;
      b += in + "const T q2 = detail::at_least(q * q, " + TN + ");\n";
      b += in + "const T q4 = detail::at_least(q2 * q2, " + TN + ");\n";
      b += in + "const T q8 = detail::at_least(q4 * q4, " + TN + ");\n";
      if (last >= 2) b += in + "const T C2 = T(2) - T(4) * s1 * s1;\n";
      std::vector<std::array<std::string, 2>> acc(C);  // per channel, odd and even k
      for (int k = 1; k <= last; ++k) {
        const std::string Ks = std::to_string(k), K2 = std::to_string(k - 2), K4 = std::to_string(k - 4);
        const bool nc = k <= lastC, ns = k <= lastS;
        if (k == 1) {
          if (nc) b += in + "const T c_1 = c1;\n";
          if (ns) b += in + "const T s_1 = s1;\n";
          b += in + "const T d_1 = q;\n";
        } else if (k == 2) {
          if (nc) b += in + "const T c_2 = T(0.5) * C2;\n";
          if (ns) b += in + "const T s_2 = T(2) * s1 * c1;\n";
          b += in + "const T d_2 = q4;\n";
        } else {
          if (nc)
            b += in + "const T c_" + Ks + " = C2 * c_" + K2 + " - " +
                 (k == 3   ? std::string("c1")
                  : k == 4 ? std::string("T(1)")
                           : "c_" + K4) +
                 ";\n";
          if (ns)
            b += in + "const T s_" + Ks + " = C2 * s_" + K2 +
                 (k == 3   ? std::string(" + s1")
                  : k == 4 ? std::string("")
                           : " - s_" + K4) +
                 ";\n";
          const std::string rprev = k == 3 ? "q8" : k == 4 ? "r_2" : "r_" + K2;
          if (k == 4) b += in + "const T r_2 = detail::at_least(q4 * q8, " + TN + ");\n";
          if (k >= 5)
            b += in + "const T r_" + K2 + " = detail::at_least(" + (k == 5 ? std::string("q8") : "r_" + K4) +
                 " * q8, " + TN + ");\n";
          b += in + "const T d_" + Ks + " = detail::at_least(d_" + K2 + " * " + rprev + ", " + TN + ");\n";
        }
        for (size_t ci = 0; ci < C; ++ci) {
          const auto& ab = abs[ci];
          std::string t;
          if (!ab[k].first.empty()) t = ab[k].first + " * c_" + Ks;
          if (!ab[k].second.empty()) t += (t.empty() ? "" : " + ") + ab[k].second + " * s_" + Ks;
          auto& a = acc[ci][k % 2];
          if (!t.empty()) a += (a.empty() ? "d_" : " + d_") + Ks + " * (" + t + ")";
        }
      }
      std::vector<std::string> vals(C);
      for (size_t ci = 0; ci < C; ++ci) {
        const std::string a0 = coef_text(chs[ci]->a0);
        b += in + "const T " + accn(ci) + " = " + (a0.empty() ? std::string("T(0)") : a0);
        for (int par : {1, 0})
          if (!acc[ci][par].empty()) b += " + (" + acc[ci][par] + ")";
        b += ";\n";
        vals[ci] = accn(ci);
      }
      b += in + "return " + result(vals) + ";\n";
      return drop_unused(b);
    };
    // Wider kernels need fewer terms: each tier returns with its own K (its sigma bound from the
    // same tail test); the last block is the plan's K at sigma_b.
    for (const auto& [sig, K] : p.tiers)
      o += "    if (sigma >= " + lit(sig) + ") {  // " + std::to_string(K) + " term(s)\n" +
           harmonics(K, "      ") + "    }\n";
    o += harmonics(p.K, "    ");
    o = o.substr(0, fourier_at) + drop_unused(o.substr(fourier_at));
    return o;
  };
  auto header = [&](const Plan& p, const char* name, double tol) {
    std::ostringstream h;
    h.precision(4);
    h << "    // " << name << " (tolerance " << tol << "): sigma < " << p.sigma_b << ": the " << p.nside
      << " nearest break(s) on each side (the dropped ones lie beyond " << p.z << " sd";
    if (p.sigma_0 > 0)
      h << "; below " << p.sigma_0 << " the nearest one alone, the others beyond " << p.z0 << " sd";
    h << ": their tails sum to <= tol); else " << p.K
      << " Fourier terms (tail <= tol for sigma/T >= " << p.sigma_b / Pd << ")";
    for (const auto& [sig, K] : p.tiers) h << ", " << K << " from " << sig / Pd;
    h << ".\n";
    return h.str();
  };
  std::string out;
  if (lang == Lang::Glsl) {
    out +=
        "  // Straight-line form (rulegen/emit_gauss_periodic.cpp, the C++ entry's float regimes): break\n";
    out += "  // regime sum_k e_k (+-sigma)^k J_k(t) per candidate break, Fourier regime unrolled.\n";
    // Every sigma > 0 (C++ hands sigma < 1e-30 to the generic image sum): a GLSL function that keeps
    // the generic code behind this block holds its piece tables in local memory, and NVIDIA's driver
    // reserves that per inlined call whether or not it runs (docs/gpu_timing.md, stop 28: 12 such
    // calls made a 1.5 ns/px shader 41 ns/px). A subnormal sigma is taken as FLT_MIN, which keeps
    // 1/sigma finite; the two differ only within 9 FLT_MIN of a break.
    out += "  if (sigma > 0.0) {\n    sigma = max(sigma, 1.17549435e-38);\n" +
           header(pf, "float", kTolFloat) + glsl_spelling(regimes(pf, true)) + "  }\n";
    return out;
  }
  out += "  // Straight-line form (float, double): break regime sum_k e_k (+-sigma)^k J_k(t) per candidate\n";
  out +=
      "  // break (one phi_Phic), Fourier regime unrolled, cos/sin(k theta) by Chebyshev recurrence from\n";
  out += "  // Taylor sin/cos of pi v / 2 (v = x_r/T - round(x_r/T), |pi v / 2| <= pi/4: remainder float\n";
  out += "  // < 2e-9, double < 5e-17) and two angle doublings; q, damp and ratio are floored at 2^-60\n";
  out += "  // (float) or 2^-500 (double): no subnormal arithmetic, and K B 2^-60 is far below tol. A\n";
  out +=
      "  // break beyond tail_cut sd is taken at tail_cut (its tail there is < 1e-18: no subnormal exp).\n";
  out += "  if constexpr (std::is_same<T, float>::value || std::is_same<T, double>::value) {\n";
  out += "   if (sigma >= (sizeof(T) < sizeof(double) ? T(1e-30) : T(1e-300))) {\n";
  out += "    if constexpr (sizeof(T) < sizeof(double)) {\n" + header(pf, "float", kTolFloat) +
         regimes(pf, true) + "    } else {\n" + header(pd, "double", 1e-13) + regimes(pd, false) + "    }\n";
  out += "   }\n  }\n";
  return out;
}

// Pixel-sized kernels, C++: the nearest break alone, located by rint instead of the reduction by
// the period (see box_tent_periodic_hot for the exact offset d and the piece from floor), for one
// or two equally spaced breaks per period at a power-of-two spacing g, one channel and no delta.
// Below sigma_0 (plan_for(tol, 0)'s test: every other break lies g/2 or more from x, their tails
// summed <= tol, float 1e-7 and double 1e-13) the break regime's one term is the whole sum.
std::string gauss_periodic_hot(const GaussPeriodicSpec& sp, const std::string& general,
                               const std::string& clamp, bool* in_range) {
  const size_t N = sp.lo.size();
  // The channels of the pass (sp, then sp.more: one piece only, as in gauss_periodic_fast).
  std::vector<const GaussPeriodicSpec*> chs{&sp};
  for (const GaussPeriodicSpec& m : sp.more) chs.push_back(&m);
  const size_t C = chs.size();
  if ((N != 1 && N != 2) || (C > 1 && (N != 1 || sp.finish.empty()))) return "";
  for (const GaussPeriodicSpec* ch : chs)
    if (ch->c.size() != N || (N != 1 && !ch->delta.is_zero())) return "";
  if (!dyadic(sp.period) || sp.lo[0] != 0) return "";
  const numeric T = sp.period, g = T / numeric(static_cast<long>(N));
  if (!power_of_two(T) || !power_of_two(g) || (N == 2 && sp.lo[1] != g)) return "";
  std::vector<std::vector<Break>> brs(C, std::vector<Break>(N));
  for (size_t ci = 0; ci < C; ++ci)
    for (size_t i = 0; i < N; ++i) {
      brs[ci][i] = break_of(sp, chs[ci]->c, i);
      brs[ci][i].delta = i == 0 && !chs[ci]->delta.is_zero();
      // Not a break of the first channel: the pieces would not alternate with k's parity.
      if (ci == 0 && brs[ci][i].e.empty() && !brs[ci][i].delta) return "";
    }
  const double gd = g.to_double();
  auto sigma_0 = [&](double tol) {
    auto dropped = [&](double sig) {
      double sum = 0;
      for (int m = 0; m < 200; ++m) {
        double b = 0;
        for (size_t ci = 0; ci < C; ++ci)
          for (const Break& x : brs[ci])
            b = std::max(b, break_bound(x, chs[ci]->delta, sig, (0.5 * gd + m * gd) / sig));
        sum += b;
        if (b < 1e-30) break;
      }
      return 2 * sum;
    };
    double sig = T.to_double();
    while (sig > 1e-4 * T.to_double() && !(dropped(sig) <= tol)) sig *= 0.995;
    return sig;
  };
  const double sf = sigma_0(kTolFloat), sd = sigma_0(1e-13);
  // E q(p + U), Horner in p (gauss_mean_coefs) and s2.
  bool s2 = false;
  auto mean = [&](const std::vector<ex>& c, const std::string& p) {
    s2 |= c.size() > 2;  // a sigma^2 term from degree 2 on
    return horner(gauss_mean_coefs(c), p);
  };
  bool constant = C == 1;
  for (const auto& c : sp.c) constant &= c.size() <= 1;
  const std::string gl = lit(gd), y = "(" + sp.y + ")";
  const std::string Tl = lit(T.to_double());
  std::string o;
  o += "  if constexpr (std::is_same<T, float>::value || std::is_same<T, double>::value) {\n";
  o += "    if (sigma >= (sizeof(T) < sizeof(double) ? T(1e-30) : T(1e-300)) && sigma < (sizeof(T) < "
       "sizeof(double) ? " +
       lit(sf) + " : " + lit(sd) + ")" + (gd < 1 ? " && abs(" + sp.y + ") <= T(1e30)" : std::string()) +
       ") {  // the nearest break alone\n";
  // Two shapes need neither x's piece nor the side of the break (box_tent_periodic_hot for both):
  // - a pulse train (constant: N = 2, piece 0 on [0, g), piece 1 on [g, T)): with e = x - T rint(x / T)
  //   exact in [-g, g], piece 0 holds x iff e >= 0, the nearest break is min(|e|, g - |e|) away
  //   (exact: g - |e| is Sterbenz when it is the smaller), and piece 0's mass is
  //   1/2 + copysign(1/2 - Phic, e);
  // - one linear piece a + b t and one jump per period (fract): the mean is a + b e + b T P(U < -e),
  //   P = 1/2 - copysign(1/2 - Phic(|e| / sigma), e).
  // (The other breaks' tails are what sigma_0 drops.)
  const bool linear = C == 1 && N == 1 && sp.c[0].size() <= 2 && sp.delta.is_zero();
  if (constant || linear) {
    const std::string it = lit(1 / T.to_double());
    o += "      const T e = " +
         std::string(T == 1 ? y + " - rint" + y
                            : "(" + y + " * " + it + " - rint(" + y + " * " + it + ")) * " + Tl) +
         ";  // exact, in [-T/2, T/2]\n";
    auto coef = [&](size_t j, size_t k) {
      return k < sp.c[j].size() ? ex_to<numeric>(sp.c[j][k].evalf()) : numeric(0);
    };
    std::string v;
    bool ranged;
    if (constant) {
      o += "      const T ea = abs(e);\n";
      o += "      const T t = detail::min2(detail::min2(ea, " + gl +
           " - ea) * (T(1) / sigma), detail::tail_cut<T>());\n";
      o += j_chain(1, false, "      ");
      o += "      const T p0 = T(0.5) + std::copysign(T(0.5) - j0, e);  // piece 0's mass\n";
      const numeric a = coef(1, 0), b = coef(0, 0) - coef(1, 0);
      v = b == 1 ? std::string("p0") : lit(b.to_double()) + " * p0";
      if (!a.is_zero()) v = lit(a.to_double()) + " + " + v;
      // p0 = 1/2 + copysign(1/2 - Phic, e) with Phic in [0, 1] rounds into [0, 1].
      ranged = v == "p0";
    } else {
      o += "      const T t = detail::min2(abs(e) * (T(1) / sigma), detail::tail_cut<T>());\n";
      o += j_chain(1, false, "      ");
      o += "      const T P = T(0.5) - std::copysign(T(0.5) - j0, e);  // P(U < -e)\n";
      const numeric a = coef(0, 0), b = coef(0, 1), bT = b * T;
      v = b == 1 ? std::string("e") : lit(b.to_double()) + " * e";
      if (!a.is_zero()) v = lit(a.to_double()) + " + " + v;
      v += bT == 1 ? std::string(" + P") : " + " + lit(bT.to_double()) + " * P";
      // fract: e + P lies in [0, 1] (e >= 0: P = Phic(e / sigma) <= 1/2 and tiny where e ~ 1/2; e < 0:
      // P <= 1).
      ranged = a.is_zero() && b == 1 && T == 1;
    }
    const std::string extra = coef_text(sp.break_extra);
    *in_range = ranged && extra.empty() && sp.lead.empty();
    o += "      return " + sp.lead + v + (extra.empty() ? "" : " + " + extra) + ";\n    }\n  }\n";
    return o + general_call(general, *in_range ? clamp : "");
  }
  std::vector<std::string> vals(C);
  o += "      const T u = " + (gd == 1 ? y : y + " * " + lit(1 / gd)) + ";\n";
  o += "      const T k = floor(u);\n      const T j = rint(u);\n";
  o += "      const T d = " + std::string(gd == 1 ? "u - j" : "(u - j) * " + gl) + ";  // exact\n";
  o += "      const T t = detail::min2(abs(d) * (T(1) / sigma), detail::tail_cut<T>());\n";
  if (N == 2) o += "      const T par = k - T(2) * floor(k * T(0.5));  // x's piece\n";
  size_t ne = 0;
  bool any_delta = false;
  for (size_t ci = 0; ci < C; ++ci)
    for (const Break& b : brs[ci]) ne = std::max(ne, b.e.size()), any_delta |= b.delta;
  // +1: the break right of x (j = k + 1), -1: x at or right of it; 0/1 blends, no selects.
  o += "      const T sg = T(2) * (j - k) - T(1);\n";
  o += "      const T p = " + std::string(gd == 1 ? "u - k" : "(u - k) * " + gl) +
       ";  // x's offset into its piece\n";
  if (N == 2) {
    o += "      const T p1 = " + gl + " + p;\n";
    o += "      const T pj = par + (j - k) * (T(1) - T(2) * par);  // the break's parity\n";
  }
  bool no_j0 = true;
  for (size_t ci = 0; ci < C; ++ci) {
    const auto& br = brs[ci];
    std::vector<std::string> et(ne);
    std::string base;
    if (N == 1) {
      base = mean(chs[ci]->c[0], "p");
      for (size_t k = 0; k < ne; ++k) {
        const std::string c = k < br[0].e.size() ? coef_text(br[0].e[k]) : "";
        et[k] = c.empty() ? "" : c + " * j" + std::to_string(k);
      }
    } else {
      base =
          "(par * (" + mean(chs[ci]->c[1], "p1") + ") + (T(1) - par) * (" + mean(chs[ci]->c[0], "p") + "))";
      for (size_t k = 0; k < ne; ++k) {
        const std::string a = k < br[1].e.size() ? coef_text(br[1].e[k]) : "",
                          b = k < br[0].e.size() ? coef_text(br[0].e[k]) : "";
        const std::string c = a == b ? a
                                     : "(pj * " + (a.empty() ? std::string("T(0)") : a) +
                                           " + (T(1) - pj) * " + (b.empty() ? std::string("T(0)") : b) + ")";
        et[k] = c.empty() ? "" : c + " * j" + std::to_string(k);
      }
    }
    no_j0 &= et.empty() || et[0].empty();
    std::string v = base;
    const std::string term = horner(et, "(sg * sigma)");
    if (term != "T(0)") v += " + sg * (" + term + ")";
    // theta's phi_sigma sum: the delta sits at the break (both neighbours of x are such breaks).
    if (br[0].delta) v += " + " + coef_text(chs[ci]->delta) + " * ph";
    const std::string extra = coef_text(chs[ci]->break_extra);
    vals[ci] = extra.empty() ? v : v + " + " + extra;
  }
  o += j_chain(ne, any_delta, "      ", no_j0 && !any_delta);
  if (s2) o += "      const T s2 = sigma * sigma;\n";
  std::string ret = sp.lead + vals[0];
  if (C > 1) {  // finish with @i replaced (at most 9 channels: @1 cannot clash with @10)
    ret = sp.finish;
    for (size_t ci = C; ci-- > 0;) {
      const std::string at = "@" + std::to_string(ci);
      for (size_t k = ret.find(at); k != std::string::npos; k = ret.find(at, k + 1))
        ret.replace(k, at.size(), "(" + vals[ci] + ")");
    }
  }
  o += "      return " + ret + ";\n    }\n  }\n";
  return o + general_call(general, "");
}

std::string gauss_periodic_fast_cpp(const GaussPeriodicSpec& sp) {
  return gauss_periodic_fast(sp, Lang::Cpp);
}
std::string gauss_periodic_fast_glsl(const GaussPeriodicSpec& sp) {
  return gauss_periodic_fast(sp, Lang::Glsl);
}

}  // namespace bl::rulegen
