#include <stdexcept>

#include "shaders/effects.hpp"
#include "shaders/patterns.hpp"
#include "shaders/textured.hpp"

namespace bl::shaders {
namespace {

template <class S, class Pattern>
Vec3<S> run(Pattern pattern, const Inputs<S>& in, const Effects& fx) {
  const Surface<S> s = surface(in, fx);
  return light(pattern(s.uv, in.time), s, in, fx);
}

#define BL_SHADER(NAME, USES_TIME, DESC)                                                            \
  ShaderDef {                                                                                       \
#NAME, DESC, USES_TIME, {},                                                                       \
        [](const Inputs<float>& in, const Effects& fx) {                                              \
          return run<float>([](Vec2<float> uv, float t) { return patterns::NAME<float>(uv, t); }, in, fx); \
        },                                                                                            \
        [](const Inputs<dsl::Var>& in, const Effects& fx) {                                           \
          return run<dsl::Var>([](Vec2<dsl::Var> uv, dsl::Var t) { return patterns::NAME<dsl::Var>(uv, t); }, \
                               in, fx);                                                               \
        } \
  }

}  // namespace

const std::vector<ShaderDef>& suite() {
  static const std::vector<ShaderDef> s = {
      BL_SHADER(checkerboard, false, "Greyscale checkerboard from floor (Dorn et al. Listing 1)"),
      BL_SHADER(circles, false, "Tiled greyscale circles (Dorn et al. Listing 3)"),
      BL_SHADER(color_circles, false, "Aperiodic coloured circles (three incommensurate layers)"),
      BL_SHADER(bricks, false, "Bricks with mortar and per-brick noise"),
      BL_SHADER(zigzag, false, "Colourful zigzag (triangle-displaced square-wave stripes)"),
      BL_SHADER(quadratic_sine, true, "Animated sine of a quadratic (non-stationary)"),
      BL_SHADER(fire, true, "Animated faux fire (warped |sin| turbulence, colour ramp)"),
      BL_SHADER(checkerboard_step, false, "Checkerboard from fract and step (Dorn et al. Listing 2)"),
      BL_SHADER(step_edge, false, "Black and white half-planes (Dorn et al. 'step')"),
      BL_SHADER(ridges, false, "fract(u) ramps (Dorn et al. 'ridges')"),
      BL_SHADER(pulse, false, "Black and white stripes (Dorn et al. 'pulse')"),
      BL_SHADER(value_noise, false, "Two-octave value noise (hashed lattice corners, smoothstep blend)"),
      BL_SHADER(truchet, false, "Truchet quarter-arc tiles (hashed orientation per cell)"),
      ShaderDef{
          "textured_tiles",
          "Colour texture (mean/variance pyramids) under procedural grout lines",
          false,
          {TextureSlot{"albedo", 3, texture::Encoding::Srgb}},
          [](const Inputs<float>& in, const Effects& fx) { return textured_tiles<float>(in, fx); },
          [](const Inputs<dsl::Var>& in, const Effects& fx) { return textured_tiles<dsl::Var>(in, fx); }},
      ShaderDef{
          "textured_plain",
          "The colour texture alone (what the pyramids achieve by themselves)",
          false,
          {TextureSlot{"albedo", 3, texture::Encoding::Srgb}},
          [](const Inputs<float>& in, const Effects& fx) { return textured_plain<float>(in, fx); },
          [](const Inputs<dsl::Var>& in, const Effects& fx) { return textured_plain<dsl::Var>(in, fx); }},
  };
  return s;
}

std::vector<std::string> base_shader_names() {
  return {"checkerboard", "circles", "color_circles", "bricks", "zigzag", "quadratic_sine", "fire"};
}

const ShaderDef& find_shader(const std::string& name) {
  for (const auto& s : suite())
    if (s.name == name) return s;
  std::string known;
  for (const auto& s : suite()) known += (known.empty() ? "" : ", ") + s.name;
  throw std::invalid_argument("unknown shader '" + name + "' (known: " + known + ")");
}

ir::Graph trace(const ShaderDef& s, const Effects& fx) {
  ir::Graph g;
  dsl::Tracer tracer(g);
  using dsl::Var;
  const bool view = fx.parallax != Parallax::None || fx.lighting != Lighting::None;
  for (const auto& t : s.textures) g.texture_slot(t.name);  // slots in the ShaderDef's order
  Inputs<Var> in{Var::input("u", true),
                 Var::input("v", true),
                 Var(0.0),
                 {Var(0.0), Var(0.0), Var(1.0)},
                 {Var(0.0), Var(0.0), Var(1.0)}};
  if (fx.animated && (s.uses_time || fx.parallax == Parallax::Ripples)) in.time = Var::input("time", false);
  if (view) in.view = {Var::input("view_x", false), Var::input("view_y", false), Var::input("view_z", false)};
  if (fx.lighting != Lighting::None)
    in.light = {Var::input("light_x", false), Var::input("light_y", false), Var::input("light_z", false)};
  const Vec3<Var> c = s.traced(in, fx);
  g.add_output("r", c.x.id());
  g.add_output("g", c.y.id());
  g.add_output("b", c.z.id());
  return g;
}

Vec3<float> shade(const ShaderDef& s, const Effects& fx, const Inputs<float>& in) {
  Inputs<float> x = in;
  if (!fx.animated) x.time = 0;
  return s.native(x, fx);
}

}  // namespace bl::shaders
