// Box and tent of exp-polynomial terms (x e^x, e^{-|x|}, x e^{-x} 1{x >= 0}, ...) as straight-line
// code specialised at emit time: term count, rates, degrees and coefficients are constants, the
// tent's split at its centre is structural (emit_box_tent_ept.cpp).
#pragma once

#include <string>

#include "derived.hpp"
#include "emit_syntax.hpp"

namespace bl::rulegen {

// True when every term of d (a box or tent ExpPieceTable entry) is a whole-line term or a half-line
// term decaying towards its infinite end, of degree <= 6: the form body_box_tent_ept prints.
bool box_tent_ept_straight(const sym::Derived& d);

// The function body (after BL_MATH_USING) of such an entry; `table` declares the entry's term table
// (for sigma = 0 and the generic runtime beyond |x|, sigma = 1e4), `pieces_arg` passes it.
std::string body_box_tent_ept(const sym::Derived& d, const Syntax& s, const std::string& table,
                              const std::string& pieces_arg);

}  // namespace bl::rulegen
