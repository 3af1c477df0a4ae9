// See entries.hpp.
#include "entries.hpp"

#include "bandlimit/table.hpp"
#include "naive.hpp"

namespace nbs {
namespace {

namespace nv = nb::naive;
namespace rf = nb::ref;

// emitted and naive are generic lambdas (auto x, auto s), instantiated here for float and double.
template <class E, class N, class R>
Entry make(std::string name, std::string naive_text, std::vector<double> xs, E emitted, N naive, R ref) {
  return {std::move(name),
          std::move(naive_text),
          std::move(xs),
          [emitted](double x, double s) { return emitted(x, s); },
          [naive](double x, double s) { return naive(x, s); },
          [emitted](float x, float s) { return emitted(x, s); },
          [naive](float x, float s) { return naive(x, s); },
          ref};
}

}  // namespace

std::vector<Entry> entries() {
  // x next to a jump, inside a period, just below a jump, and far out (periodic entries).
  const std::vector<double> periodic = {1e-9, 0.3, 1 - 1e-6, 1000.3};
  const std::vector<double> tan_x = {0.3, 1.2, 1.55, -2.0};  // 1.55: 0.021 from the pole
  const std::vector<double> log_x = {1e-3, 0.5, 2.0, 1e3};
  const std::vector<double> pow_x = {0.5, -1.3, 10.0, 1e3};
  const std::string K = std::to_string(kNaiveTerms);
  const std::string dq = "(F(x+h) - F(x-h))/2h at the half-width min(h, r/2)";
  return {
      make(
          "gaussian fract", "Dorn et al. Fourier series, K = " + K, periodic,
          [](auto x, auto s) { return bl::gaussian::fract(x, s); },
          [](auto x, auto s) { return nv::fourier_fract(x, s, kNaiveTerms); }, rf::gauss_fract),
      make(
          "gaussian fract_sq", "Fourier series of fract^2, K = " + K, periodic,
          [](auto x, auto s) { return bl::gaussian::fract_sq(x, s); },
          [](auto x, auto s) { return nv::fourier_fract_sq(x, s, kNaiveTerms); }, rf::gauss_fract_sq),
      make(
          "gaussian floor", "x - Dorn et al. Fourier series, K = " + K, periodic,
          [](auto x, auto s) { return bl::gaussian::floor(x, s); },
          [](auto x, auto s) { return nv::fourier_floor(x, s, kNaiveTerms); }, rf::gauss_floor),
      make(
          "box fract", "(F(x+h) - F(x-h))/2h, F = floor/2 + fract^2/2", periodic,
          [](auto x, auto s) { return bl::box::fract(x, s); },
          [](auto x, auto s) { return nv::box_fract(x, s); }, rf::box_fract),
      make(
          "tent fract", "second difference of F2 (Dorn et al. fract_3)", periodic,
          [](auto x, auto s) { return bl::tent::fract(x, s); },
          [](auto x, auto s) { return nv::tent_fract(x, s); }, rf::tent_fract),
      make(
          "box tan", dq + ", F = -log abs(cos)", tan_x, [](auto x, auto s) { return bl::box::tan(x, s); },
          [](auto x, auto s) { return nv::box_tan(x, s); },
          [](double x, double s) { return rf::box_compact("tan", x, s); }),
      make(
          "box tan_sq", dq + ", F = tan x - x", tan_x, [](auto x, auto s) { return bl::box::tan_sq(x, s); },
          [](auto x, auto s) { return nv::box_tan_sq(x, s); },
          [](double x, double s) { return rf::box_compact("tan_sq", x, s); }),
      make(
          "box log", dq + ", F = x log x - x", log_x, [](auto x, auto s) { return bl::box::log(x, s); },
          [](auto x, auto s) { return nv::box_log(x, s); },
          [](double x, double s) { return rf::box_compact("log", x, s); }),
      make(
          "box log_sq", dq + ", F = x(log^2 x - 2 log x + 2)", log_x,
          [](auto x, auto s) { return bl::box::log_sq(x, s); },
          [](auto x, auto s) { return nv::box_log_sq(x, s); },
          [](double x, double s) { return rf::box_compact("log_sq", x, s); }),
      make(
          "tent log", "second difference of F2 = x^2 log(x)/2 - 3x^2/4 at min(w, r/2)", log_x,
          [](auto x, auto s) { return bl::tent::log(x, s); },
          [](auto x, auto s) { return nv::tent_log(x, s); },
          [](double x, double s) { return rf::tent_compact("log", x, s); }),
      make(
          "gaussian pow8", "Hermite-moment sum, std::pow per term", pow_x,
          [](auto x, auto s) { return bl::gaussian::pow8(x, s); },
          [](auto x, auto s) { return nv::gauss_pow(x, s, 8); },
          [](double x, double s) { return rf::gauss_pow(x, s, 8); }),
      make(
          "gaussian pow8_sq", "Hermite-moment sum of x^16, std::pow per term", pow_x,
          [](auto x, auto s) { return bl::gaussian::pow8_sq(x, s); },
          [](auto x, auto s) { return nv::gauss_pow(x, s, 16); },
          [](double x, double s) { return rf::gauss_pow(x, s, 16); }),
      make(
          "box pow8", "((x+h)^9 - (x-h)^9)/18h", pow_x, [](auto x, auto s) { return bl::box::pow8(x, s); },
          [](auto x, auto s) { return nv::box_pow(x, s, 8); },
          [](double x, double s) { return rf::box_pow(x, s, 8); }),
  };
}

}  // namespace nbs
