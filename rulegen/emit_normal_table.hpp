// generated/bandlimit/normal_table.hpp: phi(t) and Phic(t) = P(Z > t) on [0, tail_cut] as piecewise
// polynomials for float and double, so a Gaussian break costs two short Horner chains from one table
// row instead of an exp and an erfc (or float's polynomial erfcx and its two divisions).
#pragma once

#include <string>

namespace bl::rulegen {

// One table's layout: intervals [i h, (i + 1) h], i < n = t_max / h, each a degree-`deg` polynomial
// in u = 2 (t/h - i) - 1 in [-1, 1] (the Chebyshev interpolant at deg + 1 nodes, 50-digit, then
// converted to powers of u and rounded to the type).
struct NormalTableLayout {
  const char* type;  // "float" or "double"
  int deg;
  double h;
  double t_max;  // the type's detail::tail_cut
};

// The header text (both types).
std::string normal_table_hpp();

}  // namespace bl::rulegen
