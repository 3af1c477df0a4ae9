// generated/bandlimit/normal_table.hpp through normal_fast.hpp: phi(t), Phic(t) and J_1(t) for the
// generated Gaussian breaks, float and double, against 50-digit erfc and exp (Boost.Math), on a dense
// grid, at every interval edge and one ulp either side, at 0 and tail_cut, beyond it, and NaN.
#include <gtest/gtest.h>

#include <boost/math/special_functions/erf.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <cmath>
#include <limits>
#include <vector>

#include "bandlimit/normal_fast.hpp"

namespace {

using Mp = boost::multiprecision::cpp_bin_float_50;

double ref_phic(double t) {
  return static_cast<double>(boost::math::erfc(Mp(t) / sqrt(Mp(2))) / 2);
}
double ref_phi(double t) {
  return static_cast<double>(exp(-Mp(t) * Mp(t) / 2) / sqrt(2 * boost::math::constants::pi<Mp>()));
}
// J_1(t) = phi(t) - t Phic(t) at 50 digits (the difference cancels at large t in double).
double ref_j1(double t) {
  const Mp m(t);
  return static_cast<double>(exp(-m * m / 2) / sqrt(2 * boost::math::constants::pi<Mp>()) -
                             m * boost::math::erfc(m / sqrt(Mp(2))) / 2);
}

// The points to check for T: a dense grid plus each interval edge and its float neighbours.
template <class T>
std::vector<T> points() {
  using Tab = bl::detail::NormalTable<T>;
  std::vector<T> ts;
  const int dense = 20000;
  for (int i = 0; i <= dense; ++i) ts.push_back(static_cast<T>(Tab::kTMax * i / dense));
  for (int i = 0; i <= Tab::kN; ++i) {
    const T e = static_cast<T>(i) / Tab::kInvH;
    ts.push_back(e);
    ts.push_back(std::nextafter(e, T(0)));
    ts.push_back(std::nextafter(e, T(100)));
  }
  ts.push_back(std::numeric_limits<T>::denorm_min());
  return ts;
}

// Absolute error bounds promised in normal_table.hpp's header.
template <class T>
double bound();
template <>
double bound<float>() {
  return 1e-7;
}
template <>
double bound<double>() {
  return 3e-16;
}

template <class T>
void check_accuracy() {
  double worst_c = 0, worst_p = 0, worst_j = 0, at_c = 0, at_p = 0, at_j = 0;
  for (T t : points<T>()) {
    if (t < T(0)) continue;
    T ph, pc;
    bl::detail::normal_phi_Phic(t, ph, pc);
    const double ec = std::fabs(double(pc) - ref_phic(double(t)));
    const double ep = std::fabs(double(ph) - ref_phi(double(t)));
    if (ec > worst_c) worst_c = ec, at_c = double(t);
    if (ep > worst_p) worst_p = ep, at_p = double(t);
    const double ej = std::fabs(double(bl::detail::normal_J1(t)) - ref_j1(double(t)));
    if (ej > worst_j) worst_j = ej, at_j = double(t);
    EXPECT_EQ(bl::detail::normal_Phic(t), pc) << "Phic alone differs from the pair at t = " << t;
  }
  EXPECT_LE(worst_c, bound<T>()) << "Phic worst at t = " << at_c;
  EXPECT_LE(worst_p, bound<T>()) << "phi worst at t = " << at_p;
  EXPECT_LE(worst_j, bound<T>()) << "J_1 worst at t = " << at_j;
  std::printf(
      "%s: worst |Phic error| %.2e (t = %.6g), |phi error| %.2e (t = %.6g), |J_1 error| %.2e (t = %.6g)\n",
      sizeof(T) == 4 ? "float" : "double", worst_c, at_c, worst_p, at_p, worst_j, at_j);
}

TEST(NormalTable, FloatWithinBound) {
  check_accuracy<float>();
}
TEST(NormalTable, DoubleWithinBound) {
  check_accuracy<double>();
}

// The table covers exactly [0, tail_cut]: the generated entries take no break beyond tail_cut.
TEST(NormalTable, RangeIsTailCut) {
  EXPECT_EQ(bl::detail::NormalTable<float>::kTMax, bl::detail::tail_cut<float>());
  EXPECT_EQ(bl::detail::NormalTable<double>::kTMax, bl::detail::tail_cut<double>());
}

// Beyond kTMax: the value at kTMax, tiny and non-negative (no extrapolated polynomial).
template <class T>
void check_beyond() {
  using Tab = bl::detail::NormalTable<T>;
  for (T t :
       {Tab::kTMax, std::nextafter(Tab::kTMax, T(100)), T(50), T(1e30), std::numeric_limits<T>::infinity()}) {
    T ph, pc;
    bl::detail::normal_phi_Phic(t, ph, pc);
    EXPECT_GE(pc, T(0)) << t;
    EXPECT_GE(ph, T(0)) << t;
    EXPECT_LE(double(pc), 2 * ref_phic(double(Tab::kTMax)) + bound<T>() * 1e-9) << t;
    EXPECT_LE(double(ph), 2 * ref_phi(double(Tab::kTMax)) + bound<T>() * 1e-9) << t;
  }
}
TEST(NormalTable, BeyondTailCut) {
  check_beyond<float>();
  check_beyond<double>();
}

template <class T>
void check_nan() {
  T ph = 0, pc = 0;
  bl::detail::normal_phi_Phic(std::numeric_limits<T>::quiet_NaN(), ph, pc);
  EXPECT_TRUE(std::isnan(ph));
  EXPECT_TRUE(std::isnan(pc));
  EXPECT_TRUE(std::isnan(bl::detail::normal_Phic(std::numeric_limits<T>::quiet_NaN())));
}
TEST(NormalTable, NanStaysNan) {
  check_nan<float>();
  check_nan<double>();
}

// Types without a table (long double) fall back to support.hpp's phi_Phic.
TEST(NormalTable, WideTypeFallsBack) {
  long double ph, pc;
  bl::detail::normal_phi_Phic(1.5L, ph, pc);
  EXPECT_NEAR(static_cast<double>(pc), ref_phic(1.5), 1e-18);
  EXPECT_NEAR(static_cast<double>(ph), ref_phi(1.5), 1e-18);
}

}  // namespace
