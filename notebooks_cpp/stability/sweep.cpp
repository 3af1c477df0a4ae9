// See sweep.hpp.
#include "sweep.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace nbs {

std::vector<double> sigma_grid() {
  std::vector<double> s;
  for (int k = -48; k <= 24; ++k) s.push_back(std::pow(10.0, k / 4.0));
  return s;
}

std::vector<Point> sweep(const Entry& e, const std::vector<double>& sigmas) {
  std::vector<Point> out;
  for (double s : sigmas) {
    Point p{s, 0, 0, 0, 0, 0};
    for (double x : e.xs) {
      const nb::ref::Exact r = e.ref(x, s);
      if (std::isfinite(r.hi)) {
        p.naive_d = std::max(p.naive_d, nb::ref::rel_error(e.naive_d(x, s), r));
        p.emitted_d = std::max(p.emitted_d, nb::ref::rel_error(e.emitted_d(x, s), r));
      }
      // float: the inputs rounded to float, the reference at those inputs.
      const float xf = static_cast<float>(x), sf = static_cast<float>(s);
      const nb::ref::Exact rf = e.ref(xf, sf);
      if (!(std::fabs(rf.hi) <= FLT_MAX)) {
        ++p.skipped_f;
        continue;
      }
      p.naive_f = std::max(p.naive_f, nb::ref::rel_error(e.naive_f(xf, sf), rf));
      p.emitted_f = std::max(p.emitted_f, nb::ref::rel_error(e.emitted_f(xf, sf), rf));
    }
    if (p.skipped_f == static_cast<int>(e.xs.size())) p.naive_f = p.emitted_f = NAN;  // nothing to compare
    out.push_back(p);
  }
  return out;
}

}  // namespace nbs
