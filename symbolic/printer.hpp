// Deterministic printing of GiNaC expressions as C++ (generic over the scalar type T) and GLSL.
// GiNaC's own printer orders terms by hash, which changes from run to run (ASLR), so generated
// files would drift: here every sum and product is printed with its operands sorted by their
// printed text.
#pragma once

#include <ginac/ginac.h>

#include <string>

namespace bl::sym {

enum class Lang { Cpp, Glsl, Text };

// Prints e. Symbols print by name; rationals exactly (C++: T(p)/T(q), GLSL: (p.0/q.0)); Pi as
// the runtime constant; integer powers as products; registered helpers (functions.hpp) as calls
// of the runtime support (bl::detail:: in C++, bl_ in GLSL).
std::string print(const GiNaC::ex& e, Lang lang);

}  // namespace bl::sym
