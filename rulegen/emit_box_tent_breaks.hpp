// Box and tent entries of polynomial piecewise and periodic atomics as straight-line code, by the
// break decomposition (the box/tent counterpart of emit_common.cpp's body_gauss_pw):
//   E f(x+U) = E q_j(x+U) + sum over breaks b within the kernel's support of one jump term,
// q_j the polynomial of the piece containing x, the jump terms exact integrals of the jump
// polynomial over the part of the support beyond b. See emit_box_tent_breaks.cpp.
#pragma once

#include <string>
#include <vector>

#include "derived.hpp"
#include "printer.hpp"

namespace bl::rulegen {

// The body of a box or tent PeriodicTable entry (polynomial pieces), or "" where this form does not
// apply (Gaussian kernel, or polynomials whose extension over a period would cancel).
std::string box_tent_periodic_body(const sym::Derived& d, sym::Lang lang);

// C++ only: for a box or tent PeriodicTable entry with one or two equally spaced breaks per period
// (a power-of-two spacing), the body of an entry that takes pixel-sized kernels by the nearest break
// alone and calls `general` (the full body, kept out of line) for the rest; "" where it does not apply.
// `clamp` and *in_range: see periodic_hot (emit_common.hpp).
std::string box_tent_periodic_hot(const sym::Derived& d, const std::string& general, const std::string& clamp,
                                  bool* in_range);

// For a box or tent Combination entry of a staircase (floor, ceil, trunc and their squares):
// statements that return the break sum when the kernel spans at most a few steps, else fall through
// (prepend them to the combination body); "" where the form does not apply.
std::string box_tent_staircase_narrow(const sym::Derived& d, sym::Lang lang,
                                      const std::vector<sym::Derived>* ds);

// For a box or tent PiecewiseTable entry with polynomial pieces: statements that return the break
// sum when sigma > 0 and the kernel is narrow enough, else fall through (prepend them to the
// piecewise body); "" where the form does not apply.
// Gaussian trunc/trunc^2 near 0, narrow kernels: a straight-line break sum ("" where it does not apply).
std::string gauss_staircase_near(const sym::Derived& d, sym::Lang lang, const std::vector<sym::Derived>* ds);
// Gaussian staircases at any x, narrow kernels: the nearest breaks' Phic sum ("" where it does not apply).
std::string gauss_staircase_narrow(const sym::Derived& d, sym::Lang lang,
                                   const std::vector<sym::Derived>* ds);

std::string box_tent_piecewise_narrow(const sym::Derived& d, sym::Lang lang);

}  // namespace bl::rulegen
