#include "render/glsl_frame.hpp"

#include <sstream>
#include <stdexcept>

#include "camera/camera.hpp"
#include "compiler/emit.hpp"
#include "render/frame.hpp"

namespace bl::render {

std::string glsl_fragment_source(const scene::Scene& s, const compiler::Program& p,
                                 const std::string& version, const FragmentOptions& options) {
  return glsl_version_line(version) + compiler::emit_glsl(p, "bl_shade", "scene " + s.name) + "\n" +
         glsl_fragment_main(p, "bl_shade", options);
}

std::string glsl_version_line(const std::string& version) {
  std::string v = "#version " + version + "\n";
  if (version.find("es") != std::string::npos) v += "precision highp float;\nprecision highp int;\n";
  return v;
}

namespace {

// The camera of runtime/camera/plane_hit.cpp, per fragment (gl_FragCoord: y down, see egl_runner).
const char* const kCameraPrelude = R"(uniform vec3 bl_cam_pos;
uniform vec3 bl_cam_right;
uniform vec3 bl_cam_up;
uniform vec3 bl_cam_forward;
uniform float bl_focal;
uniform vec2 bl_size;
uniform float bl_uv_scale;
uniform float bl_pixel_sigma;
uniform int bl_marginal;
uniform vec3 bl_light;
uniform float bl_time;
uniform vec3 bl_background;
out vec4 bl_color;

vec3 bl_plane_differential(float t, vec3 d, vec3 dd) { return t * (dd - d * (dd.z / d.z)); }
vec3 bl_ray(vec2 p) {
  return bl_focal * bl_cam_forward + (p.x - 0.5 * bl_size.x) * bl_cam_right - (p.y - 0.5 * bl_size.y) * bl_cam_up;
}
)";

// The pixel the fragment shades: gl_FragCoord, or (tiled) its position within the scene's image.
std::string pixel_line(const FragmentOptions& o) {
  return o.tiled ? "  vec2 p = mod(gl_FragCoord.xy, bl_size);\n" : "  vec2 p = gl_FragCoord.xy;\n";
}

// Declares m, s, gx, gy and fills them from hit, su, sv, du, dv, view (in scope), by input name.
std::string input_lines(const compiler::Program& p, const std::string& indent) {
  std::ostringstream os;
  const int n = std::max(1, p.input_count);
  os << indent << "float m[" << n << "]; float s[" << n << "]; float gx[" << n << "]; float gy[" << n
     << "];\n";
  if (p.input_count == 0) os << indent << "m[0] = 0.0; s[0] = 0.0; gx[0] = 0.0; gy[0] = 0.0;\n";
  for (int i = 0; i < p.input_count; ++i) {
    const std::string& name = p.input_names[i];
    std::string mean = "0.0", sd = "0.0", gxs = "0.0", gys = "0.0";
    if (name == "u")
      mean = "k * hit.x", sd = "su", gxs = "du.x", gys = "du.y";
    else if (name == "v")
      mean = "k * hit.y", sd = "sv", gxs = "dv.x", gys = "dv.y";
    else if (name == "view_x")
      mean = "view.x";
    else if (name == "view_y")
      mean = "view.y";
    else if (name == "view_z")
      mean = "view.z";
    else if (name == "time")
      mean = "bl_time";
    else if (name == "light_x")
      mean = "bl_light.x";
    else if (name == "light_y")
      mean = "bl_light.y";
    else if (name == "light_z")
      mean = "bl_light.z";
    else
      throw std::invalid_argument("glsl frame: the program reads an unknown input '" + name + "'");
    os << indent << "m[" << i << "] = " << mean << "; s[" << i << "] = " << sd << "; gx[" << i
       << "] = " << gxs << "; gy[" << i << "] = " << gys << ";\n";
  }
  os << indent << "float o[" << p.outputs.size() << "];\n";
  return os.str();
}

// One evaluation at the pixel centre with the pixel's footprint (the smoothed renderer).
std::string footprint_main(const compiler::Program& p, const std::string& function,
                           const FragmentOptions& o) {
  std::ostringstream os;
  os << R"(// Phi(z) through the erfc fit of generated/bandlimit.glsl (relative error < 1.2e-7).
float bl_cover_Phi(float z) {
  float x = -z * 0.70710678, a = min(abs(x), 10.0), t = 1.0 / (1.0 + 0.5 * a);
  float r = t * exp(-a * a - 1.26551223 + t * (1.00002368 + t * (0.37409196 + t * (0.09678418 +
            t * (-0.18628806 + t * (0.27886807 + t * (-1.13520398 + t * (1.48851587 +
            t * (-0.82215223 + t * 0.17087277)))))))));
  return 0.5 * (x >= 0.0 ? r : 2.0 - r);
}

void main() {
)" << pixel_line(o)
     << R"(  vec3 d = bl_ray(p);
  // The horizon by the pixel filter's coverage (runtime/camera/horizon_coverage.hpp): d.z is affine
  // in p; shade the covered part's mean, weight the shade by the covered fraction.
  float cover = d.z < 0.0 ? 1.0 : 0.0;
  vec2 g = vec2(bl_cam_right.z, -bl_cam_up.z);
  float glen = length(g);
  if (glen > 0.0 && bl_pixel_sigma > 0.0) {
    float z = -d.z / (glen * bl_pixel_sigma);
    cover = bl_cover_Phi(z);
    if (cover < 1e-3) cover = 0.0;  // kMinCoverage
    if (cover > 1.0 - 1e-3) cover = 1.0;
    if (cover > 0.0 && cover < 1.0) {
      float mills = 0.39894228 * exp(-0.5 * z * z) / cover;  // E[offset along n] / s
      p -= (bl_pixel_sigma * mills / glen) * g;
      d = bl_ray(p);
      // d.z there is -|g| s (z + mills) exactly; recomputed from p it would cancel (~1e-5 absolute in
      // float near the horizon, where t = -E.z / d.z magnifies it).
      d.z = -glen * bl_pixel_sigma * (z + mills);
    }
  }
  if (!(d.z < 0.0) || cover == 0.0) { bl_color = vec4(bl_background, 1.0); return; }
  float t = -bl_cam_pos.z / d.z;
  vec3 hit = bl_cam_pos + t * d;
  vec3 dpx = bl_plane_differential(t, d, bl_cam_right);
  vec3 dpy = bl_plane_differential(t, d, -bl_cam_up);
  float k = bl_uv_scale;
  vec2 du = k * vec2(dpx.x, dpy.x);
  vec2 dv = k * vec2(dpx.y, dpy.y);
  float su = bl_marginal != 0 ? bl_pixel_sigma * length(du) : bl_pixel_sigma * (abs(du.x) + abs(du.y));
  float sv = bl_marginal != 0 ? bl_pixel_sigma * length(dv) : bl_pixel_sigma * (abs(dv.x) + abs(dv.y));
  vec3 view = -d / length(d);
)" << input_lines(p, "  ")
     << "  " << function << "(m, s, gx, gy, o);\n"
     << "  bl_color = vec4(mix(bl_background, vec3(o[0], o[1], o[2]), cover), 1.0);\n}\n";
  return os.str();
}

// Supersampling as a renderer would run it: o.samples evaluations per fragment at Gaussian-jittered
// positions (sd bl_pixel_sigma, as runtime/render), each with a zero footprint, averaged; a sample
// whose ray misses the plane takes the background. The offsets come from a 32-bit counter hash of
// (pixel, sample) (PCG's output function), not from render/jitter.hpp's 64-bit one: desktop GLSL 4.5
// has no 64-bit integers without an extension. Same kernel, different draws.
std::string supersample_main(const compiler::Program& p, const std::string& function,
                             const FragmentOptions& o) {
  std::ostringstream os;
  os << R"(uint bl_hash(uint x) {
  uint s = x * 747796405u + 2891336453u;
  uint w = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
  return (w >> 22u) ^ w;
}

void main() {
)" << pixel_line(o)
     << "  const int bl_samples = " << o.samples << ";\n"
     << R"(  uint pixel = uint(p.y) * uint(bl_size.x) + uint(p.x);
  vec3 acc = vec3(0.0);
  for (int j = 0; j < bl_samples; ++j) {
)"
     << "    uint h1 = bl_hash(pixel + bl_hash(uint(j)"
     << (o.first_sample != 0 ? " + " + std::to_string(o.first_sample) + "u" : std::string())
     << R"()), h2 = bl_hash(h1 ^ 0x5851F42Du);
    float u1 = (float(h1 >> 8u) + 1.0) * (1.0 / 16777216.0), u2 = float(h2 >> 8u) * (1.0 / 16777216.0);
    float r = bl_pixel_sigma * sqrt(-2.0 * log(u1)), a = 6.2831853 * u2;
    vec3 d = bl_ray(p + r * vec2(cos(a), sin(a)));
    if (!(d.z < 0.0)) { acc += bl_background; continue; }
    vec3 hit = bl_cam_pos + (-bl_cam_pos.z / d.z) * d;
    float k = bl_uv_scale, su = 0.0, sv = 0.0;
    vec2 du = vec2(0.0), dv = vec2(0.0);
    vec3 view = -d / length(d);
)" << input_lines(p, "    ")
     << "    " << function << "(m, s, gx, gy, o);\n"
     << "    acc += vec3(o[0], o[1], o[2]);\n  }\n"
     << "  bl_color = vec4(acc / float(bl_samples), 1.0);\n}\n";
  return os.str();
}

}  // namespace

std::string glsl_fragment_main(const compiler::Program& p, const std::string& function,
                               const FragmentOptions& options) {
  if (options.samples < 0)
    throw std::invalid_argument("glsl frame: samples must be >= 0, got " + std::to_string(options.samples));
  return kCameraPrelude + (options.samples > 0 ? supersample_main(p, function, options)
                                               : footprint_main(p, function, options));
}

std::vector<gl::Uniform> glsl_frame_uniforms(const scene::Scene& s, const Frame& f) {
  const camera::Camera cam = make_camera(s, f.view);
  const camera::Basis b = camera::basis(cam);
  auto v3 = [](const camera::Vec3d& v) {
    return gl::Vec3{static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)};
  };
  auto a3 = [](const std::array<double, 3>& v) {
    return gl::Vec3{static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
  };
  return {{"bl_cam_pos", v3(cam.position)},
          {"bl_cam_right", v3(b.right)},
          {"bl_cam_up", v3(b.up)},
          {"bl_cam_forward", v3(b.forward)},
          {"bl_focal", static_cast<float>(camera::focal_px(cam))},
          {"bl_size", gl::Vec2{static_cast<float>(s.width), static_cast<float>(s.height)}},
          {"bl_uv_scale", static_cast<float>(s.uv_scale)},
          {"bl_pixel_sigma", static_cast<float>(s.sigma_px)},
          {"bl_marginal", s.footprint_bound == scene::FootprintBound::Marginal ? 1 : 0},
          {"bl_light", a3(s.light_dir)},
          {"bl_time", static_cast<float>(f.time)},
          {"bl_background", a3(s.background)}};
}

namespace {

gl::TextureLevels levels_of(const texture::Pyramid& p) {
  gl::TextureLevels t;
  t.width = p.width();
  t.height = p.height();
  t.channels = p.channels();
  for (int k = 0; k < p.levels(); ++k) t.levels.push_back(p.level(k).texels);
  return t;
}

}  // namespace

GlTextures::GlTextures(gl::Context& ctx, const scene::Scene& s, const compiler::Program& program)
    : ctx_(ctx) {
  const auto bound = s.texture_slots(program.texture_names);
  for (std::size_t k = 0; k < bound.size(); ++k) {
    const std::string name = "bl_tex" + std::to_string(k);
    ids_.push_back(ctx.upload(levels_of(bound[k]->mean)));
    uniforms_.push_back({name + "_mean", gl::Sampler{ids_.back()}});
    ids_.push_back(ctx.upload(levels_of(bound[k]->squares)));
    uniforms_.push_back({name + "_sq", gl::Sampler{ids_.back()}});
  }
}

GlTextures::~GlTextures() {
  for (unsigned id : ids_) ctx_.release(id);
}

std::vector<gl::Uniform> with_textures(std::vector<gl::Uniform> frame, const GlTextures& t) {
  frame.insert(frame.end(), t.uniforms().begin(), t.uniforms().end());
  return frame;
}

Image render_glsl(gl::Context& ctx, const scene::Scene& s, const Frame& f, const compiler::Program& program) {
  return render_glsl_compiled(ctx, s, f, program, ctx.compile(glsl_fragment_source(s, program)));
}

Image render_glsl_compiled(gl::Context& ctx, const scene::Scene& s, const Frame& f,
                           const compiler::Program& program, const gl::Program& prog) {
  const GlTextures textures(ctx, s, program);
  // The driver drops uniforms a scene does not read (no lighting: bl_light): ignore those, the
  // names themselves are fixed above.
  ctx.set_unknown_uniform(gl::UnknownUniform::kIgnore);
  const auto rgba = ctx.render(prog, s.width, s.height, with_textures(glsl_frame_uniforms(s, f), textures));
  ctx.set_unknown_uniform(gl::UnknownUniform::kThrow);
  return image_from_rgba(rgba, s.width, s.height);
}

}  // namespace bl::render
