// Box and tent entries of polynomial piecewise and periodic atomics as straight-line code, by the
// break decomposition (the box/tent counterpart of emit_common.cpp's body_gauss_pw):
//   E f(x+U) = E q_j(x+U) + sum over breaks b within the kernel's support of one jump term,
// q_j the polynomial of the piece containing x, the jump terms exact integrals of the jump
// polynomial over the part of the support beyond b. See emit_box_tent_breaks.cpp.
#pragma once

#include <string>

#include "derived.hpp"
#include "printer.hpp"

namespace bl::rulegen {

// The body of a box or tent PeriodicTable entry (polynomial pieces), or "" where this form does not
// apply (Gaussian kernel, or polynomials whose extension over a period would cancel).
std::string box_tent_periodic_body(const sym::Derived& d, sym::Lang lang);

}  // namespace bl::rulegen
