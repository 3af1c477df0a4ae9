// The GLSL front end: parse a file that defines `vec3 shade(vec2 uv, float time)` with glslang and
// trace it into the ir::Graph the C++ DSL produces (inputs u, v varying; time uniform; outputs r, g,
// b). Functions are inlined, constant-bound loops unrolled, branches traced on both sides and merged
// with select; see docs/own_shader.md for what is covered and how GLSL maps to the catalog.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "ir/graph.hpp"

namespace bl::glsl {

// A parse error (glslang's message, with file:line), an unsupported construct
// ("file:line:col: unsupported <what>"), or a missing or mis-typed shade().
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Pattern {
  std::string file;                   // as named in messages
  ir::Graph graph;                    // inputs "u", "v" (varying), "time" (uniform); outputs r, g, b
  std::vector<std::string> textures;  // sampler2D slots read with texture(), in order of first use
  bool uses_time = false;             // "time" reaches an output
};

// `source` with its #version line (if any, before the first code) blanked, line numbers kept: the
// front end parses the user's file as GLSL 450 behind its prelude.
std::string without_version_line(const std::string& source);
// Traces `source` (named `file` in messages). Throws Error.
Pattern trace_source(const std::string& source, const std::string& file);
// Reads and traces a file. Throws Error (also when the file cannot be read).
Pattern trace_file(const std::string& path);

}  // namespace bl::glsl
