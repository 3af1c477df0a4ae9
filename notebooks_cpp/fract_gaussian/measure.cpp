// See measure.hpp.
#include "measure.hpp"

#include <algorithm>
#include <cmath>

#include "bandlimit/table.hpp"
#include "naive.hpp"
#include "reference.hpp"
#include "timing.hpp"

namespace nbf {

std::vector<double> error_grid() {
  std::vector<double> xs;
  for (int i = 0; i < kPeriodPoints; ++i) xs.push_back((i + 0.5) / kPeriodPoints);
  for (double x : {0.0, 1e-9, -1e-9, 1 - 1e-9, 0.5, 1000.3, -7.7}) xs.push_back(x);
  return xs;
}

Errors measure_errors(double s, const std::vector<double>& xs) {
  Errors e{s, std::vector<double>(kTerms.size(), 0.0), 0, 0, 0, 0, 0, 0};
  auto worst = [](double& w, double v) { w = std::max(w, v); };
  const float sf = static_cast<float>(s);
  for (double x : xs) {
    const nb::ref::Exact g = nb::ref::gauss_fract(x, s);
    for (size_t k = 0; k < kTerms.size(); ++k)
      worst(e.naive[k], nb::ref::rel_error(nb::naive::fourier_fract(x, s, kTerms[k]), g));
    worst(e.ours, nb::ref::rel_error(bl::gaussian::fract(x, s), g));
    worst(e.box_vs_gauss, nb::ref::rel_error(bl::box::fract(x, s), g));
    worst(e.tent_vs_gauss, nb::ref::rel_error(bl::tent::fract(x, s), g));
    worst(e.box_own, nb::ref::rel_error(bl::box::fract(x, s), nb::ref::box_fract(x, s)));
    worst(e.tent_own, nb::ref::rel_error(bl::tent::fract(x, s), nb::ref::tent_fract(x, s)));
    const float xf = static_cast<float>(x);
    worst(e.ours_float, nb::ref::rel_error(bl::gaussian::fract(xf, sf), nb::ref::gauss_fract(xf, sf)));
  }
  return e;
}

Timings measure_timings(double s) {
  std::vector<double> xs;
  std::vector<float> xf;
  for (int i = 0; i < 4096; ++i) {
    xs.push_back(-1.0 + 3.0 * (i + 0.37) / 4096);
    xf.push_back(static_cast<float>(xs.back()));
  }
  const float sf = static_cast<float>(s);
  Timings t{s, {}, 0, 0, 0, 0, 0};
  for (int K : kTerms)
    t.naive.push_back(nb::ns_per_call([&](double x) { return nb::naive::fourier_fract(x, s, K); }, xs));
  t.ours = nb::ns_per_call([&](double x) { return bl::gaussian::fract(x, s); }, xs);
  t.ours_float = nb::ns_per_call([&](float x) { return bl::gaussian::fract(x, sf); }, xf);
  t.box = nb::ns_per_call([&](double x) { return bl::box::fract(x, s); }, xs);
  t.tent = nb::ns_per_call([&](double x) { return bl::tent::fract(x, s); }, xs);
  t.plain = nb::ns_per_call([](double x) { return x - std::floor(x); }, xs);
  return t;
}

double reference_check(int& n) {
  double w = 0;
  n = 0;
  const double pts[][2] = {{0.3, 0.05}, {0.999, 0.1}, {0.5, 0.2}, {0.1, 0.3}, {1e-9, 0.02}, {1000.3, 0.5}};
  for (const auto& p : pts) w = std::max(w, nb::ref::check_gauss_fract(p[0], p[1])), ++n;
  return w;
}

}  // namespace nbf
