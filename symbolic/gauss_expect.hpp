// Expectations over standard normal variables, exactly (GiNaC): the moments the bivariate rules
// are derived from. A polynomial in independent standard normals W, V1, V2, ... and in an
// indicator Q = 1{W > -t} maps to normal moments E[V^k] = (k-1)!! and the truncated moments
// J_k(t) = E[W^k 1{W > -t}] = (-t)^(k-1) phi(t) + (k-1) J_(k-2), J_0 = Phi(t), J_1 = phi(t).
#pragma once

#include <ginac/ginac.h>

#include <vector>

namespace bl::sym {

// E[p] with w, others independent standard normals and q = 1{w > -t} (q^2 = q). p must be a
// polynomial in w, others and q. t may be any expression (Phi and phi are functions.hpp's).
GiNaC::ex gauss_expect(const GiNaC::ex& p, const GiNaC::symbol& w, const std::vector<GiNaC::symbol>& others,
                       const GiNaC::symbol& q, const GiNaC::ex& t);

// E[p] with p a polynomial in independent standard normals zs only.
GiNaC::ex normal_expect(const GiNaC::ex& p, const std::vector<GiNaC::symbol>& zs);

}  // namespace bl::sym
