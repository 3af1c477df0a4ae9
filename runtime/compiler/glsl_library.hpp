// The generated GLSL library (generated/bandlimit*.glsl, embedded at build time) and a slicer that
// keeps only the top-level definitions a compiled shader reaches, so emitted GLSL carries only the
// table entries it uses.
#pragma once

#include <string>
#include <vector>

namespace bl::compiler {

const std::string& glsl_library();  // the whole library text, in include order

// The definitions (functions, structs, constants) reachable from `roots`, in library order.
// Throws std::invalid_argument naming a root the library does not define.
std::string glsl_library_slice(const std::vector<std::string>& roots);

// The texture lookups of a program reading `slots` textures: per slot the uniforms bl_tex<k>_mean
// and bl_tex<k>_sq (mipmapped, GL_LINEAR_MIPMAP_LINEAR, GL_REPEAT, levels uploaded from
// bl::texture::Pyramid), and bl_tex_plain / bl_tex_stat, the twins of texture/sample.hpp.
std::string glsl_texture_library(std::size_t slots);

}  // namespace bl::compiler
