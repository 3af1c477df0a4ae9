// Monotone pieces of an atomic and their inverses (catalog field "monotone"), used by Rule 2.
#pragma once

#include <ginac/ginac.h>

#include <vector>

#include "catalog.hpp"

namespace bl::sym {

// f on one monotone piece, in x (the definition, or the catalog piece of a piecewise/periodic
// atomic that contains it). Throws CatalogError (entry, field 'monotone') when no piece contains it.
GiNaC::ex monotone_f(const Atomic& a, const Monotone& m);

// Sample points strictly inside [lo, hi] (either end may be infinite).
std::vector<double> interior_points(const Bound& lo, const Bound& hi, int n);

// Checks every monotone piece at 30 digits: f' keeps one sign inside, and the declared inverse
// satisfies g(f(x)) = x there. Throws CatalogError naming the entry and the field 'monotone'.
void check_monotone(const Atomic& a);

}  // namespace bl::sym
