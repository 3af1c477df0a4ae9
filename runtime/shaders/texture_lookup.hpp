// Texture lookups in shaders. Natively (float) a lookup is direct sampling: level-0 bilinear, the
// function the ground truth integrates. Traced (Var) it records an ir::Op::Texture node per channel,
// whose rule decides the filtering (none: level 0; Monte Carlo: samples; any smoothing rule: the
// mean and mean-of-squares pyramids at the footprint's level).
#pragma once

#include <stdexcept>
#include <string>

#include "dsl/trace.hpp"
#include "shaders/shader.hpp"

namespace bl::shaders {

inline const texture::Texture& bound_texture(const texture::Bindings* textures, const char* slot) {
  if (const texture::Texture* t = textures ? texture::find(*textures, slot) : nullptr) return *t;
  throw std::invalid_argument(std::string("shader reads texture slot '") + slot +
                              "', which the scene does not bind");
}

inline Vec3<float> texture_rgb(const Inputs<float>& in, const char* slot, Vec2<float> uv) {
  const texture::Texture& t = bound_texture(in.textures, slot);
  return {t.plain(uv.x, uv.y, 0), t.plain(uv.x, uv.y, 1), t.plain(uv.x, uv.y, 2)};
}

inline Vec3<dsl::Var> texture_rgb(const Inputs<dsl::Var>&, const char* slot, Vec2<dsl::Var> uv) {
  ir::Graph& g = dsl::Tracer::graph();
  auto channel = [&](int c) { return dsl::Var::node(g.texture(slot, c, uv.x.id(), uv.y.id())); };
  return {channel(0), channel(1), channel(2)};
}

}  // namespace bl::shaders
