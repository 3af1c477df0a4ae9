// One registry entry as the benchmark sees it: the registry row plus the facts parsed once from
// its strings (kernel, integrand power, display name, function family). The views come from
// entry_view.cpp, the only translation unit that instantiates the generated table.
#pragma once

#include <string>
#include <vector>

#include "bandlimit/registry_types.hpp"

namespace blb {

enum class Kernel { Gaussian, Box, Tent };

template <class T>
struct EntryView {
  const bl::registry::Entry<T>* entry;
  Kernel kernel;
  int power;           // integrand g = plain^power: 1, 2 (squared entries) or n (moment of order n)
  std::string name;    // "gaussian/fract", "box/sin_sq", "tent/moment3"
  std::string family;  // trig, exp-like, powers, piecewise, periodic, singular
};

// Every registry entry, in registry order; the float and double lists are index-aligned.
const std::vector<EntryView<double>>& double_entries();
const std::vector<EntryView<float>>& float_entries();

// The families of the plot, in panel order.
const std::vector<std::string>& families();

}  // namespace blb
