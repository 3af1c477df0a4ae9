#include "normalmap/techniques.hpp"

#include <algorithm>
#include <cmath>

#include "normalmap/lobe.hpp"
#include "texture/pyramid.hpp"
#include "texture/sample.hpp"

namespace bl::normalmap {

const char* technique_name(Technique t) {
  switch (t) {
    case Technique::Direct:
      return "direct";
    case Technique::Toksvig:
      return "toksvig";
    case Technique::Lean:
      return "lean";
    case Technique::Ours:
      return "ours";
    case Technique::OursMulti:
      return "ours_multi";
  }
  return "?";
}

Shader::Shader(const NmScene& scene, const NormalMapData& data) : scene_(scene), data_(data) {
  if (scene.material.model == Model::BlinnPhong)
    coef_ = cos_power_coefficients(scene.material.exponent);
  else
    ggx_ = &ggx_lobe_table(scene.material.alpha);
}

std::array<double, 3> Shader::shade_normal(V3 n, V3 view) const {
  const V3 l = scene_.light.dir, h = normalize(l + view);
  return radiance(scene_.material, scene_.light, n, specular(scene_.material, n, l, view, h));
}

std::array<double, 3> Shader::direct(double u, double v, V3 view) const {
  const texture::Pyramid& p = data_.normals;
  const V3 n = normalize({p.bilinear(0, float(u), float(v), 0), p.bilinear(0, float(u), float(v), 1),
                          p.bilinear(0, float(u), float(v), 2)});
  return shade_normal(n, view);
}

double Shader::spec_single(V3 nhat, double len, V3 h, V3 view) const {
  const Material& m = scene_.material;
  const AngleStats a = angle_stats(dot(nhat, h), len);
  if (m.model == Model::BlinnPhong) return m.ks * expected_cos_power(coef_, m.exponent, a.mu, a.sigma);
  return ggx_->expected(a.mu, a.sigma) * ggx_rest(m, nhat, scene_.light.dir, view, h);
}

std::array<double, 3> Shader::filtered(Technique t, const Sample& s, bool* multi) const {
  if (multi) *multi = false;
  if (t == Technique::Direct) return direct(s.u, s.v, s.view);
  const Material& m = scene_.material;
  const V3 l = scene_.light.dir, h = normalize(l + s.view);
  const float u = float(s.u), v = float(s.v);
  // The footprint's probes (anisotropic footprints: 4 along the long axis, as the colour lookups).
  const texture::Probes pr =
      texture::footprint_probes(u, v, float(s.sigma_u), float(s.sigma_v), data_.width(), data_.height());
  const texture::Pyramid& np = data_.normals;
  const V3 N{texture::read(np, pr, 0), texture::read(np, pr, 1), texture::read(np, pr, 2)};
  const double len = std::fmin(1.0, length(N));
  const V3 nhat = normalize(N);
  double spec = 0;
  switch (t) {
    case Technique::Toksvig: {
      const double s2 = toksvig_variance(len);
      if (m.model == Model::BlinnPhong) {
        spec = m.ks * toksvig_blinn_phong(dot(nhat, h), m.exponent, s2);
      } else {
        Material mt = m;
        mt.alpha = toksvig_ggx_alpha(m.alpha, s2);
        spec = ggx_d(dot(nhat, h), mt.alpha) * ggx_rest(mt, nhat, l, s.view, h);
      }
      break;
    }
    case Technique::Lean: {
      float mom[5];
      for (int c = 0; c < 5; ++c) mom[c] = texture::read(data_.lean, pr, c);
      const SlopeStats st = slope_stats(mom);
      if (m.model == Model::BlinnPhong)
        spec = m.ks * lean_blinn_phong(st, h.x, h.y, h.z, m.exponent);
      else
        spec = lean_ggx_d(st, h.x, h.y, h.z, m.alpha) * ggx_rest(m, nhat, l, s.view, h);
      break;
    }
    case Technique::Ours:
      spec = spec_single(nhat, len, h, s.view);
      break;
    case Technique::OursMulti: {
      // Single lobe up to the threshold, the cells above twice it, and a linear blend between, so
      // the switch leaves no edge in the image.
      const double sigma = angle_stats(dot(nhat, h), len).sigma, thr = scene_.lobe_threshold;
      const double t = thr > 0 ? std::clamp((sigma - thr) / thr, 0.0, 1.0) : (sigma > 0 ? 1.0 : 0.0);
      if (t < 1) spec = (1 - t) * spec_single(nhat, len, h, s.view);
      if (t <= 0) break;
      if (multi) *multi = true;
      const texture::Pyramid& lp = data_.lobes;
      double cells = 0;
      for (int c = 0; c < data_.grid.cells(); ++c) {
        const double w = texture::read(lp, pr, 4 * c);
        if (w < 1e-6) continue;
        const V3 Nc{texture::read(lp, pr, 4 * c + 1) / w, texture::read(lp, pr, 4 * c + 2) / w,
                    texture::read(lp, pr, 4 * c + 3) / w};
        cells += w * spec_single(normalize(Nc), std::fmin(1.0, length(Nc)), h, s.view);
      }
      spec += t * cells;
      break;
    }
    case Technique::Direct:
      break;
  }
  return radiance(m, scene_.light, N, spec);
}

}  // namespace bl::normalmap
