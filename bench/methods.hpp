// The five ways of computing (or approximating) the smoothed value E[g(x + U)] that the benchmark
// compares, as inline functions shared by the timing loops and the error measurement, so that the
// code timed is the code whose error is reported:
//   plain     g(x): no smoothing at all (g = f, f^2 or x^n)
//   smoothed  the emitted closed form (the reference)
//   mcN       (1/N) sum g(x + U_i), U_i drawn from the entry's kernel with a splitmix64 generator
//             inside the timed region (a renderer pays for its random numbers too); Gaussian draws
//             use Box-Muller (two samples per pair of uniforms), box 1 uniform, tent the sum of 2.
// Compact (singular) box/tent entries limit the half-width to lambda * (distance to the nearest
// singular point), as the emitted function does; the Monte Carlo estimate uses the same limit.
#pragma once

#include <cmath>
#include <cstdint>

#include "entry_view.hpp"

namespace blb {

enum class Method { Plain, Smoothed, MC4, MC16, MC64 };
inline constexpr Method kMethods[] = {Method::Plain, Method::Smoothed, Method::MC4, Method::MC16,
                                      Method::MC64};
inline constexpr int kNumMethods = 5;

inline const char* method_name(Method m) {
  switch (m) {
    case Method::Plain:
      return "plain";
    case Method::Smoothed:
      return "smoothed";
    case Method::MC4:
      return "mc4";
    case Method::MC16:
      return "mc16";
    case Method::MC64:
      return "mc64";
  }
  return "?";
}

inline int mc_samples(Method m) {
  return m == Method::MC4 ? 4 : m == Method::MC16 ? 16 : m == Method::MC64 ? 64 : 0;
}

// splitmix64 (Steele, Lea, Flood 2014): one add, two multiplies per 64 random bits.
struct Rng {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
};

// Uniform in [0, 1) with the full mantissa of T.
template <class T>
inline T uniform01(Rng& r);
template <>
inline double uniform01<double>(Rng& r) {
  return static_cast<double>(r.next() >> 11) * 0x1.0p-53;
}
template <>
inline float uniform01<float>(Rng& r) {
  return static_cast<float>(r.next() >> 40) * 0x1.0p-24f;
}

// f^n by repeated squaring (what a renderer writes for x^16: 5 multiplies, not a chain of 16).
template <class T>
inline T powi(T f, int n) {
  T r = (n & 1) ? f : T(1);
  for (n >>= 1; n > 0; n >>= 1) {
    f *= f;
    if (n & 1) r *= f;
  }
  return r;
}

// The integrand g(y) = plain(y)^power.
template <class T>
inline T integrand(const EntryView<T>& v, T y) {
  return powi(v.entry->plain(y), v.power);
}

// Distance from x to the nearest singular point of the atomic (repeating with its period).
template <class T>
inline T singular_distance(const bl::registry::AtomicInfo& a, T x) {
  T r = T(INFINITY);
  for (int i = 0; i < a.nsingular; ++i) {
    const T s = T(a.singular[i]);
    if (a.period > 0) {
      const T p = T(a.period);
      const T k = std::floor((x - s) / p);
      for (int j = -1; j <= 2; ++j) r = std::fmin(r, std::fabs(x - (s + (k + T(j)) * p)));
    } else {
      r = std::fmin(r, std::fabs(x - s));
    }
  }
  return r;
}

// Half-width of the box/tent kernel at (x, sigma), compact-limited where the entry says so.
template <class T>
inline T half_width(const EntryView<T>& v, T x, T sigma) {
  const T h = (v.kernel == Kernel::Box ? T(1.7320508075688772) : T(2.4494897427831781)) * sigma;
  if (!v.entry->compact) return h;
  return std::fmin(h, T(v.entry->lambda) * singular_distance(*v.entry->atomic, x));
}

template <class T>
inline T eval_plain(const EntryView<T>& v, T x, T) {
  return integrand(v, x);
}

template <class T>
inline T eval_smoothed(const EntryView<T>& v, T x, T sigma) {
  return v.entry->smoothed(x, sigma);
}

// Monte Carlo estimate of E[g(x + U)] with n samples (n even).
template <class T>
inline T eval_mc(const EntryView<T>& v, T x, T sigma, int n, Rng& rng) {
  T sum = T(0);
  if (v.kernel == Kernel::Gaussian) {
    for (int i = 0; i < n; i += 2) {
      const T u1 = T(1) - uniform01<T>(rng);  // (0, 1]: log is finite
      const T angle = T(6.283185307179586) * uniform01<T>(rng);
      const T r = sigma * std::sqrt(T(-2) * std::log(u1));
      sum += integrand(v, x + r * std::cos(angle)) + integrand(v, x + r * std::sin(angle));
    }
  } else if (v.kernel == Kernel::Box) {
    const T h = half_width(v, x, sigma);
    for (int i = 0; i < n; ++i) sum += integrand(v, x + h * (T(2) * uniform01<T>(rng) - T(1)));
  } else {
    const T h = half_width(v, x, sigma);
    for (int i = 0; i < n; ++i)
      sum += integrand(v, x + h * (uniform01<T>(rng) + uniform01<T>(rng) - T(1)));
  }
  return sum / T(n);
}

}  // namespace blb
