// The engine's bivariate and Rule 2 derivations (GiNaC), and the catalog's monotone validation.
#include <gtest/gtest.h>

#include "bivariate.hpp"
#include "catalog.hpp"
#include "mode_fit.hpp"

namespace {
using namespace GiNaC;

TEST(BivariateDerivation, ProductVarianceIsExactAndNotEq49AsPrinted) {
  const auto& S = bl::sym::biv();
  const ex exact = pow(S.ma * S.sb, 2) + pow(S.sa * S.mb, 2) + 2 * S.rho * S.ma * S.mb * S.sa * S.sb +
                   pow(S.sa * S.sb, 2) * (1 + pow(S.rho, 2));
  for (const auto& r : bl::sym::derive_bivariate())
    if (r.op == "mul") {
      EXPECT_TRUE((r.var - exact).expand().is_zero());
      EXPECT_FALSE((r.var - bl::sym::paper_product_variance_eq49()).expand().is_zero());
      EXPECT_TRUE((r.mean - (S.ma * S.mb + S.rho * S.sa * S.sb)).expand().is_zero());
    }
}

TEST(ModeFitDerivation, ClosedFormsWhereTheEquationIsPolynomial) {
  const bl::sym::Catalog cat = bl::sym::load_catalog(BL_DEFAULT_CATALOG);
  std::vector<bl::sym::NotDerived> nd;
  const auto fits = bl::sym::derive_mode_fits(cat, &nd);
  auto find = [&](const std::string& n) -> const bl::sym::ModeFit* {
    for (const auto& f : fits)
      if (f.atomic->name == n) return &f;
    return nullptr;
  };
  ASSERT_NE(find("exp"), nullptr);
  EXPECT_EQ(find("exp")->pieces[0].degree, 1);  // x* = mu - sigma^2
  EXPECT_EQ(find("log")->pieces[0].degree, 2);
  EXPECT_EQ(find("sqrt")->pieces[0].degree, 2);
  EXPECT_EQ(find("tanh")->pieces[0].degree, -1);  // Newton
  EXPECT_EQ(find("sin"), nullptr);                // f' = 0 at the piece ends: degenerate
  bool sin_listed = false;
  for (const auto& n : nd) sin_listed |= n.atomic == "sin";
  EXPECT_TRUE(sin_listed);
}

TEST(MonotoneCatalog, WrongInverseNamesEntryAndField) {
  const std::string bad =
      R"J({"atomics": [{"name": "e2", "class": "entire", "f": "exp(x)", "domain": ["-inf", "inf"],
      "range": [0, "inf"], "monotone": [{"on": ["-inf", "inf"], "inverse": "log(y)/2"}]}]})J";
  try {
    bl::sym::parse_catalog(bad, "test");
    FAIL() << "accepted a wrong inverse";
  } catch (const bl::sym::CatalogError& e) {
    EXPECT_NE(std::string(e.what()).find("catalog entry 'e2', field 'monotone'"), std::string::npos)
        << e.what();
  }
  const std::string not_monotone =
      R"J({"atomics": [{"name": "c2", "class": "entire", "f": "cos(x)", "domain": ["-inf", "inf"],
      "range": [-1, 1], "monotone": [{"on": [-1, 1], "inverse": "acos(y)"}]}]})J";
  EXPECT_THROW(bl::sym::parse_catalog(not_monotone, "test"), bl::sym::CatalogError);
}

}  // namespace
