// blverify: double-precision references (see reference.hpp).
#include "reference.hpp"

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <exception>
#include <vector>

#include "quad_core.hpp"

namespace blv {
namespace {

constexpr double kTol = 1e-14;              // tanh_sinh termination tolerance (relative to L1)
constexpr std::size_t kPieceCap = 4000;     // most pieces one direct reference may use
constexpr double kJumpCap = 1.5e6;          // most jumps on each side for the jump-sum reference
constexpr double kPi = 3.14159265358979323846;
constexpr double kInvSqrt2Pi = 0.39894228040143267794;
constexpr double kInf = std::numeric_limits<double>::infinity();

boost::math::quadrature::tanh_sinh<double>& integrator() {
  thread_local boost::math::quadrature::tanh_sinh<double> ts;  // not const-callable in Boost 1.74
  return ts;
}

double quad(const std::function<double(double)>& f, double a, double b, double* err, double* l1) {
  try {
    return integrator().integrate(f, a, b, kTol, err, l1);
  } catch (const std::exception&) {  // Boost raises when it meets a non-finite value
    *err = std::numeric_limits<double>::infinity();
    *l1 = *err;
    return std::numeric_limits<double>::quiet_NaN();
  }
}

// Adaptive Gauss-Kronrod 31, depth 8 (the cross-check for wide pieces). Its criterion is relative to the
// running estimate, so twice the integrand's size is added (and its integral subtracted): else an
// integral that is zero up to rounding recurses to full depth.
double gk_double(const std::function<double(double)>& f, double a, double b, double* err, double* l1) {
  try {
    double c = 1e-300;
    for (double u : {-0.9, -0.5, -0.1, 0.0, 0.1, 0.5, 0.9}) c = std::fmax(c, std::fabs(f(a + (b - a) * (u + 1) / 2)));
    c *= 2;  // f + c stays away from 0 even where f is negative
    double r = boost::math::quadrature::gauss_kronrod<double, 31>::integrate([&](double t) { return f(t) + c; }, a, b,
                                                                             8, 1e-12, err, l1);
    return r - c * (b - a);
  } catch (const std::exception&) {
    *err = std::numeric_limits<double>::infinity();
    *l1 = *err;
    return std::numeric_limits<double>::quiet_NaN();
  }
}

double phi(double t) { return kInvSqrt2Pi * std::exp(-0.5 * t * t); }

// Sum_{k=1}^{n} k^p as the Faulhaber polynomial (valid for negative n too), p = 0..3.
long double faulhaber(int p, long double n) {
  switch (p) {
    case 0: return n;
    case 1: return n * (n + 1) / 2;
    case 2: return n * (n + 1) * (2 * n + 1) / 6;
    default: { long double f1 = n * (n + 1) / 2; return f1 * f1; }
  }
}
long double power_sum(int p, long double k_lo, long double k_hi) {  // sum_{k=k_lo}^{k_hi} k^p
  if (k_hi < k_lo) return 0;
  return faulhaber(p, k_hi) - faulhaber(p, k_lo - 1);
}

std::string fmt(const char* f, double a, double b = 0) {
  char buf[160];
  std::snprintf(buf, sizeof buf, f, a, b);
  return buf;
}

}  // namespace

struct RefEngine::Impl {
  Spec sp;               // the entry's spec, possibly with an inferred period
  std::string inferred;  // note when the period was inferred

  // Period model: I_m(k) = int_0^T tau^m g(kT + tau) dtau = sum_j p[m][j] k^j on each side of 0.
  struct Side {
    bool valid = false;
    double p[3][3] = {};
    std::string why;
  };
  bool model_built = false;
  Side pos, neg;
  bool one_sided = false;  // the same quadratic on both sides of 0
  bool degree0 = false;    // g periodic
  std::vector<double> fa, fb;  // Fourier coefficients (index n)

  explicit Impl(const Spec& s) : sp(s) { infer_period(); }

  void infer_period() {
    if (sp.period > 0 || !sp.breaks.empty() || !sp.singular.empty() || !sp.bounded()) return;
    std::vector<double> probes;
    for (int i = 0; i < 20; ++i) probes.push_back(-3.7 + 0.41 * i);                  // near 0
    for (int i = 0; i < 20; ++i) probes.push_back(-1e6 + 1.0527e5 * i + 0.123 * i);  // far out
    for (double T : {2 * kPi, kPi, 1.0, 2.0}) {
      bool ok = true;
      for (double s : probes) {
        double a = sp.g(s), b = sp.g(s + T);  // s + T is rounded: allow for |s| ulps
        double tol = 1e-12 * std::fmax(1.0, std::fabs(a)) + 16 * std::numeric_limits<double>::epsilon() * std::fabs(s);
        if (!(std::fabs(a - b) <= tol)) { ok = false; break; }
      }
      if (ok) {
        sp.period = T;
        sp.periodic = true;
        inferred = "period " + fmt("%.17g", T) + " inferred numerically (the catalog gives none)";
        return;
      }
    }
  }

  // Direct quadrature over t in [fixed.front(), fixed.back()], split at every break and feature
  // point. A piece wider than 2 units of s is also integrated by adaptive Gauss-Kronrod: tanh_sinh
  // returns an unresolved oscillation with a tiny error estimate (sin over 2400 periods: 3e-7 off,
  // estimate 1e-15). When the two disagree the piece is cut into up to 64 parts; if those are still
  // wider than 2 units and disagree with Gauss-Kronrod, the result is marked unresolved (non-finite).
  QuadSum<double> direct(double x0, double c, const std::vector<double>& fixed,
                         const std::function<double(double)>& w, bool* capped) {
    std::vector<Piece<double>> pieces;
    *capped = !make_pieces<double>(sp, x0, c, fixed, kPieceCap, &pieces);
    if (*capped) return {};
    auto g = [this](double s) { return sp.g(s); };
    auto ts = [](const std::function<double(double)>& f, double a, double b, double* e, double* l) {
      return quad(f, a, b, e, l);
    };
    QuadSum<double> sum;
    auto add = [&sum](const QuadSum<double>& q) {
      sum.value += q.value;
      sum.err += q.err;
      sum.l1 += q.l1;
      sum.pieces += q.pieces;
      sum.finite = sum.finite && q.finite;
    };
    std::vector<std::pair<QuadSum<double>, QuadSum<double>>> checks;  // (tanh_sinh, Gauss-Kronrod)
    for (const Piece<double>& p : pieces) {
      const double width = std::fabs(c) * (p.t1 - p.t0);
      QuadSum<double> whole = integrate_pieces<double>({p}, x0, c, g, w, ts);
      if (!whole.finite) return whole;  // not finite: no reference
      if (width <= 2) {
        add(whole);
        continue;
      }
      QuadSum<double> kr = integrate_pieces<double>({p}, x0, c, g, w, gk_double);
      // Agreement to 1e-10 is enough: an unresolved oscillation is off by far more, and rounding
      // noise (f at |s| ~ 1e6) keeps both rules from agreeing much better.
      if (std::fabs(whole.value - kr.value) <= 1e-10 * whole.l1) {
        add(whole);
        continue;
      }
      const int n = static_cast<int>(std::min(64.0, std::ceil(width / 2)));
      std::vector<Piece<double>> fine;
      for (int i = 0; i < n; ++i) {
        Piece<double> q = p;
        q.t0 = i == 0 ? p.t0 : p.t0 + (p.t1 - p.t0) * i / n;
        q.t1 = i == n - 1 ? p.t1 : p.t0 + (p.t1 - p.t0) * (i + 1) / n;
        q.lo_brk = i == 0 && p.lo_brk;
        q.hi_brk = i == n - 1 && p.hi_brk;
        fine.push_back(q);
      }
      QuadSum<double> part = integrate_pieces<double>(fine, x0, c, g, w, ts);
      add(part);
      if (width / n > 2) checks.emplace_back(part, kr);
    }
    for (const auto& [part, kr] : checks)  // what matters is the error relative to the whole integral
      if (!(std::fabs(part.value - kr.value) <= 1e-10 * part.l1 + 1e-13 * sum.l1)) sum.finite = false;
    return sum;
  }

  double anchor(int m, double k, bool* ok, double* noise = nullptr) {
    const double T = sp.period;
    bool capped = false;
    QuadSum<double> q = direct(k * T, T, {0.0, 1.0}, [m, T](double t) { return std::pow(T * t, m); }, &capped);
    *ok = !capped && q.finite;
    if (noise) *noise = (q.err + 64 * std::numeric_limits<double>::epsilon() * q.l1) * T;
    return q.value * T;  // dtau = T dt
  }

  void fit_side(Side* sd, double k0, double d) {
    const double T = sp.period;
    for (int m = 0; m < 3; ++m) {
      double ks[3] = {k0, k0 + d, k0 + 2 * d}, y[3], noise = 0;
      for (int i = 0; i < 3; ++i) {
        bool ok = true;
        double nz = 0;
        y[i] = anchor(m, ks[i], &ok, &nz);
        noise = std::fmax(noise, nz);
        if (!ok || !std::isfinite(y[i])) {
          sd->why = "the integral over period " + fmt("%.0f", ks[i]) + " is not finite";
          return;
        }
      }
      double p2 = (y[0] - 2 * y[1] + y[2]) / 2;  // second difference of k^2 with step +-1 is 2
      // Coefficients at the noise level of the anchors are zero (else k^2 amplifies the noise).
      noise *= 4;
      if (std::fabs(p2) <= noise) p2 = 0;
      double p1 = (y[1] - y[0]) / (ks[1] - ks[0]) - p2 * (ks[1] + ks[0]);
      if (std::fabs(p1) <= noise) p1 = 0;
      double p0 = y[0] - p1 * ks[0] - p2 * ks[0] * ks[0];
      sd->p[m][0] = p0;
      sd->p[m][1] = p1;
      sd->p[m][2] = p2;
      // Check the quadratic model one period on and far away (the grid reaches |k| ~ 3.5e6 / T).
      // A periodic f (catalog class "periodic") is checked to k = 1000 only: its period may be
      // irrational (2 pi), and k T in double drifts from the true k-th period by k ulp(T).
      std::vector<double> far = {k0 + 3 * d, 10 * d, 1000 * d};
      if (!sp.periodic) {
        far.push_back(std::ceil(1e6 / T) * d);
        far.push_back(std::ceil(4e6 / T) * d);
      }
      for (double k : far) {
        bool ok = true;
        double nk = 0, yk = anchor(m, k, &ok, &nk), pk = p0 + p1 * k + p2 * k * k;
        double scale = std::fmax(1.0, std::fmax(std::fabs(yk), std::fabs(p0) + std::fabs(p1 * k) + std::fabs(p2 * k * k)));
        scale = std::fmax(scale, nk / (64 * std::numeric_limits<double>::epsilon()));
        if (!ok || !(std::fabs(yk - pk) <= 1e-11 * scale)) {
          sd->why = fmt("the integral over a period is not quadratic in the period index (k = %.0f: %.3g off)", k,
                        std::fabs(yk - pk) / scale);
          return;
        }
      }
    }
    sd->valid = true;
  }

  void build_model() {
    if (model_built) return;
    model_built = true;
    fit_side(&pos, 0, 1);
    fit_side(&neg, -1, -1);
    if (pos.valid && neg.valid) {
      one_sided = true;
      for (int m = 0; m < 3; ++m)
        for (int j = 0; j < 3; ++j)
          if (std::fabs(pos.p[m][j] - neg.p[m][j]) > 1e-12 * std::fmax(1.0, std::fabs(pos.p[m][j]))) one_sided = false;
    }
    if (pos.valid) {
      degree0 = true;
      for (int m = 0; m < 3; ++m)
        for (int j = 1; j < 3; ++j)
          if (std::fabs(pos.p[m][j]) > 1e-13 * std::fmax(1.0, std::fabs(pos.p[m][0]))) degree0 = false;
    }
  }

  bool fourier_coef(std::size_t n, double* a, double* b) {
    while (fa.size() <= n) {
      std::size_t k = fa.size();
      const double T = sp.period;
      bool c1 = false, c2 = false;
      QuadSum<double> qa = direct(0.0, T, {0.0, 1.0}, [k](double t) { return 2 * std::cos(2 * kPi * k * t); }, &c1);
      QuadSum<double> qb = direct(0.0, T, {0.0, 1.0}, [k](double t) { return 2 * std::sin(2 * kPi * k * t); }, &c2);
      if (c1 || c2 || !qa.finite || !qb.finite) return false;
      fa.push_back(qa.value);
      fb.push_back(qb.value);
    }
    *a = fa[n];
    *b = fb[n];
    return true;
  }

  Ref gaussian_many(double x, double sigma) {
    Ref r;
    build_model();
    const double T = sp.period;
    if (one_sided && degree0) {
      double a0, b0;
      if (!fourier_coef(0, &a0, &b0)) { r.why = "Fourier coefficient not finite"; return r; }
      double xr = std::fmod(x, T), v = a0 / 2;
      for (std::size_t n = 1;; ++n) {
        double damp = std::exp(-2 * kPi * kPi * double(n * n) * sigma * sigma / (T * T));
        if (damp < 1e-19) break;
        double an, bn;
        if (!fourier_coef(n, &an, &bn)) { r.why = "Fourier coefficient not finite"; return r; }
        double ang = 2 * kPi * double(n) * xr / T;
        v += damp * (an * std::cos(ang) + bn * std::sin(ang));
      }
      r.ok = true;
      r.value = v;
      r.method = "fourier";
      return r;
    }
    if (one_sided) {
      // g(s) = A0(tau) + A1(tau) s + A2(tau) s^2 with A_j periodic (tau = s mod T); for more than
      // 40 periods under the Gaussian their oscillating parts are damped below 1e-20.
      const auto& P = pos.p;  // P[m][j]
      double A0 = (P[0][0] - P[1][1] / T + P[2][2] / (T * T)) / T;
      double A1 = (P[0][1] / T - 2 * P[1][2] / (T * T)) / T;
      double A2 = P[0][2] / (T * T * T);
      r.ok = true;
      r.value = A0 + A1 * x + A2 * (x * x + sigma * sigma);
      r.method = "period-mean";
      return r;
    }
    // Different structure on the two sides of 0 (trunc-like): direct, as far as affordable.
    Ref d = gaussian_direct(x, sigma);
    if (!d.ok && d.why.find("pieces") != std::string::npos && piecewise_constant())
      return gaussian_jumps(x, sigma);
    if (!d.ok && d.why.find("pieces") != std::string::npos)
      d.why = "no reference: f has a different period structure on each side of 0 and sigma/T is too large for "
              "direct quadrature (" + (!pos.valid ? pos.why : !neg.valid ? neg.why : "f differs between k < 0 and k >= 0") + ")";
    return d;
  }

  // g constant between the breaks up to the rounding of its formula (checked at 5 points of every
  // interval of 10 sample periods from -4e6 to 4e6): trunc^2 = floor(|s|)^2.
  int pw_const = -1;
  bool piecewise_constant() {
    if (pw_const >= 0) return pw_const == 1;
    pw_const = 0;
    const double T = sp.period;
    if (!(T > 0)) return false;
    std::vector<double> br = sp.breaks;
    for (double& b : br) b = b - T * std::floor(b / T);
    std::sort(br.begin(), br.end());
    br.push_back(br.empty() ? T : br.front() + T);
    if (br.size() == 1) br.insert(br.begin(), 0.0);
    for (double k : {-4e6, -1000.0, -3.0, -2.0, -1.0, 0.0, 1.0, 2.0, 1000.0, 4e6}) {
      for (std::size_t i = 0; i + 1 < br.size(); ++i) {
        const double a = k * T + br[i], b = k * T + br[i + 1], v = sp.g(0.5 * (a + b));
        for (double u : {0.01, 0.25, 0.75, 0.99})
          if (!(std::fabs(sp.g(a + u * (b - a)) - v) <= 1e-12 * std::fmax(1.0, std::fabs(v)))) return false;
      }
    }
    pw_const = 1;
    return true;
  }

  // Piecewise-constant g with jumps J_b = g(b) - g(b-) only at the breaks b (right-continuous):
  //   E[g(x+U)] = g(x_c) + sum_{b > x} J_b P(x+U >= b) - sum_{b <= x} J_b P(x+U < b),
  // x_c in x's own interval; tail probabilities by erfc (double), summed in long double over breaks within
  // 13 sigma (the rest is below 1e-37 of the jump sizes). An exact sum, no quadrature: it serves
  // where direct quadrature would need more than kPieceCap pieces (sigma >> period).
  Ref gaussian_jumps(double x, double sigma) {
    Ref r;
    const double T = sp.period;
    std::vector<double> br = sp.breaks;
    for (double& b : br) b = b - T * std::floor(b / T);
    std::sort(br.begin(), br.end());
    if (br.empty()) br.push_back(0.0);
    const double k0 = std::floor(x / T);
    const double reach = 13 * sigma;
    // ~0.2 us per jump: sigma = 1e4 periods costs 0.05 s a point; sigma = 1e6 periods (2.6e7 jumps,
    // ~5 s a point, ~3 min for one entry's grid) is left out of routine runs.
    if (reach / T > kJumpCap) {
      r.why = "no reference: more than 3e6 jumps under the kernel for the exact jump sum";
      return r;
    }
    // the interval of x: between consecutive breaks around x
    long double sum = 0, l1 = 0;
    // Both neighbours of b: a break that is not a double (3/10) lies strictly between b and one of
    // them, and g(b) itself is on the break's exact side.
    auto jump = [this](double b) { return sp.g(std::nextafter(b, kInf)) - sp.g(std::nextafter(b, -kInf)); };
    double lo_b = -kInf, hi_b = kInf;
    const double kmax = std::ceil(reach / T) + 2;
    for (double dk = -kmax; dk <= kmax; dk += 1) {
      for (double off : br) {
        const double b = (k0 + dk) * T + off;
        if (std::fabs(b - x) > reach) continue;
        const double J = jump(b);
        if (b > x) {
          hi_b = std::fmin(hi_b, b);
          const long double t =
              static_cast<long double>(J * 0.5 * std::erfc((b - x) / (sigma * std::sqrt(2.0))));
          sum += t;
          l1 += std::fabs(static_cast<double>(t));
        } else {
          lo_b = std::fmax(lo_b, b);
          const long double t =
              static_cast<long double>(J * 0.5 * std::erfc((x - b) / (sigma * std::sqrt(2.0))));
          sum -= t;
          l1 += std::fabs(static_cast<double>(t));
        }
      }
    }
    const double xc = std::isfinite(lo_b) && std::isfinite(hi_b) ? 0.5 * (lo_b + hi_b) : x;
    const double g0 = sp.g(xc);
    r.ok = true;
    r.value = static_cast<double>(g0 + sum);
    r.l1 = std::fabs(g0) + static_cast<double>(l1);
    r.err = 1e-15 * r.l1;
    r.method = "jump-sum";
    return r;
  }

  Ref gaussian_direct(double x, double sigma) {
    Ref r;
    bool capped = false;
    r.method = "direct";
    QuadSum<double> q = direct(x, sigma, {-kGaussWindow, kGaussWindow}, phi, &capped);
    if (capped) { r.why = "too many pieces for direct quadrature"; return r; }
    if (!q.finite) { r.why = "integrand not finite on the support, or not resolved by quadrature"; return r; }
    if (!sp.bounded()) {
      // Unbounded g: the mass may lie beyond 12 sigma (for exp-like growth the peak sits near
      // t = a sigma). Probe the log of the integrand at t = 12, 16, .., 40, 80, .., 40 * 2^24 on both
      // sides. Where g overflows (or between probes) it is bounded by assuming log|g| grows at most
      // like 4 |s| from the last probe (e^{2s}, cosh^2, polynomials are well inside).
      auto negligible = [&](double from, double lim) {
        const double log_lim = std::log(lim), log_norm = std::log(kInvSqrt2Pi);
        for (double side : {1.0, -1.0}) {
          double last_s = x, last_log = std::log(std::fabs(sp.g(x)));  // may be -inf
          if (!(last_log < kInf)) last_log = 710;
          for (double t = from; t < 1.01 * kGaussWindowWide * 16777216.0; t = t < kGaussWindowWide ? t + 4 : 2 * t) {
            double s = x + side * sigma * t, gv = sp.g(s);
            if (std::isnan(gv) && !sp.in_domain(s)) break;
            double lg = std::log(std::fabs(gv));
            if (std::isnan(lg)) return false;
            if (lg == kInf) lg = std::fmax(last_log, -745.0) + 4 * std::fabs(s - last_s);  // overflow: bound it
            if (lg - 0.5 * t * t + log_norm > log_lim) return false;
            last_s = s;
            last_log = lg;
          }
        }
        return true;
      };
      if (!negligible(kGaussWindow, 1e-22 * std::fmax(1.0, std::fabs(q.value)))) {
        for (auto [a, b] : {std::pair<double, double>{-kGaussWindowWide, -kGaussWindow}, {kGaussWindow, kGaussWindowWide}}) {
          QuadSum<double> t = direct(x, sigma, {a, b}, phi, &capped);
          if (capped) { r.why = "too many pieces for direct quadrature"; return r; }
          if (!t.finite) { r.why = "integrand not finite on the support"; return r; }
          q.value += t.value;
          q.err += t.err;
          q.l1 += t.l1;
          q.pieces += t.pieces;
        }
        if (!negligible(kGaussWindowWide, 1e-22 * std::fmax(1.0, std::fabs(q.value)))) {
          r.why = "Gaussian tail beyond 40 sigma not negligible";
          return r;
        }
      }
    }
    r.pieces = q.pieces;
    r.ok = true;
    r.value = q.value;
    r.err = q.err;
    r.l1 = q.l1;
    return r;
  }

  // int over t in [t0, t1] of w(t) g(x + hw t) with w(t) = wa + wb t, summing whole periods by the
  // period model. (ds measure: alpha + beta (s - x) with alpha = wa / hw, beta = wb / hw^2.)
  bool periods_piece(double x, double hw, double t0, double t1, double wa, double wb, double* val, double* err,
                     double* l1, std::string* why) {
    const double T = sp.period;
    auto w = [wa, wb](double t) { return wa + wb * t; };
    double A = x + hw * t0, B = x + hw * t1;
    double K1 = std::ceil(A / T), K2 = std::floor(B / T);  // whole periods k = K1 .. K2-1
    bool capped = false;
    if (K2 - K1 < kManyPeriods) {
      QuadSum<double> q = direct(x, hw, {t0, t1}, w, &capped);
      if (capped || !q.finite) { *why = capped ? "too many pieces" : "integrand not finite"; return false; }
      *val += q.value;
      *err += q.err;
      *l1 += q.l1;
      return true;
    }
    double tK1 = (K1 * T - x) / hw, tK2 = (K2 * T - x) / hw;
    for (auto [a, b] : {std::pair<double, double>{t0, tK1}, {tK2, t1}}) {
      if (!(b > a)) continue;
      QuadSum<double> q = direct(x, hw, {a, b}, w, &capped);
      if (capped || !q.finite) { *why = "partial period: integrand not finite"; return false; }
      *val += q.value;
      *err += q.err;
      *l1 += q.l1;
    }
    const long double alpha = wa / hw, beta = wb / (static_cast<long double>(hw) * hw);
    auto side_sum = [&](const Side& sd, long double klo, long double khi) -> long double {
      if (khi < klo) return 0;
      long double s = 0;
      for (int j = 0; j < 3; ++j) {
        s += (alpha - beta * x) * sd.p[0][j] * power_sum(j, klo, khi);
        s += beta * T * sd.p[0][j] * power_sum(j + 1, klo, khi);
        s += beta * sd.p[1][j] * power_sum(j, klo, khi);
      }
      return s;
    };
    long double total = 0;
    long double lo = K1, hi = K2 - 1;
    if (hi >= 0 && lo <= hi) {
      if (!pos.valid) { *why = "period model (k >= 0): " + pos.why; return false; }
      total += side_sum(pos, std::max<long double>(lo, 0), hi);
    }
    if (lo < 0 && lo <= hi) {
      if (!neg.valid) { *why = "period model (k < 0): " + neg.why; return false; }
      total += side_sum(neg, lo, std::min<long double>(hi, -1));
    }
    *val += static_cast<double>(total);
    return true;
  }

  Ref boxtent(double x, double hw) {
    Ref r;
    const bool tent = sp.kernel == Kernel::Tent;
    const bool many = sp.period > 0 && 2 * hw / sp.period > kManyPeriods;
    if (!many) {
      bool capped = false;
      std::vector<double> fixed = tent ? std::vector<double>{-1, 0, 1} : std::vector<double>{-1, 1};
      QuadSum<double> q = tent ? direct(x, hw, fixed, [](double t) { return 1 - std::fabs(t); }, &capped)
                               : direct(x, hw, fixed, [](double) { return 0.5; }, &capped);
      if (capped) { r.why = "too many pieces for direct quadrature"; return r; }
      r.method = "direct";
      r.pieces = q.pieces;
      if (!q.finite) { r.why = "integrand not finite on the support, or not resolved by quadrature"; return r; }
      r.ok = true;
      r.value = q.value;
      r.err = q.err;
      r.l1 = q.l1;
      return r;
    }
    build_model();
    double v = 0, e = 0, l1 = 0;
    std::string why;
    bool ok = tent ? periods_piece(x, hw, -1, 0, 1, 1, &v, &e, &l1, &why) && periods_piece(x, hw, 0, 1, 1, -1, &v, &e, &l1, &why)
                   : periods_piece(x, hw, -1, 1, 0.5, 0, &v, &e, &l1, &why);
    r.method = "period-sum";
    if (!ok) { r.why = "no reference: " + why; return r; }
    r.ok = true;
    r.value = v;
    r.err = e;
    r.l1 = l1;
    return r;
  }

  // Rounding sensitivity: how much g moves when its argument moves by one ulp, at the centre and
  // at the ends of the support (one-sided, so that a jump exactly there does not count).
  double sensitivity(double x, double c) const {
    double worst = 0;
    for (double s : {x, x - c, x + c}) {
      if (!sp.in_domain(s)) continue;
      double g0 = sp.g(s), gu = sp.g(std::nextafter(s, kInf)), gd = sp.g(std::nextafter(s, -kInf));
      double d = std::fmin(std::fabs(gu - g0), std::fabs(g0 - gd));
      if (std::isfinite(d)) worst = std::fmax(worst, d);
    }
    return worst;
  }

  Ref at(double x, double sigma) {
    Ref r;
    if (!sp.in_domain(x)) { r.why = "outside the domain"; return r; }
    const double c = sp.scale(x, sigma);
    if (!(sigma > 0) || !(c > 0)) {
      r.method = "point";
      r.value = sp.g(x);
      r.ok = std::isfinite(r.value);
      if (!r.ok) r.why = "f(x) not finite";
      return r;
    }
    if (sp.kernel == Kernel::Gaussian) {
      if (sp.period > 0 && 2 * kGaussWindow * sigma / sp.period > kManyPeriods) return gaussian_many(x, sigma);
      r = gaussian_direct(x, sigma);
    } else {
      r = boxtent(x, c);
    }
    if (r.ok && r.method == "direct") r.sens = sensitivity(x, c);
    return r;
  }
};

RefEngine::RefEngine(const Spec& spec) : impl_(new Impl(spec)) {}
const Spec& RefEngine::effective_spec() const { return impl_->sp; }
std::string RefEngine::inferred_period_note() const { return impl_->inferred; }
RefEngine::~RefEngine() = default;
Ref RefEngine::at(double x, double sigma) { return impl_->at(x, sigma); }

std::string RefEngine::period_model_summary() {
  const Impl& m = *impl_;
  if (!m.model_built) return "";
  std::string s = m.degree0 ? "periodic" : (m.one_sided ? "quadratic in the period index" : "two-sided");
  if (!m.pos.valid) s += "; k>=0 model invalid: " + m.pos.why;
  if (!m.neg.valid) s += "; k<0 model invalid: " + m.neg.why;
  return s;
}

}  // namespace blv
