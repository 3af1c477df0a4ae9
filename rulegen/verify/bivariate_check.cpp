// blverify: bivariate rules against Monte Carlo (see rules_check.hpp). Each case draws 10^6
// jointly normal pairs from a fixed seed (mt19937_64, Box-Muller written out so that the stream
// does not depend on the standard library) and compares mean and variance with the rule; the
// tolerance is 5 standard errors computed from the same samples (variance: from the fourth central
// moment) plus 1e-12 (1 + |mean| + var) for rounding.
#include <chrono>
#include <cmath>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "rules_check.hpp"

#if __has_include(<bandlimit/rules_bivariate.hpp>)
#include <bandlimit/rules_bivariate.hpp>
#define BLV_HAVE_BIVARIATE 1
#else
#define BLV_HAVE_BIVARIATE 0
#endif

#if BLV_HAVE_BIVARIATE
namespace blv {
struct NotInTree {};
}  // namespace blv
namespace bl::bivariate {
// Chosen only when the tree has no mod (rulegen emits it only when the catalog derives fract): the
// tree's float/double overloads are exact non-template matches, which overload resolution prefers.
template <class... A>
blv::NotInTree mod(A...);
}  // namespace bl::bivariate
#endif

namespace blv {

#if BLV_HAVE_BIVARIATE
namespace {

// The tree's mod, or nothing when the tree has none.
template <class... A>
std::optional<bl::stat<double>> tree_mod(A... a) {
  if constexpr (std::is_same_v<decltype(bl::bivariate::mod(a...)), NotInTree>)
    return std::nullopt;
  else
    return bl::bivariate::mod(a...);
}

struct Normal {
  std::mt19937_64 rng;
  bool have = false;
  double spare = 0;
  explicit Normal(std::uint64_t seed) : rng(seed) {}
  double u() { return (static_cast<double>(rng() >> 11) + 0.5) * 0x1.0p-53; }
  double operator()() {
    if (have) {
      have = false;
      return spare;
    }
    const double r = std::sqrt(-2 * std::log(u())), a = 2 * M_PI * u();
    spare = r * std::sin(a);
    have = true;
    return r * std::cos(a);
  }
};

// Welford mean and variance with the fourth central moment for the variance's standard error.
struct Moments {
  long n = 0;
  double mean = 0, m2 = 0, m3 = 0, m4 = 0;
  void add(double x) {
    const long n1 = n++;
    const double d = x - mean, dn = d / n, dn2 = dn * dn, t = d * dn * n1;
    mean += dn;
    m4 += t * dn2 * (double(n) * n - 3.0 * n + 3) + 6 * dn2 * m2 - 4 * dn * m3;
    m3 += t * dn * (n - 2.0) - 3 * dn * m2;
    m2 += t;
  }
  double var() const { return m2 / n; }
  double se_mean() const { return std::sqrt(var() / n); }
  double se_var() const { return std::sqrt(std::max(0.0, m4 / n - var() * var()) / n); }
};

constexpr double kDivSlack = 0.02;

struct Case {
  double ma, sa, mb, sb, rho;
};

// slack: a relative allowance for rules that are approximations of the sampled model (div, rho != 0).
void compare(RuleCheck& rc, const Moments& m, bl::stat<double> r, const std::string& where,
             double slack = 0) {
  const double floor = 1e-12 * (1 + std::abs(m.mean) + m.var());
  const double tm = 5 * m.se_mean() + floor + slack * std::abs(m.mean),
               tv = 5 * m.se_var() + floor + slack * m.var();
  const double em = std::abs(r.mean - m.mean) / tm, ev = std::abs(r.var - m.var()) / tv;
  ++rc.cases;
  const double before = std::max(rc.worst_mean, rc.worst_var);
  if (!(em <= rc.worst_mean)) rc.worst_mean = std::isnan(em) ? INFINITY : em;
  if (!(ev <= rc.worst_var)) rc.worst_var = std::isnan(ev) ? INFINITY : ev;
  if (!(std::max(em, ev) <= before)) {
    std::ostringstream o;
    o.precision(6);
    o << where << ": rule (" << r.mean << ", " << r.var << "), MC (" << m.mean << ", " << m.var()
      << ") +- 5 SE (" << tm << ", " << tv << ")";
    rc.worst_case = o.str();
  }
}

std::string show(const Case& c) {
  std::ostringstream o;
  o << "(ma " << c.ma << ", sa " << c.sa << ", mb " << c.mb << ", sb " << c.sb << ", rho " << c.rho << ")";
  return o.str();
}

// A rule the tree does not have: reported, not checked (rules_check.hpp).
RuleCheck absent(const std::string& op, const std::string& needs) {
  RuleCheck rc;
  rc.cpp = "bl::bivariate::" + op;
  rc.kind = "monte carlo";
  rc.absent = "not in this tree (rulegen emits it only when the catalog derives " + needs + ")";
  return rc;
}

RuleCheck start(const std::string& op) {
  RuleCheck rc;
  rc.cpp = "bl::bivariate::" + op;
  rc.kind = "monte carlo";
  rc.tolerance =
      "|rule - MC| <= 5 SE + 1e-12 (1 + |mean| + var), SE from the " + std::to_string(kMcSamples) +
      " samples of each case (variance: fourth central moment); worst values in units of that tolerance";
  return rc;
}

std::vector<Case> cases() {
  std::vector<Case> cs;
  const Case base[] = {
      {0.3, 1.0, -0.5, 0.7, 0},                // overlapping
      {2.0, 0.5, 3.0, 1.5, 0},                 // different widths
      {1.2, 0.0, -0.4, 0.8, 0},                // sigma 0 on one input
      {1.2, 1e-9, -0.4, 0.8, 0},               // sigma -> 0 on one input
      {1.2, 0.0, -0.4, 0.0, 0},                // both constant
      {100.0, 1.0, -50.0, 2.0, 0},             // means far apart
      {14.142135623730951, 1.0, 0.0, 1.0, 0},  // difference 10 sigma out (rho = 0)
      {-3.0, 2.0, -3.0, 2.0, 0},               // equal inputs
  };
  for (Case c : base)
    for (double rho : {-0.9, 0.0, 0.9}) {
      c.rho = rho;
      cs.push_back(c);
    }
  cs.push_back({0.7, 0.5, 0.4, 0.5, 1.0});   // B - A constant (s = 0)
  cs.push_back({0.7, 0.5, 0.7, 0.5, -1.0});  // A + B constant
  return cs;
}

}  // namespace

bool rules_compiled_in() {
  return true;
}

std::vector<RuleCheck> check_bivariate() {
  using clock = std::chrono::steady_clock;
  std::vector<RuleCheck> out;
  int n = 0;
  const auto* entries = bl::registry::binary_entries<double>(&n);
  // Operators with the (ma, sa, mb, sb, rho) signature whose reference is the joint normal model.
  const std::vector<Case> cs = cases();
  // One sample stream per case serves all seven operators (the same pairs, 10^6 of them).
  const char* ops[] = {"add", "sub", "mul", "min", "max", "less", "greater"};
  const int nops = 7;
  std::vector<RuleCheck> rcs;
  std::vector<const bl::registry::BinaryEntry<double>*> fns;
  for (const char* op : ops) {
    rcs.push_back(start(op));
    fns.push_back(nullptr);
    for (int i = 0; i < n; ++i)
      if (std::string(entries[i].op) == op) fns.back() = &entries[i];
    if (!fns.back()) throw std::runtime_error(std::string("binary_entries has no ") + op);
  }
  const auto t0 = clock::now();
  for (size_t k = 0; k < cs.size(); ++k) {
    const Case& c = cs[k];
    Normal z(1000 + k);
    std::vector<Moments> m(nops);
    const double rc2 = std::sqrt(std::max(0.0, 1 - c.rho * c.rho));
    for (long j = 0; j < kMcSamples; ++j) {
      const double z1 = z(), z2 = z();
      const double a = c.ma + c.sa * z1, b = c.mb + c.sb * (c.rho * z1 + rc2 * z2);
      m[0].add(a + b);
      m[1].add(a - b);
      m[2].add(a * b);
      m[3].add(std::min(a, b));
      m[4].add(std::max(a, b));
      m[5].add(b - a > 0 ? 1 : 0);
      m[6].add(a - b > 0 ? 1 : 0);
    }
    for (int o = 0; o < nops; ++o) compare(rcs[o], m[o], fns[o]->fn(c.ma, c.sa, c.mb, c.sb, c.rho), show(c));
  }
  const double per_op = std::chrono::duration<double>(clock::now() - t0).count() / nops;
  for (auto& r : rcs) {
    r.seconds = per_op;
    out.push_back(r);
  }

  // div: a * (1/b) with 1/b under the compact box model. Exact at rho = 0 (B = mb + box of
  // half-width min(sqrt(3) sb, |mb|/2), A independent); for rho != 0 and |mb| >= 20 sb (where the
  // Gaussian 1/B is effectively finite) against the joint normal, where corr(A, 1/B) = -rho holds
  // to first order.
  const bl::registry::BinaryEntry<double>* div = nullptr;
  for (int i = 0; i < n; ++i)
    if (std::string(entries[i].op) == "div") div = &entries[i];
  if (!div) {
    out.push_back(absent("div", "box inv and inv_sq"));
  } else {
    const auto t0 = clock::now();
    RuleCheck rc = start("div");
    rc.tolerance +=
        "; div: box model of B at rho = 0 (exact), joint normal with |mb| >= 20 sb (first order in the "
        "correlation of A with 1/B: tolerance + 2% of the MC value)";
    struct DivCase {
      Case c;
      bool box;
    };
    const DivCase dcs[] = {{{1.0, 0.5, 2.0, 0.3, 0}, true},      {{-2.0, 1.0, 0.5, 1.0, 0}, true},
                           {{3.0, 0.0, -1.0, 2.0, 0}, true},     {{1.0, 0.5, 2.0, 0.0, 0}, true},
                           {{1.0, 0.5, 20.0, 1.0, -0.9}, false}, {{1.0, 0.5, 20.0, 1.0, 0.0}, false},
                           {{1.0, 0.5, 20.0, 1.0, 0.9}, false},  {{-4.0, 2.0, -30.0, 1.0, 0.9}, false}};
    long k = 0;
    for (const DivCase& d : dcs) {
      const Case& c = d.c;
      Normal z(5000 + k++);
      Moments m;
      const double hh = std::min(std::sqrt(3.0) * c.sb, std::abs(c.mb) / 2);
      const double rc2 = std::sqrt(std::max(0.0, 1 - c.rho * c.rho));
      for (long j = 0; j < kMcSamples; ++j) {
        const double z1 = z(), z2 = z();
        const double a = c.ma + c.sa * z1;
        const double b = d.box ? c.mb + hh * (2 * z.u() - 1) : c.mb + c.sb * (c.rho * z1 + rc2 * z2);
        m.add(a / b);
      }
      compare(rc, m, div->fn(c.ma, c.sa, c.mb, c.sb, c.rho), show(c) + (d.box ? " box model" : " normal"),
              d.box ? 0.0 : kDivSlack);
    }
    rc.seconds = std::chrono::duration<double>(clock::now() - t0).count();
    out.push_back(rc);
  }

  // select(c, a, b) = c a + (1 - c) b, C independent of A and B: C normal and C Bernoulli.
  {
    const auto t0 = clock::now();
    RuleCheck rc = start("select");
    rc.tolerance += "; select: C normal or Bernoulli(p) (mc = p, sc = sqrt(p (1 - p))), independent of A, B";
    struct SelCase {
      double mc, sc, ma, sa, mb, sb;
      bool bernoulli;
    };
    const SelCase scs[] = {{0.3, 0.2, 1.0, 0.5, -2.0, 1.5, false},
                           {0.3, std::sqrt(0.21), 1.0, 0.5, -2.0, 1.5, true},
                           {0.999, std::sqrt(0.999 * 0.001), 5.0, 0.0, -5.0, 0.0, true},
                           {0.0, 0.0, 100.0, 3.0, -1.0, 0.1, false},
                           {1.0, 0.0, 100.0, 3.0, -1.0, 0.1, false},
                           {0.5, 1e-9, 0.0, 1.0, 0.0, 1.0, false}};
    long k = 0;
    for (const SelCase& s : scs) {
      Normal z(7000 + k++);
      Moments m;
      for (long j = 0; j < kMcSamples; ++j) {
        const double c = s.bernoulli ? (z.u() < s.mc ? 1.0 : 0.0) : s.mc + s.sc * z();
        const double a = s.ma + s.sa * z(), b = s.mb + s.sb * z();
        m.add(c * a + (1 - c) * b);
      }
      std::ostringstream w;
      w << "(mc " << s.mc << ", sc " << s.sc << ", ma " << s.ma << ", sa " << s.sa << ", mb " << s.mb
        << ", sb " << s.sb << (s.bernoulli ? ", C Bernoulli)" : ", C normal)");
      compare(rc, m, bl::bivariate::select(s.mc, s.sc, s.ma, s.sa, s.mb, s.sb), w.str());
    }
    rc.seconds = std::chrono::duration<double>(clock::now() - t0).count();
    out.push_back(rc);
  }

  // mod(a, c) = c fract(a / c) = a - c floor(a / c): both branches (sa/|c| <= 0.05 and beyond),
  // next to a jump, 10 sigma from one, far from 0, negative c.
  if (!tree_mod(0.0, 0.0, 1.0)) {
    out.push_back(absent("mod", "gaussian fract and fract_sq"));
  } else {
    const auto t0 = clock::now();
    RuleCheck rc = start("mod");
    struct ModCase {
      double ma, sa, c;
    };
    const ModCase mcs[] = {{0.3, 0.1, 1.0},     {2.001, 0.001, 1.0},     {0.5, 0.0499, 1.0},
                           {0.5, 0.0501, 1.0},  {1.0 + 1e-3, 1e-6, 1.0}, {3.0 + 10 * 0.02, 0.02, 1.0},
                           {1000.2, 0.03, 1.0}, {0.7, 0.3, 0.25},        {-1.3, 0.4, -0.5},
                           {5.0, 2.0, 3.0},     {0.1, 0.0, 1.0}};
    long k = 0;
    for (const ModCase& s : mcs) {
      Normal z(9000 + k++);
      Moments m;
      for (long j = 0; j < kMcSamples; ++j) {
        const double a = s.ma + s.sa * z();
        m.add(a - s.c * std::floor(a / s.c));
      }
      std::ostringstream w;
      w << "(ma " << s.ma << ", sa " << s.sa << ", c " << s.c << ")";
      compare(rc, m, *tree_mod(s.ma, s.sa, s.c), w.str());
    }
    rc.seconds = std::chrono::duration<double>(clock::now() - t0).count();
    out.push_back(rc);
  }
  return out;
}

#else
bool rules_compiled_in() {
  return false;
}
std::vector<RuleCheck> check_bivariate() {
  return {};
}
#endif

}  // namespace blv
