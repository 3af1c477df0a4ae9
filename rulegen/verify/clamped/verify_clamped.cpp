#include "verify_clamped.hpp"

#include <algorithm>
#include <bandlimit/rules_clamped.hpp>
#include <boost/math/differentiation/finite_difference.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

namespace blv::clamped {
namespace {

using mp50 = boost::multiprecision::cpp_bin_float_50;
const double kInf = std::numeric_limits<double>::infinity();
const double kNaN = std::numeric_limits<double>::quiet_NaN();

// Integral of g over [l, r] split at `cuts` (double tanh-sinh; endpoint singularities allowed).
double integrate(const std::function<double(double)>& g, double l, double r, std::vector<double> cuts = {}) {
  static thread_local boost::math::quadrature::tanh_sinh<double> ts(12);
  cuts.push_back(l);
  cuts.push_back(r);
  std::sort(cuts.begin(), cuts.end());
  double s = 0;
  for (size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double a = std::max(l, cuts[i]), b = std::min(r, cuts[i + 1]);
    if (!(a < b)) continue;
    s += ts.integrate(g, a, b, 1e-14);
  }
  return s;
}

// Mean and central moments 2..4 of the density w on [l, r] (two passes: moments about the mean).
struct Ref {
  double s0, mean, k2, k3, k4;
};
Ref density_moments(const std::function<double(double)>& w, double l, double r,
                    std::vector<double> cuts = {}) {
  Ref o;
  o.s0 = integrate(w, l, r, cuts);
  o.mean = integrate([&](double u) { return u * w(u); }, l, r, cuts) / o.s0;
  auto cm = [&](int k) {
    return integrate([&](double u) { return std::pow(u - o.mean, k) * w(u); }, l, r, cuts) / o.s0;
  };
  o.k2 = cm(2);
  o.k3 = cm(3);
  o.k4 = cm(4);
  return o;
}

// X ~ N(mu, sigma^2) on [a, b] by quadrature in z = (x - mu) / sigma, density relative to its
// maximum, cut where it is below e^-60.
Ref truncnorm_ref(double mu, double sigma, double a, double b, double* mass) {
  const double al = (a - mu) / sigma, be = (b - mu) / sigma;
  const double zm = std::min(std::max(0.0, al), be);
  const double reach = std::sqrt(zm * zm + 120);
  const double l = std::max(al, -reach), r = std::min(be, reach);
  // in t = z - zm: narrow intervals away from 0 keep their digits
  Ref z = density_moments([&](double t) { return std::exp(-0.5 * t * (t + 2 * zm)); }, l - zm, r - zm, {0.0});
  *mass = z.s0 * std::exp(-0.5 * zm * zm) / std::sqrt(2 * M_PI);
  return {z.s0, mu + sigma * (zm + z.mean), sigma * sigma * z.k2, std::pow(sigma, 3) * z.k3,
          std::pow(sigma, 4) * z.k4};
}

double rel(double got, double ref, double scale) {
  if (std::isnan(ref)) return std::isnan(got) ? 0 : kInf;
  if (std::isinf(ref)) return got == ref ? 0 : kInf;
  return std::abs(got - ref) / std::max(scale, std::abs(ref));
}

struct Record {
  std::string cpp;
  long points = 0;
  double worst_d = 0, worst_f = 0, bound_d = 1e-9, bound_f = 2e-5;
  std::string reference, where_d, where_f;
  void upd_d(double e, double mu, double sigma) {
    if (!(e <= worst_d)) {
      worst_d = e;
      where_d = "mu=" + std::to_string(mu) + " sigma=" + std::to_string(sigma);
    }
  }
  void upd_f(double e, double mu, double sigma) {
    if (!(e <= worst_f)) {
      worst_f = e;
      where_f = "mu=" + std::to_string(mu) + " sigma=" + std::to_string(sigma);
    }
  }
  bool ok() const { return worst_d <= bound_d && worst_f <= bound_f; }
};

const double kSigmas[] = {1e-7, 0.01, 0.3, 1, 5};

// ---- derivatives: 8th-order finite differences of the 50-digit plain function (step ~1e-6).
void verify_derivatives(std::vector<Record>& recs) {
  int n = 0, nm = 0, np = 0;
  const auto* d = bl::registry::derivative_entries<double>(&n);
  const auto* dm = bl::registry::derivative_entries<mp50>(&nm);
  const auto* pm = bl::registry::entries<mp50>(&np);
  const auto* df = bl::registry::derivative_entries<float>(&nm);
  for (int i = 0; i < n; ++i) {
    Record r{d[i].cpp};
    r.bound_d = 1e-9;
    r.reference = "8th-order finite differences of the 50-digit plain function";
    const auto& a = *d[i].atomic;
    mp50 (*plain)(mp50) = nullptr;
    for (int j = 0; j < np && !plain; ++j)
      if (pm[j].atomic->name == std::string(a.name)) plain = pm[j].plain;
    auto fd1 = [&](mp50 x) {
      return boost::math::differentiation::finite_difference_derivative<decltype(plain), mp50, 8>(plain, x);
    };
    for (double x : {-1e3, -7.3, -2.2, -0.6, -1e-3, 1e-3, 0.3, 0.77, 1.4, 2.9, 11.5, 1e3}) {
      bool near = x <= a.domain_lo || x >= a.domain_hi;
      for (int k = 0; k < a.nbreaks; ++k) {
        double t = x - a.breaks[k];
        if (a.period > 0) t -= a.period * std::round(t / a.period);
        if (std::abs(t) < 1e-4) near = true;
      }
      if (near) continue;
      mp50 ref;
      if (d[i].order == 1) {
        ref = fd1(mp50(x));
      } else {
        auto d1 = dm[i - 1].fn;
        ref = boost::math::differentiation::finite_difference_derivative<decltype(d1), mp50, 8>(d1, mp50(x));
      }
      const double rd = static_cast<double>(ref);
      r.upd_d(rel(d[i].fn(x), rd, 1.0), x, 0);
      const float xf = static_cast<float>(x);
      const double rf = static_cast<double>(d[i].order == 1 ? fd1(mp50(xf)) : dm[i].fn(mp50(xf)));
      r.upd_f(rel(df[i].fn(xf), rf, 1.0), x, 0);
      ++r.points;
    }
    recs.push_back(r);
  }
}

// ---- truncated-normal moments (the "truncnorm" entry): standardized errors.
void verify_truncnorm(std::vector<Record>& recs) {
  Record r{"bl::truncnorm::moments"};
  r.reference = "tanh-sinh quadrature of the normal density over [a, b] (in z, relative to its maximum)";
  const double offs[][2] = {{0, kInf}, {10, kInf},  {-kInf, -10}, {10, 12},   {-1, 2},  {0.5, 0.5 + 1e-6},
                            {1, 5},    {2.9, 6},    {3, 3.5},     {-30, -29}, {38, 39}, {-kInf, 0},
                            {-3, 0.2}, {100, kInf}, {-0.1, 0.1},  {4, 4.5}};
  for (double mu : {0.0, 1.0, -1e3})
    for (double sigma : {1e-8, 1e-3, 1.0, 1e3})
      for (const auto& o : offs) {
        const double a = mu + o[0] * sigma, b = mu + o[1] * sigma;
        double mass;
        const Ref ref = truncnorm_ref(mu, sigma, a, b, &mass);
        const auto m = bl::truncnorm::moments(mu, sigma, a, b);
        const double sd = std::sqrt(ref.k2);
        const double e = std::max(
            {rel(m.mass, mass, 1e-300), std::abs(m.mean - ref.mean) / std::max(sd, 1e-5 * std::abs(ref.mean)),
             rel(m.var, ref.k2, 0), std::abs(m.mu3 - ref.k3) / (sd * sd * sd), rel(m.mu4, ref.k4, 0)});
        r.upd_d(e, mu, sigma);
        const auto f = bl::truncnorm::moments<float>(float(mu), float(sigma), float(a), float(b));
        // float: inputs are rounded; judge each moment against the double result at the float inputs.
        const auto g = bl::truncnorm::moments<double>(float(mu), float(sigma), float(a), float(b));
        const double ef =
            std::max({rel(f.mean, g.mean, 0), rel(f.var, g.var, 1e-37), rel(f.mu4, g.mu4, 1e-37)});
        r.upd_f(ef, mu, sigma);
        ++r.points;
      }
  recs.push_back(r);
}

// (mu, sigma) points for an atomic with domain [lo, hi]: interior, the mean on a bound, a bound
// 10 sigma out.
std::vector<std::pair<double, double>> points_for(const bl::registry::AtomicInfo& a) {
  std::vector<std::pair<double, double>> p;
  for (double s : kSigmas)
    for (double mu : {-2.3, -0.4, 0.35, 1.7, 4.2}) p.push_back({mu, s});
  if (a.domain_lo > -kInf)
    for (double s : kSigmas) {
      p.push_back({a.domain_lo, s});
      p.push_back({a.domain_lo - 10 * s, s});
      p.push_back({a.domain_lo + 10 * s, s});
    }
  return p;
}

const bl::registry::AtomicInfo* info(const char* name) {
  for (const auto& a : bl::registry::kAtomics)
    if (std::string(a.name) == name) return &a;
  return nullptr;
}

// ---- Rule 3: the Taylor polynomial at the reference mean (derivatives by 50-digit finite
// differences) averaged by quadrature against the truncated normal.
void verify_rule3(const bl::registry::RuleEntry<double>& e, const bl::registry::RuleEntry<float>& ef,
                  Record& r) {
  int np = 0;
  const auto* pm = bl::registry::entries<mp50>(&np);
  mp50 (*plain)(mp50) = nullptr;
  for (int j = 0; j < np && !plain; ++j)
    if (std::string(pm[j].atomic->name) == e.atomic->name) plain = pm[j].plain;
  const auto& a = *e.atomic;
  r.reference =
      "quadrature of the Taylor polynomial (50-digit finite-difference derivatives) against the truncated "
      "normal";
  for (auto [mu, sigma] : points_for(a)) {
    double mass;
    const Ref t = truncnorm_ref(mu, sigma, a.domain_lo, a.domain_hi, &mass);
    const double c = t.mean;
    bool near = false;
    for (int k = 0; k < a.nbreaks; ++k) {
      double d = c - a.breaks[k];
      if (a.period > 0) d -= a.period * std::round(d / a.period);
      if (std::abs(d) < 1e-4) near = true;
    }
    if (near || !(c > a.domain_lo)) continue;
    auto d1 = [&](mp50 x) {
      return boost::math::differentiation::finite_difference_derivative<decltype(plain), mp50, 8>(plain, x);
    };
    const double f0 = static_cast<double>(plain(mp50(c))), f1 = static_cast<double>(d1(mp50(c)));
    const double f2 = static_cast<double>(
        boost::math::differentiation::finite_difference_derivative<decltype(d1), mp50, 8>(d1, mp50(c)));
    // The Taylor polynomial in z = (u - mu) / sigma against the density relative to its maximum on
    // the domain (no underflow 40 sigma out), over the part where it exceeds e^-60.
    const double al = (a.domain_lo - mu) / sigma, be = (a.domain_hi - mu) / sigma;
    const double zm = std::min(std::max(0.0, al), be), reach = std::sqrt(zm * zm + 120);
    const double zl = std::max(al, -reach), zr = std::min(be, reach), zc = (c - mu) / sigma;
    auto w = [&](double z) { return std::exp(-0.5 * (z - zm) * (z + zm)); };
    auto T = [&](double z) {
      const double d = sigma * (z - zc);
      return f0 + f1 * d + 0.5 * f2 * d * d;
    };
    const double s0 = integrate(w, zl, zr, {zm});
    double mean = integrate([&](double z) { return T(z) * w(z); }, zl, zr, {zm}) / s0;
    double var =
        integrate([&](double z) { return (T(z) - mean) * (T(z) - mean) * w(z); }, zl, zr, {zm}) / s0;
    // The rule is specified clamped to f's range: the mean into [lo, hi], the variance below
    // Popoviciu's (hi - lo)^2/4 (rule3::in_range; infinite ends clamp nothing).
    mean = std::min(std::max(mean, a.range_lo), a.range_hi);
    var = std::min(var, 0.25 * (a.range_hi - a.range_lo) * (a.range_hi - a.range_lo));
    const auto got = e.fn(mu, sigma);
    r.upd_d(std::max({rel(got.mean, mean, 1), rel(got.var, var, 1)}), mu, sigma);
    const auto gf = ef.fn(float(mu), float(sigma));
    const auto gd = e.fn(float(mu), float(sigma));
    r.upd_f(std::max({rel(gf.mean, gd.mean, 1), rel(gf.var, gd.var, 1)}), mu, sigma);
    ++r.points;
  }
}

double kernel_density(const std::string& k, double c, double s, double u, double zm_shift = 0) {
  const double z = (u - c) / s;
  if (k == "gaussian") return std::exp(-0.5 * z * z + 0.5 * zm_shift * zm_shift);
  if (k == "box") return std::abs(z) <= std::sqrt(3.0) ? 1.0 : 0.0;
  return std::max(0.0, 1 - std::abs(z) / std::sqrt(6.0));
}

// f of the atomic called name (the registry's plain function), or nullptr.
double (*plain_of(const char* name))(double) {
  int n = 0;
  const auto* es = bl::registry::entries<double>(&n);
  for (int i = 0; i < n; ++i)
    if (es[i].atomic && es[i].plain && std::string(es[i].atomic->name) == name) return es[i].plain;
  return nullptr;
}

// ---- Rule 1: (a) the renormalized kernel's truncated mean and variance by quadrature against the
// target (variance clamped as documented), (b) the entry against quadrature of f under it.
void verify_rule1(const bl::registry::RuleEntry<double>& e, const bl::registry::RuleEntry<float>& ef,
                  Record& r) {
  const auto& a = *e.atomic;
  const std::string k = e.kernel;
  r.reference = "quadrature of the renormalized kernel (moments) and of f, (f - mean)^2 under it";
  r.bound_d = 1e-9;
  const auto K = k == "gaussian" ? bl::rule1::Kernel::gaussian
                                 : (k == "box" ? bl::rule1::Kernel::box : bl::rule1::Kernel::tent);
  const double cK = k == "box" ? std::sqrt(3.0) : std::sqrt(6.0);
  for (double mu : {1e-6, 0.05, 0.4, 1.0, 3.5, 100.0})
    for (double sig_rel : {1e-7, 0.05, 0.3, 0.7, 0.99, 3.0}) {
      const double sigma = sig_rel * mu, v = sigma * sigma;
      const auto p = bl::rule1::renormalize(K, mu, v, a.domain_lo, a.domain_hi);
      const double zm = std::max(0.0, (a.domain_lo - p.center) / p.sigma);
      const double reach = k == "gaussian" ? std::sqrt(zm * zm + 120) * p.sigma : cK * p.sigma;
      const double l = std::max(a.domain_lo, p.center - reach), rr = std::min(a.domain_hi, p.center + reach);
      double target_v = v;
      if (k == "gaussian")
        target_v = std::min(v, 0.98 * mu * mu);
      else
        target_v = std::pow(std::min(cK * sigma, mu - a.domain_lo) / cK, 2);
      auto w = [&](double u) { return kernel_density(k, p.center, p.sigma, u, k == "gaussian" ? zm : 0.0); };
      // (a) in t = u - center, so the moments keep their digits when the kernel is narrow
      const Ref m =
          density_moments([&](double t) { return w(p.center + t); }, l - p.center, rr - p.center, {0.0});
      const double sd = std::sqrt(m.k2), mean = p.center + m.mean;
      r.upd_d(std::max(std::abs(mean - mu) / std::max(sd, 1e-5 * mu), rel(m.k2, target_v, 0)), mu, sigma);
      // (b) f under the kernel
      double (*pl)(double) = plain_of(a.name);  // f from the registry (any tree, not only sqrt and log)
      if (!pl) continue;
      const double s0 = integrate(w, l, rr, {p.center});
      const double fm = integrate([&](double u) { return pl(u) * w(u); }, l, rr, {p.center}) / s0;
      const double fv =
          integrate([&](double u) { return (pl(u) - fm) * (pl(u) - fm) * w(u); }, l, rr, {p.center}) / s0;
      const auto got = e.fn(mu, sigma);
      r.upd_d(std::max({rel(got.mean, fm, 1), rel(got.var, fv, 1)}), mu, sigma);
      const auto gf = ef.fn(float(mu), float(sigma));
      const auto gd = e.fn(float(mu), float(sigma));
      r.upd_f(std::max({rel(gf.mean, gd.mean, 1), rel(gf.var, gd.var, 1)}), mu, sigma);
      ++r.points;
    }
}

// ---- bimodal: jumps found by scanning the footprint, f and (f - mean)^2 integrated on the kept part.
void verify_bimodal(const bl::registry::RuleEntry<double>& e, const bl::registry::RuleEntry<float>& ef,
                    Record& r) {
  const auto& a = *e.atomic;
  r.reference = "quadrature of f uniform on the footprint cut at its single jump (jumps located by scanning)";
  int np = 0;
  const auto* pe = bl::registry::entries<double>(&np);
  double (*plain)(double) = nullptr;
  for (int j = 0; j < np && !plain; ++j)
    if (std::string(pe[j].atomic->name) == a.name) plain = pe[j].plain;
  for (double mu : {-3.97, -1.05, -0.02, 0.0, 0.03, 0.49, 0.51, 2.5, 7.999, 1e3 + 0.01})
    for (double sigma : {0.0, 1e-6, 0.01, 0.1, 0.3, 2.0}) {
      const double h = std::sqrt(3.0) * sigma, lo = mu - h, hi = mu + h;
      std::vector<double> js;  // jumps in (lo, hi]
      for (int k = 0; k < a.nbreaks; ++k) {
        const double P = a.period > 0 ? a.period : 0;
        // only jumps: fract/floor/ceil/trunc/square/step/sign have no kinks in the catalog
        if (P > 0)
          for (double j = a.breaks[k] + P * std::floor((lo - a.breaks[k]) / P); j <= hi; j += P) {
            if (j > lo) js.push_back(j);
          }
        else if (a.breaks[k] > lo && a.breaks[k] <= hi)
          js.push_back(a.breaks[k]);
      }
      double l = lo, rr = hi;
      if (js.size() == 1) {
        if (mu >= js[0])
          l = js[0];
        else
          rr = js[0];
      }
      double m, v;
      if (sigma == 0) {
        m = plain(mu);
        v = 0;
      } else {
        // in t = u - mu: the quadrature keeps its digits on a narrow footprint far from 0
        std::vector<double> jt;
        for (double j : js) jt.push_back(j - mu);
        auto ft = [&](double t) { return plain(mu + t); };
        m = integrate(ft, l - mu, rr - mu, jt) / (rr - l);
        v = integrate([&](double t) { return (ft(t) - m) * (ft(t) - m); }, l - mu, rr - mu, jt) / (rr - l);
      }
      const auto got = e.fn(mu, sigma);
      r.upd_d(std::max({rel(got.mean, m, 1), rel(got.var, v, 1)}), mu, sigma);
      const auto gf = ef.fn(float(mu), float(sigma));
      const auto gd = e.fn(float(mu), float(sigma));
      r.upd_f(std::max({rel(gf.mean, gd.mean, 1), rel(gf.var, gd.var, 1)}), mu, sigma);
      ++r.points;
    }
}

std::string fmt(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1e", v);
  return b;
}

}  // namespace

int run(const std::string& manifest_path, bool record, FILE* out) {
  std::vector<Record> recs;
  verify_derivatives(recs);
  verify_truncnorm(recs);
  int n = 0, nf = 0;
  const auto* e = bl::registry::clamped_rule_entries<double>(&n);
  const auto* ef = bl::registry::clamped_rule_entries<float>(&nf);
  for (int i = 0; i < n; ++i) {
    Record r{e[i].cpp};
    const std::string rule = e[i].rule;
    if (rule == "rule3")
      verify_rule3(e[i], ef[i], r);
    else if (rule == "rule1")
      verify_rule1(e[i], ef[i], r);
    else if (rule == "bimodal")
      verify_bimodal(e[i], ef[i], r);
    recs.push_back(r);
  }
  int rc = 0;
  std::map<std::string, const Record*> by_cpp;
  for (const auto& r : recs) {
    std::fprintf(out, "%-40s %5ld points  double %s  float %s  %s\n", r.cpp.c_str(), r.points,
                 fmt(r.worst_d).c_str(), fmt(r.worst_f).c_str(), r.ok() ? "pass" : "FAIL");
    if (!r.ok())
      std::fprintf(stderr, "  %s: worst double at %s, float at %s\n", r.cpp.c_str(), r.where_d.c_str(),
                   r.where_f.c_str());
    if (!r.ok()) rc = 1;
    by_cpp[r.cpp] = &r;
  }
  if (!record) return rc;
  std::ifstream in(manifest_path);
  std::stringstream ss;
  ss << in.rdbuf();
  auto m = nlohmann::ordered_json::parse(ss.str());
  for (auto& en : m["entries"]) {
    auto it = by_cpp.find(en.value("cpp", std::string()));
    if (it == by_cpp.end()) continue;
    const Record& r = *it->second;
    nlohmann::ordered_json v;
    v["points"] = r.points;
    v["worst_rel_error_double"] = std::stod(fmt(r.worst_d));
    v["worst_rel_error_float"] = std::stod(fmt(r.worst_f));
    v["bound_double"] = r.bound_d;
    v["bound_float"] = r.bound_f;
    v["reference"] = r.reference;
    v["status"] = r.ok() ? "pass" : "fail";
    en["verification"] = v;
  }
  std::ofstream o(manifest_path + ".tmp");
  o << m.dump(2) << "\n";
  o.close();
  if (std::rename((manifest_path + ".tmp").c_str(), manifest_path.c_str()) != 0) return 2;
  return rc;
}

}  // namespace blv::clamped
