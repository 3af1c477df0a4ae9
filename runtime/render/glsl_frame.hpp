// Rendering a frame with the emitted GLSL on a (headless) OpenGL driver: the compiled shader
// function plus a fragment main that computes the same camera, footprint and inputs as the C++
// renderer (runtime/camera), per fragment.
#pragma once

#include <string>

#include "compiler/lir.hpp"
#include "gl/egl_runner.hpp"
#include "image/image.hpp"
#include "render/render.hpp"

namespace bl::render {

// The complete fragment shader (with its #version line) for `program` in scene `s`.
std::string glsl_fragment_source(const scene::Scene& s, const compiler::Program& program,
                                 const std::string& version = "450");
// Uniform values for frame f.
std::vector<gl::Uniform> glsl_frame_uniforms(const scene::Scene& s, const Frame& f);

Image render_glsl(gl::Context& ctx, const scene::Scene& s, const Frame& f, const compiler::Program& program);

}  // namespace bl::render
