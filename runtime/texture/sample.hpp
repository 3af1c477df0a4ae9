// The two texture lookups a lowered shader makes, shared by the evaluator and the emitted C++
// (header-only, so an emitted shader needs no library): direct sampling, and the smoothed lookup of
// the clamped-domain paper's eqs. 21-22 at the footprint's level. GLSL twins: bl_tex_plain and
// bl_tex_stat in compiler/glsl_library.cpp, over the same uploaded levels.
#pragma once

#include <bandlimit/emit_helpers.hpp>
#include <cmath>

#include "texture/texture.hpp"

namespace bl::texture {

// Level-0 bilinear: what an unsmoothed shader reads.
inline float sample_plain(const Texture& t, float u, float v, int c) {
  return t.mean.bilinear(0, u, v, c);
}

// Mean and variance over a Gaussian footprint with sds (su, sv) in texture coordinates: the mean
// pyramid and the mean-of-squares pyramid read at the same trilinear level, var = E[p^2] - E[p]^2
// (rounding can make it slightly negative; it is clamped at 0 like every emitted variance).
//
// Anisotropic footprints (a plane seen at a grazing angle: one sd many times the other) are not read
// at the level of the larger sd, which would blur the short axis too: the level follows the smaller
// sd (at most kMaxAnisotropy times finer than the larger), and 4 probes along the long axis at the
// Gauss-Hermite nodes of the remaining variance, sd_rest^2 = s_long^2 - s_level^2, supply the rest,
// so the total variance along the long axis is the footprint's (what GL's anisotropic filtering
// approximates with its own probe rule).
inline constexpr float kMaxAnisotropy = 16.0f;

inline bl::stat<float> sample_stat(const Texture& t, float u, float v, float su, float sv, int c) {
  const int w = t.mean.width(), h = t.mean.height();
  const float tu = su * float(w), tv = sv * float(h);  // sds in level-0 texels
  const float s_long = tu > tv ? tu : tv, s_short = tu > tv ? tv : tu;
  float m = 0, q = 0;
  if (!(s_long > 2.0f * s_short)) {  // near-isotropic (and NaN): one probe at the larger sd
    const float lod = lod_for_sd(s_long);
    m = t.mean.trilinear(u, v, lod, c);
    q = t.squares.trilinear(u, v, lod, c);
  } else {
    const float s_level = s_short > s_long / kMaxAnisotropy ? s_short : s_long / kMaxAnisotropy;
    const float lod = lod_for_sd(s_level);
    const float rest = std::sqrt(s_long * s_long - s_level * s_level);
    // Probe offsets in texture coordinates along the long axis.
    const float du = tu > tv ? rest / float(w) : 0.0f, dv = tu > tv ? 0.0f : rest / float(h);
    const float node[2] = {0.741960677f, 2.33441422f}, weight[2] = {0.454124578f, 0.0458758548f};
    for (int k = 0; k < 2; ++k)
      for (float sign : {-1.0f, 1.0f}) {
        const float pu = u + sign * node[k] * du, pv = v + sign * node[k] * dv;
        m += weight[k] * t.mean.trilinear(pu, pv, lod, c);
        q += weight[k] * t.squares.trilinear(pu, pv, lod, c);
      }
  }
  const float var = q - m * m;
  return {m, var > 0.0f ? var : 0.0f};
}

}  // namespace bl::texture
