// The valid range of a scene's pixel values, per channel, for the out-of-range counts of the
// reports (image/pixel_check.hpp): the shader's declared range where interval analysis bounds its
// output (ir/ranges.hpp: the plain shader can never leave it, so neither can an average of it);
// on an unbounded side, [0, 1] widened to what the ground truth and the plain render reach. The
// background colour (rays that miss) is always inside.
#pragma once

#include <vector>

#include "image/pixel_check.hpp"
#include "ir/graph.hpp"
#include "scene/scene.hpp"

namespace bl::render {

// `truths`: the ground truth of every frame (render::frames order); renders the plain frames.
ValueRange valid_range(const scene::Scene& s, const ir::Graph& g, const std::vector<Image>& truths);

// The declared part alone: the output's interval bounds where finite, widened to the background.
// (blgpu_pack packs them; blgpu_time widens [0, 1] by its own truth and plain images.)
DeclaredBounds declared_bounds(const scene::Scene& s, const ir::Graph& g);

}  // namespace bl::render
