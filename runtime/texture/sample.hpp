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
  return t.plain(u, v, c);
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

// Where to read a footprint: one probe (near-isotropic) or 4 along the long axis, all at one level.
// Any pyramid of linear moments (means, mean squares, averaged normals, LEAN moments) is filtered
// by the weighted sum of its trilinear reads at these probes.
struct Probes {
  int count = 1;
  float lod = 0;
  float u[4] = {}, v[4] = {}, w[4] = {1, 0, 0, 0};
};

inline Probes footprint_probes(float u, float v, float su, float sv, int width, int height) {
  Probes p;
  const float tu = su * float(width), tv = sv * float(height);  // sds in level-0 texels
  const float s_long = tu > tv ? tu : tv, s_short = tu > tv ? tv : tu;
  if (!(s_long > 2.0f * s_short)) {  // near-isotropic (and NaN): one probe at the larger sd
    p.lod = lod_for_sd(s_long);
    p.u[0] = u;
    p.v[0] = v;
    return p;
  }
  const float s_level = s_short > s_long / kMaxAnisotropy ? s_short : s_long / kMaxAnisotropy;
  p.lod = lod_for_sd(s_level);
  const float rest = std::sqrt(s_long * s_long - s_level * s_level);
  // Probe offsets in texture coordinates along the long axis.
  const float du = tu > tv ? rest / float(width) : 0.0f, dv = tu > tv ? 0.0f : rest / float(height);
  const float node[2] = {0.741960677f, 2.33441422f}, weight[2] = {0.454124578f, 0.0458758548f};
  p.count = 4;
  int n = 0;
  for (int k = 0; k < 2; ++k)
    for (float sign : {-1.0f, 1.0f}) {
      p.u[n] = u + sign * node[k] * du;
      p.v[n] = v + sign * node[k] * dv;
      p.w[n] = weight[k];
      ++n;
    }
  return p;
}

// The footprint-filtered value of channel c of a pyramid of linear moments.
inline float read(const Pyramid& pyr, const Probes& p, int c) {
  if (p.count == 1) return pyr.trilinear(p.u[0], p.v[0], p.lod, c);
  float sum = 0;
  for (int k = 0; k < p.count; ++k) sum += p.w[k] * pyr.trilinear(p.u[k], p.v[k], p.lod, c);
  return sum;
}

inline bl::stat<float> sample_stat(const Texture& t, float u, float v, float su, float sv, int c) {
  const Probes p = footprint_probes(u, v, su, sv, t.mean.width(), t.mean.height());
  const float m = read(t.mean, p, c), q = read(t.squares, p, c);
  const float var = q - m * m;
  return {m, var > 0.0f ? var : 0.0f};
}

}  // namespace bl::texture
