// What each catalog class assumes, checked on a parsed entry (catalog.cpp calls these). Every
// failure is a CatalogError naming the entry and the field. Numerical checks run at 40 digits at
// irrational sample points (k sqrt(2)/3 + pi/100, far points, points next to finite domain ends and
// singular points), never at round numbers that a wrong definition could be tuned to.
#pragma once

#include <ginac/ginac.h>

#include <string>
#include <vector>

#include "catalog.hpp"

namespace bl::sym {

// The real roots of u's numerator when that is a polynomial in x with rational coefficients (exact
// isolation over the Cauchy bound, each to ~1e-40), else none.
std::vector<GiNaC::numeric> real_roots(const GiNaC::ex& u);

// Sample points in the open domain, away from singular points and their periodic images, sorted.
std::vector<GiNaC::numeric> sample_points(const Atomic& a);

// F' = f: GiNaC differentiation (x real) and simplification to zero; where that does not decide,
// the difference at every sample point, relative 1e-25 at 40 digits.
void check_antiderivative(const Atomic& a, const std::string& field, const GiNaC::ex& F, const GiNaC::ex& f);

// F is real and continuous between singular points: at every zero of the argument of a
// discontinuous or branching function in F (sgn, step, abs, log, non-integer powers, poles), the
// values just left and right agree. (A jump that GiNaC differentiates away, as d/dx sgn = 0, is
// invisible to check_antiderivative.)
void check_continuity(const Atomic& a, const std::string& field, const GiNaC::ex& F);

// Antiderivative class: f is analytic between the singular points (the box/tent evaluate its
// Taylor series in the half-width): an argument of abs/sgn/step, a pole or a branch point that
// changes sign at a non-singular point is an error. abs(u) left in f (u vanishing only at singular
// points) is rewritten as u sgn(u), which differentiates without complex conjugates.
void check_smooth(Atomic& a);

// "flat": f equals left/right to within 2^-52 for |x| >= beyond.
void check_flat(const Atomic& a);

// The declared range contains every value f takes. Polynomial pieces: exact extremes (end points,
// limits at +-inf, critical points by root isolation at 40 digits); exp-polynomial pieces: checked at
// spread points and the critical points between them. Entire and antiderivative
// atomics: f at the sample points and at the critical points between them.
void check_range(const Atomic& a);

}  // namespace bl::sym
