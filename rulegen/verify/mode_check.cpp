// blverify: Rule 2 against an independent reference (see rules_check.hpp). The reference uses only
// the plain function f from the registry: the piece containing mu from the atomic's breaks, the
// mode as the global maximum of log f_Y(f(x)) = -(x - mu)^2 / (2 sigma^2) - log|f'(x)| over the
// piece (f' by Richardson-extrapolated central differences; a scan, then Brent), and f_Y at that
// mode from the probability of a small interval, P(|Y - mY| < h) / (2 h) with the interval's ends
// inverted by TOMS 748 (Richardson in h). So neither the engine's derivative nor its mode equation
// enters. Ties (tanh at mu = 0 with two equal modes) take the larger x, like the emitted rule.
#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/roots.hpp>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "rules_check.hpp"

#if __has_include(<bandlimit/rules_mode.hpp>)
#include <bandlimit/rules_mode.hpp>
#define BLV_HAVE_MODE 1
#else
#define BLV_HAVE_MODE 0
#endif

namespace blv {

#if BLV_HAVE_MODE
namespace {

using Fn = double (*)(double);

double Phi(double z) {
  return 0.5 * std::erfc(-z / std::sqrt(2.0));
}
double Phic(double z) {
  return 0.5 * std::erfc(z / std::sqrt(2.0));
}
// Phi(u) - Phi(v) for u >= v without cancellation in the upper tail.
double Phi_diff(double u, double v) {
  return v > 0 ? Phic(v) - Phic(u) : Phi(u) - Phi(v);
}

struct Piece {
  double lo, hi;  // open; may be infinite
};

// The piece of the reduced mu between consecutive breaks (the nearest when mu is outside the domain).
Piece piece_of(const bl::registry::AtomicInfo& a, double* mu) {
  std::vector<double> cuts;
  if (a.period > 0) {
    const double b0 = a.breaks[0];
    *mu -= a.period * std::floor((*mu - b0) / a.period);
    for (int i = 0; i < a.nbreaks; ++i) cuts.push_back(a.breaks[i]);
    cuts.push_back(b0 + a.period);
  } else {
    cuts.push_back(a.domain_lo);
    for (int i = 0; i < a.nbreaks; ++i)
      if (a.breaks[i] > a.domain_lo && a.breaks[i] < a.domain_hi) cuts.push_back(a.breaks[i]);
    cuts.push_back(a.domain_hi);
  }
  for (size_t i = 0; i + 2 < cuts.size(); ++i)
    if (*mu < cuts[i + 1]) return {cuts[i], cuts[i + 1]};
  return {cuts[cuts.size() - 2], cuts.back()};
}

double dist_to_end(const Piece& p, double x) {
  return std::min(x - p.lo, p.hi - x);
}

double deriv(Fn f, const Piece& p, double x) {
  const double h = 1e-3 * std::min(std::max(1.0, std::abs(x)), 0.5 * dist_to_end(p, x));
  auto D = [&](double e) { return (f(x + e) - f(x - e)) / (2 * e); };
  return (4 * D(h / 2) - D(h)) / 3;
}

struct Ref {
  double x = NAN, mY = NAN, sY = NAN;
};

Ref reference(Fn f, const Piece& p, double mu, double s) {
  // Where f' does not resolve in double (tanh saturated, the last ulps before tan's pole) the point is
  // no candidate.
  auto L = [&](double x) {
    const double d = std::abs(deriv(f, p, x));
    if (!(d > 0) || !std::isfinite(d)) return -std::numeric_limits<double>::infinity();
    return -(x - mu) * (x - mu) / (2 * s * s) - std::log(d);
  };
  const double c = std::min(std::max(mu, p.lo), p.hi), W = 10 * s + 4 * s * s;
  const double lo = std::max(p.lo, c - W), hi = std::min(p.hi, c + W);
  auto inside = [&](double x) {
    return x > p.lo && x < p.hi && dist_to_end(p, x) > 1e-9 * std::max(1.0, std::abs(x));
  };
  std::vector<double> xs;
  for (int i = 0; i <= 4000; ++i) xs.push_back(lo + (hi - lo) * i / 4000.0);
  for (int k = 1; k <= 60; ++k) {
    if (std::isfinite(p.lo) && lo == p.lo) xs.push_back(lo + (hi - lo) * std::ldexp(1.0, -k));
    if (std::isfinite(p.hi) && hi == p.hi) xs.push_back(hi - (hi - lo) * std::ldexp(1.0, -k));
  }
  std::sort(xs.begin(), xs.end());
  double best = -INFINITY;
  size_t bi = 0;
  for (size_t i = 0; i < xs.size(); ++i) {
    if (!inside(xs[i])) continue;
    const double v = L(xs[i]);
    if (v >= best - 1e-12 * (1 + std::abs(best))) {
      if (v > best) best = v;
      bi = i;
    }
  }
  if (!(best > -INFINITY)) return {};
  // Brent in u = (x - xb) / s, so the tolerance is relative to sigma, not to |x|.
  const double xb = xs[bi];
  double a = bi > 0 ? xs[bi - 1] : xb, b = bi + 1 < xs.size() ? xs[bi + 1] : xb;
  while (!inside(a)) a = (a + xb) / 2;
  while (!inside(b)) b = (b + xb) / 2;
  const auto r = boost::math::tools::brent_find_minima([&](double u) { return -L(xb + s * u); }, (a - xb) / s,
                                                       (b - xb) / s, std::numeric_limits<double>::digits / 2);
  Ref ref;
  ref.x = xb + s * r.first;
  ref.mY = f(ref.x);
  // f_Y(mY) from P(|Y - mY| < h): invert f at mY +- h inside the piece.
  const double fp = deriv(f, p, ref.x);
  const double sy_est = s * std::abs(fp) * std::exp((ref.x - mu) * (ref.x - mu) / (2 * s * s));
  auto inverse = [&](double y) {
    const double dir = ((y > ref.mY) == (fp > 0)) ? 1 : -1;
    double a0 = ref.x, step = s;
    double b0 = a0;
    for (int k = 0; k < 200; ++k) {
      b0 = a0 + dir * step;
      if (!inside(b0)) b0 = (a0 + (dir > 0 ? p.hi : p.lo)) / 2;
      if ((f(b0) - y) * (f(a0) - y) <= 0) break;
      a0 = b0;
      step *= 2;
    }
    if (!(a0 != b0) || !((f(b0) - y) * (f(a0) - y) <= 0))
      return std::nan("");  // no bracket: the case is skipped
    boost::uintmax_t it = 200;
    try {
      const auto rr = boost::math::tools::toms748_solve([&](double x) { return f(x) - y; }, std::min(a0, b0),
                                                        std::max(a0, b0),
                                                        boost::math::tools::eps_tolerance<double>(52), it);
      return (rr.first + rr.second) / 2;
    } catch (const std::exception&) {
      return std::nan("");
    }
  };
  auto density = [&](double h) {
    double x1 = inverse(ref.mY - h), x2 = inverse(ref.mY + h);
    if (x1 > x2) std::swap(x1, x2);
    return Phi_diff((x2 - mu) / s, (x1 - mu) / s) / (2 * h);
  };
  // h: small against the density's own scale in y, |f'| times the x-scale (sigma, or the distance to
  // a piece end), which can be far below sY where the fit is poor (log of mostly negative X).
  const double h = 1e-4 * std::abs(fp) * std::min(s, 0.5 * dist_to_end(p, ref.x));
  (void)sy_est;
  // The reference cannot decide a mode at a piece end (it evaluates strictly inside), nor a density
  // whose interval spans few ulps of mY (tanh saturated): such cases are skipped.
  if (dist_to_end(p, ref.x) < 1e-4 * s + 4e-9 * std::max(1.0, std::abs(ref.x)) ||
      h < 1e6 * (std::nextafter(std::abs(ref.mY), INFINITY) - std::abs(ref.mY)))
    return {};
  const double fy = (4 * density(h / 2) - density(h)) / 3;
  ref.sY = 1 / (std::sqrt(2 * M_PI) * fy);
  return ref;
}

}  // namespace

std::vector<RuleCheck> check_rule2() {
  std::vector<RuleCheck> out;
  int n = 0, nt = 0;
  const auto* rules = bl::registry::rule2_entries<double>(&n);
  const auto* table = bl::registry::entries<double>(&nt);
  for (int i = 0; i < n; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    RuleCheck rc;
    rc.cpp = rules[i].cpp;
    rc.kind = "mode reference";
    rc.bound_mean = 1e-5;
    rc.bound_var = 1e-5;
    rc.tolerance =
        "|mY - mY_ref| <= 1e-5 max(sY_ref, 1e-7 |mY_ref|) (worst_mean, in those units) and |sY/sY_ref - 1| "
        "<= 1e-5 "
        "(worst_var); reference: global maximum of the density of Y on the piece (scan + Brent), f_Y(mY) "
        "from "
        "P(|Y - mY| < h)/(2h)";
    double worst_score = -1;
    Fn f = nullptr;
    for (int j = 0; j < nt && !f; ++j)
      if (table[j].atomic == rules[i].atomic) f = table[j].plain;
    for (double mu0 : {-3.0, -1.0, -0.2, 0.0, 0.3, 1.0, 2.5})
      for (double s : {1e-4, 0.01, 0.1, 0.5, 1.0, 2.0}) {
        const bl::stat<double> r = rules[i].fn(mu0, s);
        double mu = mu0;
        const Piece p = piece_of(*rules[i].atomic, &mu);
        const Ref ref = reference(f, p, mu, s);
        const double sY = std::sqrt(r.var);
        if (!std::isfinite(ref.mY) || !std::isfinite(ref.sY) || !(ref.sY > 0) || !std::isfinite(r.mean) ||
            !std::isfinite(r.var)) {
          ++rc.skipped;  // density underflow, a mode at a piece end, or Y unresolved in double
          continue;
        }
        ++rc.cases;
        const double em = std::abs(r.mean - ref.mY) / std::max(ref.sY, 1e-7 * std::abs(ref.mY));
        const double ev = std::abs(sY / ref.sY - 1);
        const double score = std::max(em / rc.bound_mean, ev / rc.bound_var);
        rc.worst_mean = std::max(rc.worst_mean, std::isnan(em) ? INFINITY : em);
        rc.worst_var = std::max(rc.worst_var, std::isnan(ev) ? INFINITY : ev);
        if (!(score <= worst_score)) {
          worst_score = std::isnan(score) ? INFINITY : score;
          std::ostringstream o;
          o.precision(10);
          o << "(mu " << mu0 << ", sigma " << s << "): rule (" << r.mean << ", sY " << sY << "), reference ("
            << ref.mY << ", sY " << ref.sY << ")";
          rc.worst_case = o.str();
        }
      }
    rc.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    out.push_back(rc);
  }
  return out;
}

#else
std::vector<RuleCheck> check_rule2() {
  return {};
}
#endif

}  // namespace blv
