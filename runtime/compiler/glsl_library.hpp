// The generated GLSL library (generated/bandlimit*.glsl, embedded at build time) and a slicer that
// keeps only the top-level definitions a compiled shader reaches, so emitted GLSL carries only the
// table entries it uses.
#pragma once

#include <string>
#include <vector>

namespace bl::compiler {

const std::string& glsl_library();  // the whole library text, in include order

// The definitions (functions, structs, constants) reachable from `roots`, in library order.
// Throws std::invalid_argument naming a root the library does not define. The definitions reachable
// from `precise_roots` (a subset of what `roots` reaches) have GLSL's `precise` on every local float /
// vector / matrix declaration of their bodies (computed as written: no fused multiply-add, no
// reassociation; see precise_declarations).
std::string glsl_library_slice(const std::vector<std::string>& roots,
                               const std::vector<std::string>& precise_roots = {});

// `text` (GLSL without comments) with `precise ` before every declaration of a float, vecN or matN
// that begins a statement inside braces (function bodies; not parameters, for-loop headers, struct
// members or top-level constants, where GLSL allows no `precise` or nothing is computed).
std::string precise_declarations(const std::string& text);

// The texture lookups of a program reading `slots` textures: per slot the uniforms bl_tex<k>_mean
// and bl_tex<k>_sq (mipmapped, GL_LINEAR_MIPMAP_LINEAR, GL_REPEAT, levels uploaded from
// bl::texture::Pyramid), and bl_tex_plain / bl_tex_stat, the twins of texture/sample.hpp.
std::string glsl_texture_library(std::size_t slots);

}  // namespace bl::compiler
