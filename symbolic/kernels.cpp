#include "kernels.hpp"

#include <map>

#include "functions.hpp"

namespace bl::sym {
using namespace GiNaC;

const char* to_string(Kernel k) {
  switch (k) {
    case Kernel::Gaussian: return "gaussian";
    case Kernel::Box: return "box";
    case Kernel::Tent: return "tent";
  }
  return "?";
}

const symbol& var_sigma() {
  static const symbol s("sigma");
  return s;
}

ex half_width(Kernel k) {
  switch (k) {
    case Kernel::Box: return sqrt(ex(3)) * var_sigma();
    case Kernel::Tent: return sqrt(ex(6)) * var_sigma();
    default: return 0;
  }
}

namespace {
ex mgf(Kernel k, const symbol& s) {
  const ex sig = var_sigma();
  switch (k) {
    case Kernel::Gaussian: return exp(pow(sig * s, 2) / 2);
    case Kernel::Box: return sinh(half_width(k) * s) / (half_width(k) * s);
    case Kernel::Tent: return pow(sinh(half_width(k) * s / 2) / (half_width(k) * s / 2), 2);
  }
  return 0;
}
}  // namespace

ex raw_moment(Kernel k, int n) {
  static std::map<std::pair<int, int>, ex> cache;
  auto key = std::make_pair(static_cast<int>(k), n);
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  const symbol s("s");
  // E[U^n] = n! [s^n] M(s).
  const ex ser = series_to_poly(mgf(k, s).series(s == 0, n + 2));
  ex m = (ser.expand().coeff(s, n) * factorial(n)).expand();
  cache[key] = m;
  return m;
}

ex exp_times_mgf(Kernel k, const numeric& a, const ex& x) {
  const ex sig = var_sigma();
  const numeric aa = abs(a);  // M is even in a
  switch (k) {
    case Kernel::Gaussian: return exp(a * x + pow(a * sig, 2) / 2);
    case Kernel::Box: return exp_sinhc(a * x, aa * half_width(k));
    case Kernel::Tent: return exp_sinhc2(a * x, aa * half_width(k) / 2);
  }
  return 0;
}

ex kernel_mgf(Kernel k, const numeric& a) {
  const ex sig = var_sigma();
  const numeric aa = abs(a);
  switch (k) {
    case Kernel::Gaussian: return exp(pow(aa * sig, 2) / 2);
    case Kernel::Box: return sinhc(aa * half_width(k));
    case Kernel::Tent: return pow(sinhc(aa * half_width(k) / 2), 2);
  }
  return 0;
}

ex characteristic(Kernel k, const numeric& omega) {
  const ex sig = var_sigma();
  switch (k) {
    case Kernel::Gaussian: return exp(-pow(omega * sig, 2) / 2);
    case Kernel::Box: return sinc(omega * half_width(k));
    case Kernel::Tent: return pow(sinc(omega * half_width(k) / 2), 2);
  }
  return 0;
}

}  // namespace bl::sym
