// GiNaC functions that GiNaC lacks and that derived formulas use. Each has an evalf (CLN, for
// checks at high precision), a derivative where the engine differentiates through it, and a name
// that the printer (printer.hpp) maps to the emitted runtime helper.
#pragma once

#include <ginac/ginac.h>

namespace bl::sym {

DECLARE_FUNCTION_1P(Phi)         // standard normal CDF
DECLARE_FUNCTION_1P(phi)         // standard normal density
DECLARE_FUNCTION_1P(sinc)        // sin t / t
DECLARE_FUNCTION_1P(sinhc)       // sinh t / t
DECLARE_FUNCTION_1P(logcosh)     // log cosh x, without overflow
DECLARE_FUNCTION_2P(exp_sinhc)   // exp(u) sinhc(v), without overflow
DECLARE_FUNCTION_2P(exp_sinhc2)  // exp(u) sinhc(v)^2, without overflow
DECLARE_FUNCTION_2P(prod0)       // a * b, with 0 * inf = 0 (a sinh that is 0 times a huge kernel factor)
DECLARE_FUNCTION_1P(sgn)         // sign of x (derivative 0 almost everywhere)
DECLARE_FUNCTION_1P(clausen2)    // Clausen's Cl2(t) = -int_0^t log|2 sin(u/2)| du

// Forces registration (static initialisers in a library may be dropped by the linker).
void register_functions();

}  // namespace bl::sym
