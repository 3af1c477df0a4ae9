// (x, sigma) pairs for one atomic; see inputs.hpp.
#include "inputs.hpp"

#include <algorithm>
#include <cmath>

#include "methods.hpp"

namespace blb {

std::vector<Input<double>> make_inputs(const bl::registry::AtomicInfo& a) {
  const double lo = std::max(-4.0, a.domain_lo + 1e-3), hi = std::min(4.0, a.domain_hi - 1e-3);
  Rng rng{0x5EEDBA5Eull};
  std::vector<Input<double>> out;
  while (static_cast<int>(out.size()) < kNumInputs) {
    const double x = lo + (hi - lo) * uniform01<double>(rng);
    const double sigma = 0.01 * std::pow(100.0, uniform01<double>(rng));
    // Exact hits on a pole make the plain function infinite; keep a hair away from them.
    if (singular_distance(a, x) < 1e-6) continue;
    out.push_back({x, sigma});
  }
  return out;
}

std::vector<Input<float>> to_float(const std::vector<Input<double>>& in) {
  std::vector<Input<float>> out;
  out.reserve(in.size());
  for (const auto& p : in) out.push_back({static_cast<float>(p.x), static_cast<float>(p.sigma)});
  return out;
}

}  // namespace blb
