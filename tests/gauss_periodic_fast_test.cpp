// The straight-line Gaussian periodic entries (rulegen/emit_gauss_periodic.cpp: a break regime
// below sigma_b, unrolled Fourier terms above) at hard inputs, float and double, against an
// independent reference: the sum over periods of the truncated-normal moments of each polynomial
// piece (degree <= 2) in long double, E[Z^j 1{a <= Z < b}] for Z ~ N(mu, sigma^2) from Phi and phi.
// Hard inputs: x at and next to breaks, |x| = 1e6, sigma from 1e-30 to 10 and next to each
// entry's regime boundary sigma_b (the emitted comments state them).
#include <gtest/gtest.h>

#include <bandlimit/table.hpp>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

using LD = long double;

struct Pc {
  LD lo, hi, c0, c1, c2;  // c0 + c1 t + c2 t^2 on [lo, hi), t = y - m T
};
// The pieces of period m.
using Pieces = std::function<std::vector<Pc>(long m)>;

LD Phic(LD z) {
  return 0.5L * std::erfc(z / std::sqrt(2.0L));
}
LD phi(LD z) {
  return std::isinf(z) ? 0.0L : std::exp(-0.5L * z * z) / std::sqrt(2.0L * 3.14159265358979323846264338L);
}

// E f(x + sigma Z) by the sum over the periods within 40 sigma (+1) of x.
LD reference(const Pieces& f, LD T, LD x, LD sigma) {
  const long m0 = static_cast<long>(std::floor((x - 40 * sigma) / T)) - 1;
  const long m1 = static_cast<long>(std::floor((x + 40 * sigma) / T)) + 1;
  LD s = 0;
  for (long m = m0; m <= m1; ++m)
    for (const Pc& p : f(m)) {
      const LD mu = x - m * T;  // exact for the x used here
      // The ends as (end + m T) - x: exact near x (x - m T would round a tiny x away).
      const LD a = ((p.lo + m * T) - x) / sigma, b = ((p.hi + m * T) - x) / sigma;
      const LD M0 = a > 0 ? Phic(a) - Phic(b) : Phic(-b) - Phic(-a);
      const LD dphi = phi(a) - phi(b);
      const LD M1 = mu * M0 + sigma * dphi;
      const LD M2 = mu * mu * M0 + 2 * mu * sigma * dphi + sigma * sigma * (M0 + a * phi(a) - b * phi(b));
      s += p.c0 * M0 + p.c1 * M1 + p.c2 * M2;
    }
  return s;
}

struct Entry {
  std::string name;
  LD T;
  Pieces f;
  float (*ef)(float, float);
  double (*ed)(double, double);
  bool huge_x;  // values stay O(1) (periodic): |x| = 1e6 is tested
};

std::vector<Entry> entries() {
  namespace g = bl::gaussian;
  auto one = [](LD c0, LD c1, LD c2) { return std::vector<Pc>{{0, 1, c0, c1, c2}}; };
  auto tr = [](long m) { return LD(m >= 0 ? m : m + 1); };  // trunc on [m, m+1) (a.e.)
  return {
      {"fract", 1, [=](long) { return one(0, 1, 0); }, g::fract, g::fract, true},
      {"fract_sq", 1, [=](long) { return one(0, 0, 1); }, g::fract_sq, g::fract_sq, true},
      {"square", 1,
       [](long) {
         return std::vector<Pc>{{0, 0.5L, 1, 0, 0}, {0.5L, 1, 0, 0, 0}};
       },
       g::square, g::square, true},
      {"square_sq", 1,
       [](long) {
         return std::vector<Pc>{{0, 0.5L, 1, 0, 0}, {0.5L, 1, 0, 0, 0}};
       },
       g::square_sq, g::square_sq, true},
      {"triangle", 2,
       [](long) {
         return std::vector<Pc>{{0, 1, 0, 1, 0}, {1, 2, 2, -1, 0}};
       },
       g::triangle, g::triangle, true},
      {"triangle_sq", 2,
       [](long) {
         return std::vector<Pc>{{0, 1, 0, 0, 1}, {1, 2, 4, -4, 1}};
       },
       g::triangle_sq, g::triangle_sq, true},
      {"floor", 1, [=](long m) { return one(m, 0, 0); }, g::floor, g::floor, true},
      {"floor_sq", 1, [=](long m) { return one(LD(m) * m, 0, 0); }, g::floor_sq, g::floor_sq, false},
      {"ceil", 1, [=](long m) { return one(m + 1, 0, 0); }, g::ceil, g::ceil, true},
      {"ceil_sq", 1, [=](long m) { return one(LD(m + 1) * (m + 1), 0, 0); }, g::ceil_sq, g::ceil_sq, false},
      {"trunc", 1, [=](long m) { return one(tr(m), 0, 0); }, g::trunc, g::trunc, true},
      {"trunc_sq", 1, [=](long m) { return one(tr(m) * tr(m), 0, 0); }, g::trunc_sq, g::trunc_sq, false},
  };
}

template <class R>
std::vector<R> xs(bool huge) {
  std::vector<R> v = {R(0),  R(1e-30), R(-1e-30), R(0.25), R(0.5), R(1),
                      R(-1), R(-0.5),  R(1.75),   R(-3.3), R(2)};
  for (R b : {R(0), R(0.5), R(1), R(-1), R(2)}) {
    v.push_back(std::nextafter(b, R(10)));
    v.push_back(std::nextafter(b, R(-10)));
  }
  if (huge)
    for (R b : {R(1e6), R(-1e6), R(1e6 + 0.5), R(-1e6 + 0.25)}) {
      v.push_back(b);
      v.push_back(std::nextafter(b, R(2e6)));
      v.push_back(std::nextafter(b, R(-2e6)));
    }
  return v;
}

// Every sigma bound the generated Gaussian entries of these atomics test ("sigma < T(b)", "sigma >=
// T(b)", ...): the regime and tier edges of whatever plan rulegen emitted, read from the header itself.
std::vector<double> emitted_sigma_bounds() {
  std::ifstream in(BL_TABLE_HPP);
  EXPECT_TRUE(in.good()) << "cannot read " << BL_TABLE_HPP;
  std::stringstream text;
  text << in.rdbuf();
  const std::string all = text.str();
  std::set<double> out;
  // The entries' bodies: _raw (or the entry itself), its out-of-line _general, and the stat pairs.
  const std::regex fn(
      "\\n(BL_NOINLINE )?T "
      "gaussian_(fract|fract_sq|square|square_sq|triangle|triangle_sq|floor|floor_sq|ceil|"
      "ceil_sq|trunc|trunc_sq)_(raw|general)\\(|\\n(BL_NOINLINE )?stat<T> "
      "gaussian_(fract|floor|ceil)_stat(_general)?\\(");
  // "sigma < T(b)", or the pixel-sized path's per-type bound "sigma < (sizeof(T) < sizeof(double) ?
  // T(b_float) : T(b_double))".
  const std::regex bound(
      "sigma (<|<=|>=) (T\\(([0-9.e+-]+)\\)|\\(sizeof\\(T\\) < sizeof\\(double\\) \\? T\\(([0-9.e+-]+)\\) : "
      "T\\(([0-9.e+-]+)\\)\\))");
  for (auto it = std::sregex_iterator(all.begin(), all.end(), fn); it != std::sregex_iterator(); ++it) {
    const size_t from = static_cast<size_t>(it->position());
    const size_t to = all.find("\n}\n", from);
    const std::string body = all.substr(from, to - from);
    for (auto b = std::sregex_iterator(body.begin(), body.end(), bound); b != std::sregex_iterator(); ++b)
      for (int g : {3, 4, 5}) {
        if (!(*b)[g].matched) continue;
        const double v = std::stod((*b)[g].str());
        if (v > 1e-20 && v < 100) out.insert(v);
      }
  }
  EXPECT_GE(out.size(), 60u) << "the emitted regime bounds were not found in " << BL_TABLE_HPP;
  return {out.begin(), out.end()};
}

template <class R>
std::vector<R> sigmas() {
  // 1e-30 and 1e-12 (narrow kernels), every regime and tier bound of the emitted plans and their
  // neighbours, wide kernels.
  std::vector<R> v = {R(1e-30), R(1e-12), R(1e-6), R(1e-3), R(0.01), R(0.05),
                      R(0.3),   R(0.5),   R(1),    R(3),    R(10)};
  static const std::vector<double> bounds = emitted_sigma_bounds();
  for (double b : bounds) {
    v.push_back(R(b));
    v.push_back(std::nextafter(R(b), R(1)));
    v.push_back(std::nextafter(R(b), R(0)));
  }
  return v;
}

template <class R>
void check(const Entry& e, R (*fn)(R, R), double tol) {
  int bad = 0;
  for (R x : xs<R>(e.huge_x))
    for (R s : sigmas<R>()) {
      const R v = fn(x, s);
      const LD ref = reference(e.f, e.T, LD(x), LD(s));
      const double err = std::fabs(double(LD(v) - ref)) / std::max(1.0, std::fabs(double(ref)));
      if (!(err <= tol) && bad++ < 5)
        ADD_FAILURE() << e.name << (sizeof(R) == 4 ? " float" : " double") << " x=" << double(x)
                      << " sigma=" << double(s) << ": " << double(v) << " vs " << double(ref) << " (err "
                      << err << ")";
    }
  EXPECT_EQ(bad, 0) << e.name;
}

TEST(GaussPeriodicFast, DoubleWithin1e9OfTheReference) {
  for (const Entry& e : entries()) check<double>(e, e.ed, 1e-9);
}

TEST(GaussPeriodicFast, FloatWithin2e5OfTheReference) {
  for (const Entry& e : entries()) check<float>(e, e.ef, 2e-5);
}

// gaussian trunc^2 near 0 (narrow kernels: the straight-line break sums; sigma in [0.25, 3]: floor^2~(|x|)
// minus the loop over the breaks n <= 0 of trunc^2 - floor^2; the combination beyond): reference sum_n
// trunc(n + 1/2)^2 P(n <= x + U < n + 1) in long double over the steps within 40 sigma (the rest <
// 1e-300), sigma <= 10. Hard inputs: x = 0, +-1e-12, next to the integers, the near-0 window edge 7
// sigma, |x| = 1e6 (1e30 would not step the long double loop), far |x|; sigma -> 0, the mirrored
// form's ends and the tier edges.
LD trunc_sq_reference(LD x, LD s) {
  if (s == 0) {
    const LD t = std::trunc(x);
    return t * t;
  }
  LD acc = 0;
  for (LD n = std::floor(x - 40 * s) - 1; n <= std::floor(x + 40 * s) + 1; ++n) {
    const LD v = std::trunc(n + 0.5L);
    const LD pa = Phic((n - x) / s), pb = Phic((n + 1 - x) / s);
    acc += v * v * (pa - pb);
  }
  return acc;
}

template <class R>
void check_trunc_sq(double tol) {
  std::vector<R> xs = {R(0), R(1e-12), R(-1e-12), R(0.5), R(-0.5), R(2.3), R(-2.7), R(1e6), R(-1e6)};
  for (R b : {R(1), R(-1), R(2), R(-2), R(3), R(-3)}) {
    xs.push_back(b);
    xs.push_back(std::nextafter(b, R(10)));
    xs.push_back(std::nextafter(b, R(-10)));
  }
  int bad = 0;
  for (R s :
       {R(1e-30), R(1e-12), R(1e-3),  R(0.05),   R(0.166), R(0.3),   R(0.47),  R(0.48),  R(0.6),  R(0.666),
        R(0.667), R(0.7),   R(0.706), R(0.71),   R(0.9),   R(0.999), R(1),     R(1.001), R(1.05), R(1.058),
        R(1.06),  R(3),     R(10),    R(0.2499), R(0.25),  R(2),     R(2.999), R(3.001)})
    for (R x0 : xs)
      for (R x : {x0, R(x0 + R(7) * s), R(x0 - R(7) * s)}) {
        const R v = bl::detail::gen::gaussian_trunc_sq<R>(x, s);
        const LD ref = trunc_sq_reference(LD(x), LD(s));
        const double err = std::fabs(double(LD(v) - ref)) / std::max(1.0, std::fabs(double(ref)));
        if (!(err <= tol) && bad++ < 5)
          ADD_FAILURE() << "trunc_sq" << (sizeof(R) == 4 ? " float" : " double") << " x=" << double(x)
                        << " sigma=" << double(s) << ": " << double(v) << " vs " << double(ref);
      }
  EXPECT_EQ(bad, 0);
}

TEST(GaussPeriodicFast, TruncSqNearZeroDouble) {
  check_trunc_sq<double>(1e-9);
}
TEST(GaussPeriodicFast, TruncSqNearZeroFloat) {
  check_trunc_sq<float>(2e-5);
}

// The mirrored form loops over breaks until one lies beyond its cut: a NaN x must leave the loop.
TEST(GaussPeriodicFast, TruncSqNaNLeavesTheBreakLoop) {
  for (double s : {0.25, 1.0, 3.0}) {
    EXPECT_TRUE(std::isnan(bl::detail::gen::gaussian_trunc_sq<double>(NAN, s))) << s;
    EXPECT_TRUE(std::isnan(bl::detail::gen::gaussian_trunc_sq<float>(NAN, float(s)))) << s;
  }
}

// The one-pass stat entries (rulegen/emit_stat_pairs.hpp): {E f, Var f} against the same
// truncated-normal sums for f and f^2, Var = E f^2 - (E f)^2 formed in long double. Bound: the mean
// as the entries' (tol max(1, |E f|)), the variance within tol max(1, E f^2) (it is a difference of
// two such values; the compiler shifts floor's argument into [0, 1) so E f^2 stays O(1) there).
struct StatCase {
  std::string name;
  Pieces f, f2;
  bl::stat<float> (*ef)(float, float);
  bl::stat<double> (*ed)(double, double);
  bool huge_x;
};

std::vector<StatCase> stat_cases() {
  namespace g = bl::gaussian;
  auto one = [](LD c0, LD c1, LD c2) { return std::vector<Pc>{{0, 1, c0, c1, c2}}; };
  return {
      {"fract_stat", [=](long) { return one(0, 1, 0); }, [=](long) { return one(0, 0, 1); }, g::fract_stat,
       g::fract_stat, true},
      {"floor_stat", [=](long m) { return one(m, 0, 0); }, [=](long m) { return one(LD(m) * m, 0, 0); },
       g::floor_stat, g::floor_stat, false},
      {"ceil_stat", [=](long m) { return one(m + 1, 0, 0); },
       [=](long m) { return one(LD(m + 1) * (m + 1), 0, 0); }, g::ceil_stat, g::ceil_stat, false},
  };
}

template <class R>
void check_stat(const StatCase& e, bl::stat<R> (*fn)(R, R), double tol) {
  int bad = 0;
  std::vector<R> x_all = xs<R>(e.huge_x);
  for (R x : {R(7.3), R(-12.5), R(40.7)}) x_all.push_back(x);  // floor away from 0 (E f^2 ~ 1e3)
  for (R x : x_all)
    for (R s : sigmas<R>()) {
      const bl::stat<R> v = fn(x, s);
      const LD m = reference(e.f, 1, LD(x), LD(s)), m2 = reference(e.f2, 1, LD(x), LD(s));
      const LD var = m2 - m * m;
      const double em = std::fabs(double(LD(v.mean) - m)) / std::max(1.0, std::fabs(double(m)));
      const double ev = std::fabs(double(LD(v.var) - var)) / std::max(1.0, double(m2));
      if (!(em <= tol && ev <= tol && v.var >= 0) && bad++ < 5)
        ADD_FAILURE() << e.name << (sizeof(R) == 4 ? " float" : " double") << " x=" << double(x)
                      << " sigma=" << double(s) << ": {" << double(v.mean) << ", " << double(v.var)
                      << "} vs {" << double(m) << ", " << double(var) << "}";
    }
  EXPECT_EQ(bad, 0) << e.name;
}

TEST(GaussPeriodicFast, StatEntriesDoubleWithin1e9) {
  for (const StatCase& e : stat_cases()) check_stat<double>(e, e.ed, 1e-9);
}
TEST(GaussPeriodicFast, StatEntriesFloatWithin2e5) {
  for (const StatCase& e : stat_cases()) check_stat<float>(e, e.ef, 2e-5);
}

// NaN and negative sigma give NaN moments; NaN x NaN moments; sigma = 0 the plain value, variance 0.
TEST(GaussPeriodicFast, StatEntriesBadInput) {
  for (const StatCase& e : stat_cases()) {
    for (double s : {-1.0, double(NAN)}) {
      const auto d = e.ed(0.3, s);
      EXPECT_TRUE(std::isnan(d.mean) && std::isnan(d.var)) << e.name << " sigma " << s;
      const auto f = e.ef(0.3f, float(s));
      EXPECT_TRUE(std::isnan(f.mean) && std::isnan(f.var)) << e.name << " sigma " << s;
    }
    for (double s : {0.0, 0.01, 0.3, 3.0}) {
      EXPECT_TRUE(std::isnan(e.ed(NAN, s).mean)) << e.name << " sigma " << s;
      EXPECT_TRUE(std::isnan(e.ef(NAN, float(s)).mean)) << e.name << " sigma " << s;
    }
    const auto z = e.ed(2.25, 0.0);
    EXPECT_EQ(z.var, 0.0) << e.name;
  }
  EXPECT_EQ(bl::gaussian::floor_stat(2.25, 0.0).mean, 2.0);
  EXPECT_EQ(bl::gaussian::ceil_stat(2.25f, 0.0f).mean, 3.0f);
}

}  // namespace
