// The three smoothing kernels, each with standard deviation sigma (DESIGN.md): Gaussian N(0, s^2),
// box U[-h, h] with h = sqrt(3) s, tent on [-w, w] with w = sqrt(6) s. Their moment generating
// functions M(s) = E[e^{sU}] are the only kernel-specific input of the exp-polynomial rules.
#pragma once

#include <ginac/ginac.h>

#include <string>

namespace bl::sym {

enum class Kernel { Gaussian, Box, Tent };
const char* to_string(Kernel k);
inline constexpr Kernel kAllKernels[] = {Kernel::Gaussian, Kernel::Box, Kernel::Tent};

const GiNaC::symbol& var_sigma();
GiNaC::ex half_width(Kernel k);  // h = sqrt(3) sigma (box), w = sqrt(6) sigma (tent), 0 (Gaussian)

// E[U^n], derived from the series of the kernel's moment generating function.
GiNaC::ex raw_moment(Kernel k, int n);

// E[e^{aU}] for real a != 0 multiplied by e^{a x}, in overflow-safe runtime form.
GiNaC::ex exp_times_mgf(Kernel k, const GiNaC::numeric& a, const GiNaC::ex& x);

// M(a) = E[e^{aU}] for real a (even in a).
GiNaC::ex kernel_mgf(Kernel k, const GiNaC::numeric& a);

// E[cos(omega U)] (the characteristic function; kernels are symmetric, so E[sin(omega U)] = 0).
GiNaC::ex characteristic(Kernel k, const GiNaC::numeric& omega);

}  // namespace bl::sym
