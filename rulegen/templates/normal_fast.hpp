// phi(t) and Phic(t) = P(Z > t) for the generated Gaussian entries' breaks (0 <= t <= tail_cut):
// float and double read the piecewise polynomials of normal_table.hpp (two Horner chains from one
// row: no exp, no erfc, no division); other types take support.hpp's phi_Phic.
#pragma once

#include "normal_table.hpp"
#include "support.hpp"

namespace bl {
namespace detail {

// The table row holding t >= 0, and u in [-1, 1] within it. Above NormalTable<T>::kTMax
// (= tail_cut<T>()) the row of kTMax at u = 1: values below 1e-18 (float) and 1e-32 (double), and
// the callers take no break beyond tail_cut anyway. NaN stays NaN (row 0 is read, u is NaN).
template <class T>
inline const T* normal_row(T t, T& u) {
  using Tab = NormalTable<T>;
  const T y = (t > Tab::kTMax ? Tab::kTMax : t) * Tab::kInvH;
  int i = y >= T(0) ? static_cast<int>(y) : 0;
  if (i > Tab::kN - 1) i = Tab::kN - 1;
  u = T(2) * (y - T(i)) - T(1);
  return Tab::kC + i * Tab::kStride;
}

// phi(t) and Phic(t), t >= 0: two Horner chains from one row.
template <class T>
inline void normal_phi_Phic(T t, T& ph, T& pc) {
  using Tab = NormalTable<T>;
  if constexpr (Tab::kHave) {
    T u;
    const T* c = normal_row(t, u);
    T p = c[Tab::kDeg], q = c[2 * Tab::kDeg + 1];
    for (int k = Tab::kDeg - 1; k >= 0; --k) {
      p = p * u + c[k];
      q = q * u + c[Tab::kDeg + 1 + k];
    }
    pc = p;
    ph = q;
  } else {
    phi_Phic(t, ph, pc);
  }
}

// One function of t's row alone: column 0 Phic, 1 phi, 2 J_1 (one Horner chain).
template <class T>
inline T normal_column(T t, int column) {
  using Tab = NormalTable<T>;
  T u;
  const T* c = normal_row(t, u) + column * (Tab::kDeg + 1);
  T p = c[Tab::kDeg];
  for (int k = Tab::kDeg - 1; k >= 0; --k) p = p * u + c[k];
  return p;
}

// Phic(t) alone, t >= 0 (a break whose jump is a constant).
template <class T>
inline T normal_Phic(T t) {
  if constexpr (NormalTable<T>::kHave) {
    return normal_column(t, 0);
  } else {
    return Phic_tail(t);
  }
}

// J_1(t) = phi(t) - t Phic(t) alone, t >= 0 (a break whose jump is a kink: only the first
// derivative jumps).
template <class T>
inline T normal_J1(T t) {
  if constexpr (NormalTable<T>::kHave) {
    return normal_column(t, 2);
  } else {
    T ph, pc;
    phi_Phic(t, ph, pc);
    return ph - t * pc;
  }
}

}  // namespace detail
}  // namespace bl
