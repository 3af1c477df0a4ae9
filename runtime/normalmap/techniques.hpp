// Per-pixel shading of the normal-mapped plane by each technique (see lobe.hpp for the formulas):
//   direct      level-0 bilinear normal, renormalized, shaded once (what an unfiltered shader does);
//   toksvig     averaged normal at the footprint's level, Toksvig's widened lobe;
//   lean        LEAN's slope moments at the footprint's level;
//   ours        eqs. 24-25: one Gaussian lobe over the angle to h, E[spec];
//   ours_multi  ours with the multi-lobe cells where the single lobe's sigma_theta exceeds the
//               scene's threshold (each cell: its share times its own lobe's E[spec]), blended
//               linearly from the single lobe at the threshold to the cells alone at twice it.
// Filtered techniques read their pyramids at texture::footprint_probes(sigma_u, sigma_v) (one
// trilinear probe, or 4 along the long axis of an anisotropic footprint), and shade the diffuse term
// with the averaged normal (brdf.hpp).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "normalmap/brdf.hpp"
#include "normalmap/lobe.hpp"
#include "normalmap/nm_scene.hpp"
#include "normalmap/normal_data.hpp"

namespace bl::normalmap {

enum class Technique { Direct, Toksvig, Lean, Ours, OursMulti };
const char* technique_name(Technique t);

struct Sample {
  double u = 0, v = 0;              // texture coordinates (the map repeats every unit)
  double sigma_u = 0, sigma_v = 0;  // footprint sds in the same units
  V3 view{0, 0, 1};                 // unit, hit -> eye, tangent space
};

class Shader {
 public:
  Shader(const NmScene& scene, const NormalMapData& data);
  // Direct shading with the unit normal n.
  std::array<double, 3> shade_normal(V3 n, V3 view) const;
  // Direct: the level-0 bilinear normal at (u, v), renormalized.
  std::array<double, 3> direct(double u, double v, V3 view) const;
  // Any technique at a footprint. `multi`, when given, is set to whether the multi-lobe path ran.
  std::array<double, 3> filtered(Technique t, const Sample& s, bool* multi = nullptr) const;

  const NmScene& scene() const { return scene_; }

 private:
  double spec_single(V3 nhat, double len, V3 h, V3 view) const;

  const NmScene& scene_;
  const NormalMapData& data_;
  std::vector<double> coef_;           // cos^s expansion (Blinn-Phong)
  const GgxLobeTable* ggx_ = nullptr;  // E[D] over theta (GGX)
};

}  // namespace bl::normalmap
