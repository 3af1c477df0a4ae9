// blverify: the (x, sigma) grid (see grid.hpp).
#include "grid.hpp"

#include <algorithm>
#include <cmath>

namespace blv {
namespace {

const std::vector<double> kBaseX = {0, 1e-9, -1e-9, 0.25, -0.25, 0.5, -0.5, 1, -1, 1.5, -1.5, 3.7, -3.7,
                                    10, -10, 1e3 + 0.3, 1e6 + 0.3, -1e6 - 0.3};
const std::vector<double> kMomentX = {0, 1e-9, -1e-9, 0.5, -0.5, 1, -1, 3.7, -3.7, 10, -10, 1e3 + 0.3, -1e6 - 0.3};
const std::vector<double> kBreakOffsets = {0, 1e-9, -1e-9, 1e-4, -1e-4};

}  // namespace

const std::vector<double>& sigma_grid() {
  static const std::vector<double> s = {0, 1e-12, 1e-8, 1e-4, 0.01, 0.1, 0.3, 1, 3, 10, 100, 1e4, 1e6};
  return s;
}

std::vector<double> x_grid(const Spec& spec, bool moment) {
  std::vector<double> xs = moment ? kMomentX : kBaseX;
  for (double b : spec.breaks)
    for (double d : kBreakOffsets) xs.push_back(b + d);
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  return xs;
}

std::vector<GridPoint> grid(const Spec& spec, bool moment) {
  std::vector<GridPoint> g;
  for (double x : x_grid(spec, moment))
    for (double s : sigma_grid()) g.push_back({x, s});
  return g;
}

std::string grid_description() {
  return "x in {0, +-1e-9, +-0.25, +-0.5, +-1, +-1.5, +-3.7, +-10, 1e3+0.3, 1e6+0.3, -1e6-0.3} plus, for every "
         "break b of the atomic (first period), {b, b+-1e-9, b+-1e-4}; moments: x in {0, +-1e-9, +-0.5, +-1, +-3.7, "
         "+-10, 1e3+0.3, -1e6-0.3}. sigma in {0, 1e-12, 1e-8, 1e-4, 0.01, 0.1, 0.3, 1, 3, 10, 100, 1e4, 1e6}. "
         "Points outside the domain are not compared (compact entries must return NaN there). Points whose "
         "reference is not finite or overflows double are skipped and counted.";
}

}  // namespace blv
