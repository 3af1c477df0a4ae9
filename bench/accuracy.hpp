// The error each method reaches: RMS over the input set (and, for Monte Carlo, over kErrorSeeds
// independent seeds) of method(x, sigma) - reference(x, sigma), the reference being the emitted
// double-precision smoothed function (verified elsewhere against quadrature to 1e-9). Inputs
// whose reference is not finite are skipped.
#pragma once

#include <vector>

#include "entry_view.hpp"
#include "inputs.hpp"
#include "methods.hpp"

namespace blb {

inline constexpr int kErrorSeeds = 16;

// For T = double and Method::Smoothed the answer is 0 by construction and is not computed: NaN.
// For T = float the inputs are rounded to float first and the reference is taken at the rounded
// inputs, so the float error is the function's own, not that of rounding x and sigma.
template <class T>
double rms_error(const EntryView<T>& v, const EntryView<double>& ref,
                 const std::vector<Input<double>>& in, Method m);

// RMS of the reference values over the inputs: the scale against which to read the errors.
double rms_reference(const EntryView<double>& ref, const std::vector<Input<double>>& in);

}  // namespace blb
