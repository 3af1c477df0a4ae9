// Derived closed forms against independent results from the literature, evaluated with CLN.
#include <gtest/gtest.h>

#include <cmath>

#include "catalog.hpp"
#include "derived.hpp"
#include "kernels.hpp"

namespace {
using namespace GiNaC;
using bl::sym::Kernel;

double eval(const ex& e, double x, double sigma) {
  const ex v = e.subs(lst{bl::sym::var_x() == numeric(x), bl::sym::var_sigma() == numeric(sigma)}).evalf();
  return ex_to<numeric>(v).to_double();
}

const bl::sym::Derived& find(const std::vector<bl::sym::Derived>& ds, const std::string& atomic, Kernel k,
                             bool sq, int order = -1) {
  for (const auto& d : ds)
    if (d.atomic_name == atomic && d.kernel == k && d.squared == sq && (order < 0 || d.order == order)) return d;
  throw std::runtime_error("no entry " + atomic);
}

class Derivation : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    cat_ = new bl::sym::Catalog(bl::sym::load_catalog(BL_DEFAULT_CATALOG));
    ds_ = new std::vector<bl::sym::Derived>(bl::sym::derive_all(*cat_));
  }
  static bl::sym::Catalog* cat_;
  static std::vector<bl::sym::Derived>* ds_;
};
bl::sym::Catalog* Derivation::cat_ = nullptr;
std::vector<bl::sym::Derived>* Derivation::ds_ = nullptr;

// Characteristic functions: E cos(w(x+U)) = cos(wx) phi(w); Gaussian e^{-w^2 s^2/2}, box sinc(w h).
TEST_F(Derivation, TrigMatchesCharacteristicFunctions) {
  for (double x : {-2.0, 0.3, 7.5})
    for (double s : {0.1, 0.7, 2.0}) {
      EXPECT_NEAR(eval(find(*ds_, "sin", Kernel::Gaussian, false).closed, x, s), std::sin(x) * std::exp(-s * s / 2), 1e-14);
      const double h = std::sqrt(3.0) * s;
      EXPECT_NEAR(eval(find(*ds_, "cos", Kernel::Box, false).closed, x, s), std::cos(x) * std::sin(h) / h, 1e-14);
      EXPECT_NEAR(eval(find(*ds_, "sin", Kernel::Gaussian, true).closed, x, s),
                  0.5 - 0.5 * std::cos(2 * x) * std::exp(-2 * s * s), 1e-14);
      EXPECT_NEAR(eval(find(*ds_, "exp", Kernel::Gaussian, false).closed, x, s), std::exp(x + s * s / 2),
                  1e-13 * std::exp(x + s * s / 2));
    }
}

// Raw moments: Gaussian E[(x+sZ)^n] = He_n^{[-s^2]}(x) (smoothing paper eq. A.2),
// box E[U^2j] = h^2j/(2j+1), tent E[U^2j] = 2 w^2j/((2j+1)(2j+2)).
TEST_F(Derivation, MomentsMatchHermiteAndUniformMoments) {
  auto fact = [](int n) { return std::tgamma(n + 1.0); };
  for (int n = 0; n <= 16; ++n)
    for (double x : {-1.3, 0.4, 2.0})
      for (double s : {0.2, 1.1}) {
        double g = 0, b = 0, t = 0;
        const double h = std::sqrt(3.0) * s, w = std::sqrt(6.0) * s;
        for (int k = 0; 2 * k <= n; ++k) {
          g += fact(n) / (fact(n - 2 * k) * fact(k)) * std::pow(2.0, -k) * std::pow(x, n - 2 * k) * std::pow(s * s, k);
          const double c = fact(n) / (fact(2 * k) * fact(n - 2 * k)) * std::pow(x, n - 2 * k);
          b += c * std::pow(h, 2 * k) / (2 * k + 1);
          t += c * 2 * std::pow(w, 2 * k) / ((2 * k + 1) * (2 * k + 2));
        }
        const double tol = 1e-13 * std::max(1.0, std::abs(g));
        EXPECT_NEAR(eval(find(*ds_, "moment", Kernel::Gaussian, false, n).closed, x, s), g, tol) << n;
        EXPECT_NEAR(eval(find(*ds_, "moment", Kernel::Box, false, n).closed, x, s), b, tol) << n;
        EXPECT_NEAR(eval(find(*ds_, "moment", Kernel::Tent, false, n).closed, x, s), t, tol) << n;
      }
}

// fract's Fourier series (Dorn et al., section 3.3): 1/2 - sum sin(2 pi n x)/(pi n).
TEST_F(Derivation, FractFourierCoefficientsMatchDorn) {
  const auto& d = find(*ds_, "fract", Kernel::Gaussian, false);
  EXPECT_TRUE((d.a0 - numeric(1, 2)).is_zero());
  for (int k = 1; k <= 6; ++k) {
    const ex sub = lst{bl::sym::var_k() == k, bl::sym::var_pk() == (k % 2 ? -1 : 1)};
    EXPECT_NEAR(ex_to<numeric>(d.ak.subs(sub).evalf()).to_double(), 0.0, 1e-15);
    EXPECT_NEAR(ex_to<numeric>(d.bk.subs(sub).evalf()).to_double(), -1.0 / (M_PI * k), 1e-15);
  }
  // Triangle wave (period 2, 0 at 0, 1 at 1): a_k = -4/(pi k)^2 for odd k, 0 for even.
  const auto& t = find(*ds_, "triangle", Kernel::Gaussian, false);
  for (int k = 1; k <= 6; ++k) {
    const ex sub = lst{bl::sym::var_k() == k, bl::sym::var_pk() == (k % 2 ? -1 : 1)};
    EXPECT_NEAR(ex_to<numeric>(t.ak.subs(sub).evalf()).to_double(), k % 2 ? -4.0 / (M_PI * M_PI * k * k) : 0.0, 1e-15);
  }
}

// E|x + sZ| = s sqrt(2/pi) e^{-x^2/2s^2} + x erf(x / (s sqrt 2)) (folded normal mean).
TEST_F(Derivation, AbsGaussianClosedFormIsTheFoldedNormalMean) {
  const auto& d = find(*ds_, "abs", Kernel::Gaussian, false);
  for (double x : {-3.0, -0.2, 0.0, 0.5, 4.0})
    for (double s : {0.05, 0.6, 3.0}) {
      const double ref = s * std::sqrt(2 / M_PI) * std::exp(-x * x / (2 * s * s)) + x * std::erf(x / (s * std::sqrt(2.0)));
      EXPECT_NEAR(eval(d.closed, x, s), ref, 1e-14) << x << " " << s;
    }
}

// Dorn et al. Table 1, saturate under a Gaussian of standard deviation w.
TEST_F(Derivation, SaturateGaussianClosedFormMatchesDornTable1) {
  const auto& d = find(*ds_, "saturate", Kernel::Gaussian, false);
  for (double x : {-1.0, 0.0, 0.3, 1.0, 2.5})
    for (double w : {0.1, 0.5, 2.0}) {
      const double r2 = std::sqrt(2.0), c = w * std::sqrt(2 / M_PI);
      const double ref = 0.5 * (x * std::erf(x / (w * r2)) - (x - 1) * std::erf((x - 1) / (w * r2)) +
                                c * (std::exp(-x * x / (2 * w * w)) - std::exp(-(x - 1) * (x - 1) / (2 * w * w))) + 1);
      EXPECT_NEAR(eval(d.closed, x, w), ref, 1e-14) << x << " " << w;
    }
}

// Antiderivative rules: the Taylor coefficients are f^(2j)(x) E[U^2j]/(2j)!.
TEST_F(Derivation, BoxSeriesOfLogIsItsTaylorSeries) {
  const auto& d = find(*ds_, "log", Kernel::Box, false);
  ASSERT_EQ(d.series.size(), 7u);
  // f'' = -1/x^2, E[U^2]/2 = h^2/6  ->  coefficient -1/(6 x^2)
  const double x = 1.7;
  EXPECT_NEAR(ex_to<numeric>(d.series[1].subs(bl::sym::var_x() == numeric(17, 10)).evalf()).to_double(),
              -1.0 / (6 * x * x), 1e-15);
}

}  // namespace
