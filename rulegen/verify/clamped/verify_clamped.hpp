// blverify: the clamped-domain rules of generated/bandlimit/rules_clamped.hpp (derivatives,
// truncated-normal moments, Rule 3, Rule 1, bimodal) against Boost.Math quadrature of the quantity
// each one defines, at the hard cases (sigma -> 0, a domain bound at the mean, a bound 10 sigma out),
// in double and float. Prints one line per entry; --record writes each entry's "verification".
#pragma once

#include <cstdio>
#include <string>

namespace blv::clamped {

// Returns 0 when every entry is within its bound, 1 otherwise, 2 when the manifest cannot be written.
int run(const std::string& manifest_path, bool record, FILE* out);

}  // namespace blv::clamped
