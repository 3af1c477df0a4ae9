// The two texture lookups a lowered shader makes, shared by the evaluator and the emitted C++
// (header-only, so an emitted shader needs no library): direct sampling, and the smoothed lookup of
// the clamped-domain paper's eqs. 21-22 at the footprint's level. GLSL twins: bl_tex_plain and
// bl_tex_stat in compiler/glsl_library.cpp, over the same uploaded levels.
#pragma once

#include <bandlimit/emit_helpers.hpp>

#include "texture/texture.hpp"

namespace bl::texture {

// Level-0 bilinear: what an unsmoothed shader reads.
inline float sample_plain(const Texture& t, float u, float v, int c) {
  return t.mean.bilinear(0, u, v, c);
}

// Mean and variance over a Gaussian footprint with sds (su, sv) in texture coordinates: the mean
// pyramid and the mean-of-squares pyramid read at the same trilinear level, var = E[p^2] - E[p]^2
// (rounding can make it slightly negative; it is clamped at 0 like every emitted variance).
inline bl::stat<float> sample_stat(const Texture& t, float u, float v, float su, float sv, int c) {
  const float lod = footprint_lod(su, sv, t.mean.width(), t.mean.height());
  const float m = t.mean.trilinear(u, v, lod, c);
  const float q = t.squares.trilinear(u, v, lod, c);
  const float var = q - m * m;
  return {m, var > 0.0f ? var : 0.0f};
}

}  // namespace bl::texture
