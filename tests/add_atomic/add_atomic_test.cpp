// A test-only catalog entry ("bump", a periodic parabolic pulse) is emitted at build time by
// rulegen; here its smoothed functions are compared with Boost quadrature of the test's own
// definition of the pulse, in float and double, including hard inputs.
#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>

#include "bandlimit/table.hpp"

namespace {

double bump(double t) {
  const double r = t - 2 * std::floor(t / 2);
  return r < 1 ? 4 * r * (1 - r) : 0.0;
}

enum class K { Gauss, Box, Tent };

// E[g(x + U)], integrating over u with splits at every break of g (integers) and the kernel's kink.
double reference(K k, double x, double s, bool sq) {
  auto g = [&](double t) { const double v = bump(t); return sq ? v * v : v; };
  double lo, hi;
  auto density = [&](double u) {
    if (k == K::Gauss) return std::exp(-u * u / (2 * s * s)) / (s * std::sqrt(2 * M_PI));
    if (k == K::Box) return 1 / (2 * std::sqrt(3.0) * s);
    const double w = std::sqrt(6.0) * s;
    return (w - std::abs(u)) / (w * w);
  };
  if (k == K::Gauss) { lo = -12 * s; hi = 12 * s; }
  else if (k == K::Box) { lo = -std::sqrt(3.0) * s; hi = -lo; }
  else { lo = -std::sqrt(6.0) * s; hi = -lo; }
  std::vector<double> cuts{lo, hi, 0.0};
  for (double b = std::ceil(x + lo); b < x + hi; b += 1) cuts.push_back(b - x);
  std::sort(cuts.begin(), cuts.end());
  double sum = 0;
  for (size_t i = 0; i + 1 < cuts.size(); ++i) {
    if (cuts[i + 1] - cuts[i] < 1e-300) continue;
    sum += boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
        [&](double u) { return g(x + u) * density(u); }, cuts[i], cuts[i + 1], 10, 1e-14);
  }
  return sum;
}

double call(K k, bool sq, double x, double s) {
  if (k == K::Gauss) return sq ? bl::gaussian::bump_sq(x, s) : bl::gaussian::bump(x, s);
  if (k == K::Box) return sq ? bl::box::bump_sq(x, s) : bl::box::bump(x, s);
  return sq ? bl::tent::bump_sq(x, s) : bl::tent::bump(x, s);
}
float callf(K k, bool sq, float x, float s) {
  if (k == K::Gauss) return sq ? bl::gaussian::bump_sq(x, s) : bl::gaussian::bump(x, s);
  if (k == K::Box) return sq ? bl::box::bump_sq(x, s) : bl::box::bump(x, s);
  return sq ? bl::tent::bump_sq(x, s) : bl::tent::bump(x, s);
}

TEST(AddAtomic, BumpMatchesQuadratureInDoubleAndFloat) {
  for (K k : {K::Gauss, K::Box, K::Tent})
    for (bool sq : {false, true})
      for (double x : {-3.7, -1.0, 0.0, 1e-9, 0.5, 1.0, 1.0 + 1e-9, 1.9, 1e3 + 0.3})
        for (double s : {1e-6, 0.01, 0.1, 0.4, 1.0, 3.0, 10.0}) {
          const double ref = reference(k, x, s, sq);
          const double tol = std::max(1.0, std::abs(ref));
          EXPECT_LE(std::abs(call(k, sq, x, s) - ref) / tol, 1e-9) << int(k) << sq << " x=" << x << " s=" << s;
          const float xf = static_cast<float>(x), sf = static_cast<float>(s);
          const double reff = reference(k, xf, sf, sq);
          EXPECT_LE(std::abs(callf(k, sq, xf, sf) - reff) / std::max(1.0, std::abs(reff)), 2e-5)
              << "float " << int(k) << sq << " x=" << x << " s=" << s;
        }
}

TEST(AddAtomic, SigmaZeroIsTheFunctionAndNegativeSigmaIsNaN) {
  for (double x : {-0.5, 0.25, 1.5}) {
    EXPECT_EQ(bl::gaussian::bump(x, 0.0), bump(x));
    EXPECT_EQ(bl::box::bump_sq(x, 0.0), bump(x) * bump(x));
    EXPECT_TRUE(std::isnan(bl::tent::bump(x, -1.0)));
  }
  EXPECT_EQ(bl::plain::bump(0.5), 1.0);
}

}  // namespace
