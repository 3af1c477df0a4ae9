// The GLSL prelude the front end puts before a user's file: bandlimit's atomics that GLSL lacks
// (saturate, triangle, square, pow2..pow8, inv, inv2), written as plain GLSL with the catalog's
// definitions, so a user's file stays valid GLSL for any compiler once the prelude is pasted in
// front of it. The tracer maps calls of these functions straight to the atomics.
#pragma once

#include <string>
#include <vector>

namespace bl::glsl {

// The prelude's text (GLSL 450, no #version line), float and vec2/vec3/vec4 overloads.
const std::string& prelude();
// The atomic names the prelude defines (each a catalog atomic of the same name).
const std::vector<std::string>& prelude_atomics();

}  // namespace bl::glsl
