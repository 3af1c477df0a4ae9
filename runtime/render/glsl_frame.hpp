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

// How the fragment main turns a fragment into the program's inputs.
struct FragmentOptions {
  // 0: one evaluation at the pixel centre with the pixel's footprint (the smoothed renderer).
  // n > 0: supersampling, n evaluations at Gaussian-jittered positions with a zero footprint,
  // averaged (MSAA-n of a plain program, as a renderer runs it: all samples in one fragment).
  int samples = 0;
  // Shade pixel gl_FragCoord mod bl_size: a target larger than the scene repeats the scene's image,
  // so a GPU can be filled with exactly the scene's per-pixel work (timing).
  bool tiled = false;
  // Supersampling's sample j draws from the hash of (pixel, j + first_sample): a reference image of
  // many samples (blgpu_pack's GPU truth) starts past MSAA-n's samples so the two are independent.
  unsigned first_sample = 0;
};

// The complete fragment shader (with its #version line) for `program` in scene `s`.
std::string glsl_fragment_source(const scene::Scene& s, const compiler::Program& program,
                                 const std::string& version = "450", const FragmentOptions& options = {});
// Its parts: the #version line (with the precision lines of an "es" version), and the uniforms and
// main() that compute the program's inputs per fragment and call `function`, a function of the
// emit_glsl signature defined before them (e.g. bltune's front/<label>.glsl, named "shade").
std::string glsl_version_line(const std::string& version = "450");
std::string glsl_fragment_main(const compiler::Program& program, const std::string& function,
                               const FragmentOptions& options = {});
// Uniform values for frame f.
std::vector<gl::Uniform> glsl_frame_uniforms(const scene::Scene& s, const Frame& f);

// The scene's textures a program reads, uploaded (mean and mean-of-squares pyramids, every level),
// with the sampler uniforms bl_tex<slot>_mean / bl_tex<slot>_sq; released when destroyed.
class GlTextures {
 public:
  GlTextures(gl::Context& ctx, const scene::Scene& s, const compiler::Program& program);
  ~GlTextures();
  GlTextures(const GlTextures&) = delete;
  GlTextures& operator=(const GlTextures&) = delete;
  const std::vector<gl::Uniform>& uniforms() const { return uniforms_; }

 private:
  gl::Context& ctx_;
  std::vector<unsigned> ids_;
  std::vector<gl::Uniform> uniforms_;
};

// Frame uniforms followed by the texture samplers.
std::vector<gl::Uniform> with_textures(std::vector<gl::Uniform> frame, const GlTextures& t);

Image render_glsl(gl::Context& ctx, const scene::Scene& s, const Frame& f, const compiler::Program& program);
// The same with a fragment shader compiled by the caller (one built with glsl_fragment_main for
// `program`, e.g. around a front/<label>.glsl file; compiled once for every frame).
Image render_glsl_compiled(gl::Context& ctx, const scene::Scene& s, const Frame& f,
                           const compiler::Program& program, const gl::Program& fragment);

}  // namespace bl::render
