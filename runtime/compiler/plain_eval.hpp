// The plain shader in double: the value of every node of a traced graph at given input values,
// with the catalog's own f (ir::plain_atomic). The tuner's rho estimate and the lowering's
// continuity probes read it.
#pragma once

#include <vector>

#include "ir/graph.hpp"
#include "texture/texture.hpp"

namespace bl::compiler {

// The plain value of node n (arithmetic, constant or atomic call) from its arguments' values a, b,
// c; false for an input or a texture, whose values the caller holds.
bool plain_node(const ir::Node& n, double a, double b, double c, double* y);

// Per node, in node order. `inputs` is indexed by input slot. Texture nodes read the textures
// (indexed by texture slot; an unbound slot throws, naming it); without textures they are NaN.
std::vector<double> plain_values(const ir::Graph& g, const std::vector<double>& inputs,
                                 const std::vector<const texture::Texture*>* textures = nullptr);

// Per node, at surface point (u, v): the inputs named u and v, view_z and light_z 1 (view and light
// along the normal), every other input 0; textures NaN. The compile-time probes of the lowering
// (continuity across cells, a tiling's spatial moments) read the plain shader here.
std::vector<double> plain_at_surface(const ir::Graph& g, double u, double v);

}  // namespace bl::compiler
