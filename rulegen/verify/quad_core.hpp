// blverify: splitting an integration range at every break of the integrand and integrating the
// pieces. Shared by the double reference (reference.cpp) and the 50-digit one (reference_mp.cpp).
//
// All integrals are written in a scaled coordinate t: s = x0 + c t (s is the argument of f), so the
// integrator never sees the absolute position (x may be 1e6 while c is 1e-12). A break b maps to
// t = (b - x0) / c, computed in Real. On each piece the argument s is clamped to the piece's own side
// of its end breaks: rounding of x0 + c t can otherwise put a node just across a jump
// (Boost's integrators silently lose accuracy across a jump, ../../shared/TOOLCHAIN.md).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <vector>

#include <boost/math/special_functions/fpclassify.hpp>

#include "spec.hpp"

namespace blv {

template <class Real>
struct Piece {
  Real t0, t1;            // t-range
  bool lo_brk, hi_brk;    // the end is a break of f: clamp s to this piece's side
  Real s_lo, s_hi;        // absolute break positions (when lo_brk / hi_brk)
};

template <class Real>
Real step_inside_up(const Real& s) {  // the smallest value > s worth evaluating
  if constexpr (std::is_same<Real, double>::value) {
    return std::nextafter(s, std::numeric_limits<double>::infinity());
  } else {
    using std::abs;
    Real m = abs(s) > 1 ? Real(abs(s)) : Real(1);
    return s + 4 * std::numeric_limits<Real>::epsilon() * m;
  }
}
template <class Real>
Real step_inside_down(const Real& s) {
  if constexpr (std::is_same<Real, double>::value) {
    return std::nextafter(s, -std::numeric_limits<double>::infinity());
  } else {
    using std::abs;
    Real m = abs(s) > 1 ? Real(abs(s)) : Real(1);
    return s - 4 * std::numeric_limits<Real>::epsilon() * m;
  }
}

// Number of breaks of `sp` in the absolute range [lo, hi] (doubles), counting period repeats.
inline double count_breaks(const Spec& sp, double lo, double hi) {
  if (!(hi >= lo)) return 0;
  if (sp.period <= 0) {
    double n = 0;
    for (double b : sp.breaks) n += (b >= lo && b <= hi);
    return n;
  }
  double n = 0;
  std::vector<double> b0 = sp.breaks;
  if (b0.empty()) b0.push_back(0.0);  // periodic without breaks: still split once per period
  for (double b : b0) n += std::floor((hi - b) / sp.period) - std::ceil((lo - b) / sp.period) + 1;
  return n;
}

// Extra split points in t where s = x0 + c t is 0, +-1, +-2, +-4, ..., +-2^60: catalog functions
// have their features near the origin (tanh's step, smoothstep's kinks when the catalog does not
// list them), and splitting geometrically resolves them at every scale of the kernel.
template <class Real>
std::vector<Real> feature_points(const Real& x0, const Real& c, const Real& tlo, const Real& thi) {
  std::vector<Real> out;
  auto add = [&](const Real& s) {
    Real t = (s - x0) / c;
    if (t > tlo && t < thi) out.push_back(t);
  };
  add(Real(0));
  Real p = 1;
  for (int k = 0; k <= 60; ++k, p *= 2) {
    add(p);
    add(-p);
  }
  return out;
}

// Split [fixed.front(), fixed.back()] (sorted t points; inner ones are kernel kinks or window
// splits) at every break of sp strictly inside. Returns false (and no pieces) when more than
// `cap` pieces would be needed.
template <class Real>
bool make_pieces(const Spec& sp, const Real& x0, const Real& c, const std::vector<Real>& fixed,
                 std::size_t cap, std::vector<Piece<Real>>* out) {
  using std::abs;
  out->clear();
  struct Pt { Real t; bool brk; Real s; };
  std::vector<Pt> pts;
  for (const Real& t : fixed) pts.push_back({t, false, Real(0)});
  const Real tlo = fixed.front(), thi = fixed.back();
  for (const Real& t : feature_points(x0, c, tlo, thi)) pts.push_back({t, false, Real(0)});
  double a = static_cast<double>(Real(x0 + c * tlo)), b = static_cast<double>(Real(x0 + c * thi));
  if (a > b) std::swap(a, b);
  double pad = 1e-9 * std::fmax(std::fabs(a), std::fabs(b)) + 1e-300;
  a -= pad;
  b += pad;
  if (count_breaks(sp, a, b) > static_cast<double>(cap)) return false;
  // t of the break s from kx = (k T - x0) + b (+ b's rest, break_rest): formed without rounding
  // b + k T to |x|'s ulp, which at x = 1e6 + 0.3 moves a break b = 3/10 by up to 6e-11 onto x.
  auto add_break = [&](const Real& s, const Real& kx) {
    Real t = kx / c;
    if (t < tlo - 8 * std::numeric_limits<Real>::epsilon() * (abs(tlo) + 1) ||
        t > thi + 8 * std::numeric_limits<Real>::epsilon() * (abs(thi) + 1))
      return;
    pts.push_back({t, true, s});
  };
  if (sp.period > 0) {
    std::vector<double> b0 = sp.breaks;
    if (b0.empty()) b0.push_back(0.0);
    for (double bb : b0) {
      double k0 = std::ceil((a - bb) / sp.period), k1 = std::floor((b - bb) / sp.period);
      for (double k = k0; k <= k1; k += 1)
        add_break(Real(bb) + Real(k) * Real(sp.period),
                  ((Real(k) * Real(sp.period) - x0) + Real(bb)) + Real(break_rest(bb)));
    }
  } else {
    for (double bb : sp.breaks) add_break(Real(bb), (Real(bb) - x0) + Real(break_rest(bb)));
  }
  std::sort(pts.begin(), pts.end(), [](const Pt& p, const Pt& q) { return p.t < q.t; });
  // Merge points closer than a few ulps (a break on a window end or on the tent's kink).
  std::vector<Pt> m;
  for (const Pt& p : pts) {
    if (!m.empty() && abs(p.t - m.back().t) <= 8 * std::numeric_limits<Real>::epsilon() * (abs(p.t) + 1)) {
      if (p.brk && !m.back().brk) { m.back().brk = true; m.back().s = p.s; }
      continue;
    }
    m.push_back(p);
  }
  for (std::size_t i = 0; i + 1 < m.size(); ++i) {
    const Pt &p = m[i], &q = m[i + 1];
    if (q.t <= tlo || p.t >= thi) continue;
    Real t0 = p.t < tlo ? tlo : p.t, t1 = q.t > thi ? thi : q.t;
    if (!(t1 > t0)) continue;
    out->push_back({t0, t1, p.brk, q.brk, p.s, q.s});
  }
  return true;
}

// The argument s of f on piece `pc` at t, clamped to the piece's side of its end breaks.
template <class Real>
Real piece_arg(const Piece<Real>& pc, const Real& x0, const Real& c, const Real& t) {
  Real s = x0 + c * t;
  if (pc.lo_brk && s <= pc.s_lo) s = step_inside_up(pc.s_lo);
  if (pc.hi_brk && s >= pc.s_hi) s = step_inside_down(pc.s_hi);
  return s;
}

template <class Real>
struct QuadSum {
  Real value = 0, err = 0, l1 = 0;
  bool finite = true;
  long pieces = 0;
};

// Integrate w(t) g(s(t)) over the pieces with integrator `integ(f, t0, t1, &err, &l1)`.
template <class Real, class G, class W, class Integ>
QuadSum<Real> integrate_pieces(const std::vector<Piece<Real>>& pieces, const Real& x0, const Real& c,
                               G&& g, W&& w, Integ&& integ) {
  QuadSum<Real> r;
  for (const Piece<Real>& pc : pieces) {
    // Each piece is mapped onto [-1, 1]: Boost 1.74's tanh_sinh loses accuracy on a short interval
    // far from 0 (the integral of 1 over [1000, 1000 + 1e-3] comes out 2.6e-10 low), and the box
    // and tent pieces sit near t = +-1.
    const Real mid = (pc.t0 + pc.t1) / 2, half = (pc.t1 - pc.t0) / 2;
    auto f = [&](Real u) -> Real {
      Real t = mid + half * u;
      Real wt = w(t);
      if (wt == 0) return Real(0);
      return half * wt * g(piece_arg<Real>(pc, x0, c, t));
    };
    Real e = 0, l = 0;
    Real v = integ(f, Real(-1), Real(1), &e, &l);
    if (!(boost::math::isfinite)(v)) r.finite = false;
    r.value += v;
    r.err += e;
    r.l1 += l;
    ++r.pieces;
  }
  return r;
}

}  // namespace blv
