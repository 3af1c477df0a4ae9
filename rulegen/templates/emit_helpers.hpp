// Small helpers the generated table uses besides support.hpp (copied verbatim by `rulegen emit`).
#pragma once

#include <cmath>
#include <limits>

// Unqualified math calls in generated code resolve to std:: for float/double and, by ADL, to the
// multiprecision library's overloads when the verifier instantiates the table at 50 digits.
#define BL_MATH_USING \
  using std::abs;     \
  using std::atan;    \
  using std::cos;     \
  using std::cosh;    \
  using std::exp;     \
  using std::floor;   \
  using std::log;     \
  using std::sin;     \
  using std::sinh;    \
  using std::sqrt;    \
  using std::tan;     \
  using std::tanh;

namespace bl {
namespace detail {

template <class T>
T nan() {
  return T(std::numeric_limits<double>::quiet_NaN());
}
// pi in the precision of T (atan folds to a constant for float and double).
template <class T>
T pi() {
  using std::atan;
  return T(4) * atan(T(1));
}
// Up to which hh / scale the antiderivative rules use their 7-term Taylor series instead of the
// difference quotient: the series' truncation error is about (hh/scale)^14, the quotient's rounding
// error about eps |F| / (hh |f|) (eps |F2| / (hh^2 |f|) for the tent). 0.05 keeps both below 1e-13
// in double; float needs the longer reach (0.35^14 = 4e-7 < 2e-5).
template <class T>
T series_reach() {
  return std::numeric_limits<T>::digits <= 24 ? T(0.35) : T(0.05);
}
template <class T>
T min2(T a, T b) {
  return b < a ? b : a;
}

}  // namespace detail
}  // namespace bl
