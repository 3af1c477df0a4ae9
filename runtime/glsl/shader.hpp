// A GLSL pattern as a suite-style ShaderDef: traced once into a pattern graph (inputs u, v, time),
// replayed into the caller's graph when traced (so parallax and lighting wrap it exactly as they wrap
// the built-in patterns, runtime/shaders/effects.hpp) and evaluated natively from the same graph.
#pragma once

#include <memory>
#include <string>

#include "dsl/vec.hpp"
#include "glsl/trace.hpp"
#include "shaders/shader.hpp"

namespace bl::glsl {

// Re-emits `pattern` into the current dsl::Tracer's graph with u, v, time bound to the given values
// (constants fold again, identical nodes are shared); returns its r, g, b.
dsl::Vec3<dsl::Var> replay(const ir::Graph& pattern, dsl::Var u, dsl::Var v, dsl::Var time);

// The ShaderDef of a traced pattern: name, description (the file), uses_time, RGB sRGB texture
// slots for its samplers, native and traced functions.
shaders::ShaderDef make_shader(std::shared_ptr<const Pattern> pattern, const std::string& name);

// Traces `path` and wraps it; the name is the file's stem. Throws Error.
std::shared_ptr<const shaders::ShaderDef> load_shader(const std::string& path);

}  // namespace bl::glsl
