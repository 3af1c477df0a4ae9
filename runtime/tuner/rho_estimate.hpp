// Yang & Barnes Appendix B.1: a constant correlation rho per binary node, estimated by sampling.
// At a fixed random set of pixels, the plain shader is evaluated (in double) at n samples of the
// pixel's Gaussian footprint; the Pearson correlation of the node's two inputs over those samples
// is averaged over the pixels where both inputs vary. The rule "gaussian:rho=const" uses it.
#pragma once

#include <cstdint>
#include <vector>

#include "ir/graph.hpp"
#include "scene/scene.hpp"

namespace bl::tuner {

// Per graph node: the estimate rounded to 0.01 (exact in checkpoints and schedules), 0 for nodes
// that are not binary or whose inputs never vary together.
std::vector<double> estimate_rho(const ir::Graph& g, const scene::Scene& s, int pixels = 64, int samples = 32,
                                 std::uint64_t seed = 11);

}  // namespace bl::tuner
