// The "naive" forms: the textbook closed forms a user would type, evaluated directly in the scalar
// type T (float or double) with no series switch, no argument reduction and no cancellation care.
// They are what the generated table is compared against in the notebooks; none of them is used by
// the table itself.
#pragma once

#include <cmath>

namespace nb::naive {

template <class T>
constexpr T kPi = T(3.14159265358979323846);

// Dorn et al. 2015, Table 1, fract_1 truncated after K terms (their Figure 3b):
// 1/2 - sum_{n<=K} e^{-2 pi^2 n^2 s^2} sin(2 pi n x) / (pi n).
template <class T>
T fourier_fract(T x, T s, int K) {
  T acc = T(0.5);
  for (int n = 1; n <= K; ++n) {
    const T nf = T(n);
    acc -= std::exp(T(-2) * kPi<T> * kPi<T> * nf * nf * s * s) * std::sin(T(2) * kPi<T> * nf * x) /
           (kPi<T> * nf);
  }
  return acc;
}

// fract^2 = 1/3 + sum_n (cos(2 pi n x)/(pi n)^2 - sin(2 pi n x)/(pi n)), damped and truncated alike.
template <class T>
T fourier_fract_sq(T x, T s, int K) {
  T acc = T(1) / T(3);
  for (int n = 1; n <= K; ++n) {
    const T nf = T(n), th = T(2) * kPi<T> * nf * x;
    const T damp = std::exp(T(-2) * kPi<T> * kPi<T> * nf * nf * s * s);
    acc += damp * (std::cos(th) / (kPi<T> * kPi<T> * nf * nf) - std::sin(th) / (kPi<T> * nf));
  }
  return acc;
}

// floor = x - fract (Dorn et al., Table 1).
template <class T>
T fourier_floor(T x, T s, int K) {
  return x - fourier_fract(x, s, K);
}

// Box of fract: (F(x+h) - F(x-h)) / 2h with F(y) = floor(y)/2 + fract(y)^2/2 = int_0^y fract
// (Dorn et al.'s fract_2, written with the box's half-width h = sqrt(3) s).
template <class T>
T box_fract(T x, T s) {
  auto F = [](T y) {
    const T q = std::floor(y), r = y - q;
    return q / T(2) + r * r / T(2);
  };
  const T h = std::sqrt(T(3)) * s;
  return (F(x + h) - F(x - h)) / (T(2) * h);
}

// Tent of fract: (F2(x+w) - 2 F2(x) + F2(x-w)) / w^2, F2(y) = int_0^y F = q(q-1)/4 + q/6 + q r/2
// + r^3/6 (q = floor(y), r = fract(y); Dorn et al.'s fract_3 with w = sqrt(6) s).
template <class T>
T tent_fract(T x, T s) {
  auto F2 = [](T y) {
    const T q = std::floor(y), r = y - q;
    return q * (q - T(1)) / T(4) + q / T(6) + q * r / T(2) + r * r * r / T(6);
  };
  const T w = std::sqrt(T(6)) * s;
  return (F2(x + w) - T(2) * F2(x) + F2(x - w)) / (w * w);
}

// The compact kernels of the table (box/tent of tan and log) use the half-width hh = min(h, r/2),
// r the distance to the nearest singularity; the naive forms take the same hh, so both compute the
// same quantity and only the numerics differ.
template <class T>
T tan_pole_distance(T x) {
  const T xr = x - kPi<T> * std::floor(x / kPi<T>);
  return std::fabs(xr - kPi<T> / T(2));
}

// Antiderivatives: F' = f (tan, tan^2, log, log^2) and F2'' = log.
template <class T>
T F_tan(T y) {
  return -std::log(std::fabs(std::cos(y)));
}
template <class T>
T F_tan_sq(T y) {
  return std::tan(y) - y;
}
template <class T>
T F_log(T y) {
  return y * std::log(y) - y;
}
template <class T>
T F_log_sq(T y) {
  const T l = std::log(y);
  return y * (l * l - T(2) * l + T(2));
}
template <class T>
T F2_log(T y) {
  return y * y / T(2) * std::log(y) - T(3) / T(4) * y * y;
}

template <class T, class F>
T box_diff(F Fn, T x, T hh) {
  return (Fn(x + hh) - Fn(x - hh)) / (T(2) * hh);
}

template <class T>
T box_tan(T x, T s) {
  return box_diff<T>(F_tan<T>, x, std::fmin(std::sqrt(T(3)) * s, tan_pole_distance(x) / T(2)));
}
template <class T>
T box_tan_sq(T x, T s) {
  return box_diff<T>(F_tan_sq<T>, x, std::fmin(std::sqrt(T(3)) * s, tan_pole_distance(x) / T(2)));
}
template <class T>
T box_log(T x, T s) {
  return box_diff<T>(F_log<T>, x, std::fmin(std::sqrt(T(3)) * s, x / T(2)));
}
template <class T>
T box_log_sq(T x, T s) {
  return box_diff<T>(F_log_sq<T>, x, std::fmin(std::sqrt(T(3)) * s, x / T(2)));
}
template <class T>
T tent_log(T x, T s) {
  const T w = std::fmin(std::sqrt(T(6)) * s, x / T(2));
  return (F2_log(x + w) - T(2) * F2_log(x) + F2_log(x - w)) / (w * w);
}

// Gaussian of x^n: the Hermite-moment sum E[(x + sZ)^n] = sum_j C(n, 2j) x^{n-2j} s^{2j} (2j-1)!!,
// term by term with std::pow.
template <class T>
T gauss_pow(T x, T s, int n) {
  T acc = T(0), binom = T(1), dfact = T(1);  // C(n, 2j) and (2j-1)!!
  for (int j = 0; 2 * j <= n; ++j) {
    acc += binom * std::pow(x, T(n - 2 * j)) * std::pow(s, T(2 * j)) * dfact;
    binom = binom * T(n - 2 * j) * T(n - 2 * j - 1) / (T(2 * j + 1) * T(2 * j + 2));
    dfact *= T(2 * j + 1);
  }
  return acc;
}

// Box of x^n: ((x+h)^{n+1} - (x-h)^{n+1}) / (2 (n+1) h).
template <class T>
T box_pow(T x, T s, int n) {
  const T h = std::sqrt(T(3)) * s;
  return (std::pow(x + h, T(n + 1)) - std::pow(x - h, T(n + 1))) / (T(2 * (n + 1)) * h);
}

}  // namespace nb::naive
