// The (x, sigma) pairs every method is timed and measured on: x uniform in [-4, 4] clipped to the
// atomic's open domain, sigma log-uniform in [0.01, 1]. Fixed seed: every entry of an atomic sees
// the same set, and every run the same sets.
#pragma once

#include <vector>

#include "bandlimit/registry_types.hpp"

namespace blb {

inline constexpr int kNumInputs = 256;

template <class T>
struct Input {
  T x, sigma;
};

std::vector<Input<double>> make_inputs(const bl::registry::AtomicInfo& a);

// The same pairs rounded to float (rounding keeps them inside the open domain: they start
// at least 1e-3 inside it).
std::vector<Input<float>> to_float(const std::vector<Input<double>>& in);

}  // namespace blb
