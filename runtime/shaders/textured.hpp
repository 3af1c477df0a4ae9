// Shaders that read textures (clamped-domain paper, Section 4.3): a colour texture with a
// procedural pattern on top, so the smoothed texture lookup feeds further nonlinear operations.
#pragma once

#include "shaders/effects.hpp"
#include "shaders/texture_lookup.hpp"

namespace bl::shaders {

// The "albedo" texture (repeating every uv unit) with dark grout lines every half unit on top.
template <class S>
Vec3<S> textured_tiles(const Inputs<S>& in, const Effects& fx) {
  using namespace dsl;
  const Surface<S> s = surface(in, fx);
  const Vec3<S> albedo = texture_rgb(in, "albedo", s.uv);
  S gu = fract(s.uv.x * S(2)), gv = fract(s.uv.y * S(2));
  S grout = max(less(gu, S(0.06)), less(gv, S(0.06)));
  return light(select(grout, splat3(S(0.06)), albedo), s, in, fx);
}

// The texture alone: what mipmapping by itself achieves (eqs. 21-22 with nothing downstream).
template <class S>
Vec3<S> textured_plain(const Inputs<S>& in, const Effects& fx) {
  const Surface<S> s = surface(in, fx);
  return light(texture_rgb(in, "albedo", s.uv), s, in, fx);
}

}  // namespace bl::shaders
