// The catalog loader rejects bad entries with a message that names the entry and the field.
#include <gtest/gtest.h>

#include <string>

#include "catalog.hpp"
#include "derived.hpp"

namespace {
using bl::sym::CatalogError;

std::string wrap(const std::string& entry) { return R"J({"atomics": [)J" + entry + "]}"; }

// Returns the error message of loading (and deriving) a one-entry catalog, or "" when accepted.
std::string error_of(const std::string& json) {
  try {
    auto cat = bl::sym::parse_catalog(json, "test");
    bl::sym::derive_all(cat, 0);
  } catch (const CatalogError& e) {
    return e.what();
  }
  return "";
}

void expect_error(const std::string& json, const std::string& entry, const std::string& field,
                  const std::string& detail = "") {
  const std::string msg = error_of(json);
  ASSERT_FALSE(msg.empty()) << "accepted: " << json;
  EXPECT_NE(msg.find("'" + entry + "'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("field '" + field + "'"), std::string::npos) << msg;
  if (!detail.empty()) EXPECT_NE(msg.find(detail), std::string::npos) << msg;
}

TEST(Catalog, ProjectCatalogLoadsAndDerives) {
  auto cat = bl::sym::load_catalog(BL_DEFAULT_CATALOG);
  EXPECT_GE(cat.atomics.size(), 29u);
  for (const char* name : {"sin", "cos", "tan", "exp", "log", "sqrt", "sinh", "cosh", "tanh", "abs", "sign",
                           "step", "floor", "ceil", "fract", "trunc", "saturate", "smoothstep", "pow2",
                           "pow3", "pow4", "pow5", "pow6", "pow7", "pow8", "inv", "inv2", "triangle", "square"})
    EXPECT_NE(cat.find(name), nullptr) << name;
  EXPECT_GT(bl::sym::derive_all(cat).size(), 150u);
}

TEST(Catalog, WrongAntiderivativeIsRejected) {
  expect_error(wrap(R"J({"name": "badtan", "class": "antiderivative", "f": "tan(x)", "F": "log(abs(cos(x)))",
    "F_sq": "tan(x) - x", "domain": ["-inf", "inf"], "period": "Pi", "singular": ["Pi/2"], "range": ["-inf", "inf"]})J"),
               "badtan", "F", "differs from the integrand");
  expect_error(wrap(R"J({"name": "badlog", "class": "antiderivative", "f": "log(x)", "F": "x*log(x) - x",
    "F_sq": "x*log(x)^2", "domain": [0, "inf"], "singular": [0], "range": ["-inf", "inf"]})J"),
               "badlog", "F_sq");
}

TEST(Catalog, MissingDomainIsRejected) {
  expect_error(wrap(R"J({"name": "nodomain", "class": "entire", "f": "sin(x)", "range": [-1, 1]})J"), "nodomain",
               "domain", "missing");
}

TEST(Catalog, PeriodThatDoesNotMatchPiecesIsRejected) {
  expect_error(wrap(R"J({"name": "saw", "class": "periodic", "period": 2, "domain": ["-inf", "inf"], "range": [0, 1],
    "jumps": [0], "pieces": [{"on": [0, 1], "f": "x"}]})J"),
               "saw", "period", "period is 2");
}

TEST(Catalog, UnknownNamesAreRejected) {
  expect_error(wrap(R"J({"name": "flr", "class": "combination", "of": "x - frac(x)", "domain": ["-inf", "inf"],
    "range": ["-inf", "inf"]})J"),
               "flr", "of", "unknown atomic 'frac'");
  expect_error(wrap(R"J({"name": "odd", "class": "entire", "f": "sin(x) + erfx(x)", "domain": ["-inf", "inf"],
    "range": [-1, 1]})J"),
               "odd", "f");
  expect_error(wrap(R"J({"name": "odd", "class": "wavy", "domain": ["-inf", "inf"], "range": [-1, 1]})J"), "odd",
               "class", "unknown class");
  expect_error(wrap(R"J({"name": "odd", "class": "entire", "f": "x", "domian": [0, 1], "domain": ["-inf", "inf"],
    "range": [-1, 1]})J"),
               "odd", "domian", "unknown field");
}

TEST(Catalog, DeclaredBreaksMustMatchThePieces) {
  expect_error(wrap(R"J({"name": "ramp", "class": "piecewise", "domain": ["-inf", "inf"], "range": [0, "inf"],
    "pieces": [{"on": ["-inf", 0], "f": "0"}, {"on": [0, "inf"], "f": "x"}]})J"),
               "ramp", "kinks", "kinks at [0]");
  expect_error(wrap(R"J({"name": "hop", "class": "piecewise", "domain": ["-inf", "inf"], "range": [0, 1],
    "kinks": [0], "pieces": [{"on": ["-inf", 0], "f": "0"}, {"on": [0, "inf"], "f": "1"}]})J"),
               "hop", "jumps");
}

TEST(Catalog, OutsideTheDerivableClassIsRejected) {
  expect_error(wrap(R"J({"name": "gauss", "class": "entire", "f": "exp(x^2)", "domain": ["-inf", "inf"],
    "range": [1, "inf"]})J"),
               "gauss", "f", "rational multiple of x");
  expect_error(
      wrap(
          R"J({"name": "irr", "class": "periodic", "period": "2*Pi", "domain": ["-inf", "inf"], "range": [0, 1],
    "jumps": [0, 1], "pieces": [{"on": [0, 1], "f": "1"}, {"on": [1, "2*Pi"], "f": "0"}]})J"),
      "irr", "pieces", "rational numbers");
  expect_error(wrap(R"J({"name": "flt", "class": "entire", "f": "x", "domain": ["-inf", "inf"], "range": [-0.5, 1]})J"),
               "flt", "range", "exact expressions");
}

TEST(Catalog, RangeMustContainEveryValue) {
  // Polynomial pieces: the extremes are exact (critical point 3/4 of x(3 - 2x) on [0, 1] gives 9/8).
  expect_error(wrap(R"J({"name": "hump", "class": "piecewise", "domain": ["-inf", "inf"], "range": [0, 1],
    "kinks": [0], "jumps": [1], "pieces": [{"on": ["-inf", 0], "f": "0"}, {"on": [0, 1], "f": "x*(3 - 2*x)"}, {"on": [1, "inf"], "f": "0"}]})J"),
               "hump", "range", "critical point x = 0.75");
  EXPECT_EQ(error_of(wrap(R"J({"name": "hump", "class": "piecewise", "domain": ["-inf", "inf"], "range": [0, "9/8"],
    "kinks": [0], "jumps": [1], "pieces": [{"on": ["-inf", 0], "f": "0"}, {"on": [0, 1], "f": "x*(3 - 2*x)"}, {"on": [1, "inf"], "f": "0"}]})J")),
            "");
  expect_error(wrap(R"J({"name": "ramp", "class": "piecewise", "domain": ["-inf", "inf"], "range": [0, 1], "kinks": [0],
    "pieces": [{"on": ["-inf", 0], "f": "0"}, {"on": [0, "inf"], "f": "x"}]})J"),
               "ramp", "range", "+inf");
  expect_error(wrap(R"J({"name": "sine", "class": "entire", "f": "sin(x)", "domain": ["-inf", "inf"], "range": [-1, "1/2"]})J"),
               "sine", "range", "takes the value 0.99");
  expect_error(wrap(R"J({"name": "sqr", "class": "antiderivative", "f": "sqrt(x)", "F": "2*x^(3/2)/3", "F_sq": "x^2/2",
    "domain": [0, "inf"], "singular": [0], "range": [0, 100]})J"),
               "sqr", "range");
}

TEST(Catalog, AbsOnlyAtASingularPointIsSmoothEnough) {
  // |x| vanishes only at the declared singular point: accepted, and its derivatives print.
  EXPECT_EQ(error_of(wrap(R"J({"name": "invabs", "class": "antiderivative", "f": "1/abs(x)", "F": "sgn(x)*log(abs(x))",
    "F_sq": "-1/x", "domain": ["-inf", "inf"], "singular": [0], "range": [0, "inf"]})J")),
            "");
  // A pole that is not declared singular is not.
  expect_error(wrap(R"J({"name": "shifted", "class": "antiderivative", "f": "1/(x - 1)", "F": "log(abs(x - 1))",
    "F_sq": "-1/(x - 1)", "domain": ["-inf", "inf"], "singular": [0], "range": ["-inf", "inf"]})J"),
               "shifted", "f", "not smooth at x = 1");
}

TEST(Catalog, MalformedValuesNameTheField) {
  const std::string fract = R"J({"name": "fract", "class": "periodic", "period": 1, "domain": ["-inf", "inf"], "range": [0, 1], "jumps": [0], "pieces": [{"on": [0, 1], "f": "x"}]})J";
  expect_error(wrap(R"J({"name": "e", "class": "entire", "f": true, "domain": ["-inf", "inf"], "range": [0, 1]})J"), "e", "f", "a boolean");
  expect_error(wrap(R"J({"name": "e", "class": "entire", "f": "x", "domain": "everywhere", "range": [0, 1]})J"), "e", "domain");
  expect_error(wrap(R"J({"name": "e", "class": "entire", "f": "x", "domain": ["-inf", "inf"], "range": [1, 0]})J"), "e", "range", "lo > hi");
  expect_error(wrap(R"J({"name": "e", "class": "entire", "f": "x", "domain": ["-inf", "inf"], "range": ["sqrt(-1)", 1]})J"), "e", "range", "not a real number");
  expect_error(wrap(R"J({"name": "e", "class": "entire", "f": "exp(x)", "period": "log(-1)", "domain": ["-inf", "inf"], "range": [0, "inf"]})J"), "e", "period");
  expect_error(wrap(R"J({"name": "p", "class": "periodic", "period": 1, "domain": ["-inf", "inf"], "range": [0, 1], "jumps": [0], "pieces": {"on": [0, 1], "f": "x"}})J"), "p", "pieces", "expected a list");
  expect_error(wrap(R"J({"name": "p", "class": "periodic", "period": 1, "domain": ["-inf", "inf"], "range": [0, 1], "jumps": [0], "pieces": [{"on": [0, 1], "f": "x", "g": 1}]})J"), "p", "pieces", "unknown key 'g'");
  expect_error(wrap(R"J({"name": "p", "class": "periodic", "period": 1, "domain": ["-inf", "inf"], "range": [0, 1], "jumps": [0], "pieces": [{"on": [0, 1], "f": "Pi*x"}]})J"), "p", "pieces", "rational");
  expect_error(wrap(R"J({"name": "p", "class": "periodic", "period": 1, "domain": ["-inf", "inf"], "range": [0, 1], "jumps": ["x"], "pieces": [{"on": [0, 1], "f": "x"}]})J"), "p", "jumps", "not a constant");
  expect_error(wrap(R"J({"name": "p", "class": "periodic", "period": 1, "domain": ["-inf", "inf"], "range": [0, 1], "jumps": [0], "monotone": {"on": [0, 1]}, "pieces": [{"on": [0, 1], "f": "x"}]})J"), "p", "monotone", "expected a list");
  expect_error(wrap(fract + R"J(, {"name": "flr", "class": "combination", "of": "x - log(-1)*fract(x)", "domain": ["-inf", "inf"], "range": ["-inf", "inf"]})J"), "flr", "of", "not a real");
  expect_error(wrap(R"J({"name": 7, "class": "entire", "f": "x", "domain": ["-inf", "inf"], "range": ["-inf", "inf"]})J"), "#0", "name", "expected a string");
  expect_error(wrap(R"J(["not", "an", "object"])J"), "#0", "");
}

TEST(Catalog, FlatMustHoldToMachinePrecision) {
  expect_error(wrap(R"J({"name": "th", "class": "antiderivative", "f": "tanh(x)", "F": "logcosh(x)", "F_sq": "x - tanh(x)",
    "domain": ["-inf", "inf"], "range": [-1, 1], "scale": "Pi/2", "flat": {"beyond": 5, "left": -1, "right": 1}})J"),
               "th", "flat", "to within 2e-16");
}

TEST(Catalog, ErrorsNameTheFile) {
  try {
    bl::sym::parse_catalog(wrap(R"J({"name": "e", "class": "entire", "f": "x", "domain": [0], "range": [0, 1]})J"), "my.json");
    FAIL() << "accepted";
  } catch (const CatalogError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("my.json: catalog entry 'e', field 'domain'", 0), 0u) << e.what();
  }
}

// Issue 15: exp(-|x|) was rejected ("piece 0 is not a polynomial in x"); exp-polynomial pieces are
// in the piecewise class now, within limits that name the piece and the term.
TEST(Catalog, ExpPolynomialPieces) {
  EXPECT_EQ(
      error_of(wrap(R"J({"name": "bump", "class": "piecewise", "domain": ["-inf", "inf"], "range": [0, 1],
    "kinks": [0], "pieces": [{"on": ["-inf", 0], "f": "exp(x)"}, {"on": [0, "inf"], "f": "exp(-x)"}]})J")),
      "");
  EXPECT_EQ(
      error_of(wrap(R"J({"name": "charge", "class": "piecewise", "domain": ["-inf", "inf"], "range": [0, 1],
    "kinks": [0], "pieces": [{"on": ["-inf", 0], "f": "0"}, {"on": [0, "inf"], "f": "1 - exp(-x/2)"}]})J")),
      "");
  // The declared range is checked on exp pieces too: at the ends and at the critical points
  // (x e^{-x} peaks at 1/e = 0.3679 at x = 1).
  expect_error(wrap(R"J({"name": "bump", "class": "piecewise", "domain": ["-inf", "inf"], "range": [0, "1/2"],
    "kinks": [0], "pieces": [{"on": ["-inf", 0], "f": "exp(x)"}, {"on": [0, "inf"], "f": "exp(-x)"}]})J"),
               "bump", "range", "takes the value 1");
  expect_error(wrap(R"J({"name": "ramp", "class": "piecewise", "domain": ["-inf", "inf"], "range": [0, "1/3"],
    "kinks": [0], "pieces": [{"on": ["-inf", 0], "f": "0"}, {"on": [0, "inf"], "f": "x*exp(-x)"}]})J"),
               "ramp", "range", "critical point x = 1");
  EXPECT_EQ(
      error_of(wrap(R"J({"name": "ramp", "class": "piecewise", "domain": ["-inf", "inf"], "range": [0, "1/2"],
    "kinks": [0], "pieces": [{"on": ["-inf", 0], "f": "0"}, {"on": [0, "inf"], "f": "x*exp(-x)"}]})J")),
      "");
  expect_error(wrap(R"J({"name": "grow", "class": "piecewise", "domain": ["-inf", "inf"], "range": [0, "inf"],
    "jumps": [0], "pieces": [{"on": ["-inf", 0], "f": "0"}, {"on": [0, "inf"], "f": "exp(x)"}]})J"),
               "grow", "pieces", "grows exponentially towards +inf");
  expect_error(wrap(R"J({"name": "wave", "class": "piecewise", "domain": ["-inf", "inf"], "range": [-1, 1],
    "pieces": [{"on": ["-inf", 0], "f": "0"}, {"on": [0, "inf"], "f": "sin(x)*exp(-x)"}]})J"),
               "wave", "pieces", "complex rate");
  expect_error(wrap(R"J({"name": "steep", "class": "piecewise", "domain": ["-inf", "inf"], "range": [0, 1],
    "pieces": [{"on": ["-inf", 0], "f": "0"}, {"on": [0, "inf"], "f": "x^4*exp(-x)"}]})J"),
               "steep", "pieces", "power above 3");
  expect_error(wrap(R"J({"name": "lg", "class": "piecewise", "domain": ["-inf", "inf"], "range": [0, 1],
    "pieces": [{"on": ["-inf", 1], "f": "0"}, {"on": [1, "inf"], "f": "log(x)"}]})J"),
               "lg", "pieces", "neither a polynomial nor an exp-polynomial");
}

// Issue 15: periodic breaks had to be multiples of half the period (a duty-3/10 pulse was rejected).
TEST(Catalog, PeriodicBreaksAtRationalPoints) {
  EXPECT_EQ(error_of(wrap(R"J({"name": "duty", "class": "periodic", "period": 1, "domain": ["-inf", "inf"],
    "range": [0, 1], "jumps": [0, "3/10"], "pieces": [{"on": [0, "3/10"], "f": "1"}, {"on": ["3/10", 1], "f": "0"}]})J")),
            "");
  EXPECT_EQ(
      error_of(wrap(
          R"J({"name": "third", "class": "periodic", "period": 3, "domain": ["-inf", "inf"], "range": [0, 1],
    "jumps": [0, 1], "pieces": [{"on": [0, 1], "f": "1"}, {"on": [1, 3], "f": "0"}]})J")),
      "");
}

// Issue 15: x^n e^{ax} was refused in the entire class.
TEST(Catalog, PowerTimesExpInTheEntireClass) {
  EXPECT_EQ(
      error_of(
          wrap(R"J({"name": "xe", "class": "entire", "f": "x^2*exp(-x/3) + exp(x)", "domain": ["-inf", "inf"],
    "range": ["-inf", "inf"]})J")),
      "");
}

TEST(Catalog, NotJsonIsRejectedWithTheFileName) {
  try {
    bl::sym::parse_catalog("{\"atomics\": [", "broken.json");
    FAIL() << "accepted broken JSON";
  } catch (const CatalogError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.json"), std::string::npos);
  }
}

}  // namespace
