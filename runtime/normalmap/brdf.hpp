// The shading model of the normal-map scenes: a plane lit by one directional light, with a
// tangent-space normal n from the normal map (T = +u, B = +v, N = +z; see runtime/camera/plane_hit.hpp).
//
//   L(n) = albedo (ambient + E max(0, n.l)) + E spec(n)
//
// Blinn-Phong:  spec(n) = ks max(0, n.h)^s                       (unnormalized lobe, h = |l + v|^-1 (l + v))
// GGX:          spec(n) = F(v.h) D(n.h) G1(n.l) G1(n.v) / (4 n.v)  (Cook-Torrance: GGX D, separable Smith
//                                                                  G1, Schlick F; 0 where n.l or n.v <= 0)
// The diffuse term is linear in n up to its clamp, so every filtered technique computes it from the
// averaged (unnormalized) normal, which gives its footprint mean exactly where no texel faces away
// from the light; the techniques differ in the specular term.
#pragma once

#include <array>
#include <cmath>

namespace bl::normalmap {

struct V3 {
  double x = 0, y = 0, z = 0;
};
inline V3 operator+(V3 a, V3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline V3 operator*(double s, V3 a) {
  return {s * a.x, s * a.y, s * a.z};
}
inline double dot(V3 a, V3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline double length(V3 a) {
  return std::sqrt(dot(a, a));
}
inline V3 normalize(V3 a) {
  const double l = length(a);
  return l > 0 ? (1.0 / l) * a : V3{0, 0, 1};
}

enum class Model { BlinnPhong, GGX };

struct Material {
  Model model = Model::BlinnPhong;
  std::array<double, 3> albedo{0.5, 0.5, 0.5};
  double ambient = 0.05;
  double ks = 1.0;     // Blinn-Phong specular weight
  int exponent = 64;   // Blinn-Phong s (an integer: the single-lobe closed form expands cos^s)
  double alpha = 0.2;  // GGX roughness (alpha = perceptual roughness squared is the caller's business)
  double f0 = 0.04;    // GGX Schlick reflectance at normal incidence
};

struct Light {
  V3 dir{0.3, 0.2, 0.93};                // towards the light, unit
  std::array<double, 3> color{1, 1, 1};  // irradiance E
};

// GGX normal distribution of c = n.h (0 for c <= 0).
inline double ggx_d(double c, double alpha) {
  if (c <= 0) return 0;
  const double a2 = alpha * alpha, t = c * c * (a2 - 1) + 1;
  return a2 / (M_PI * t * t);
}
// Separable Smith G1 for GGX, of c = n.l or n.v (0 for c <= 0).
inline double ggx_g1(double c, double alpha) {
  if (c <= 0) return 0;
  const double a2 = alpha * alpha;
  return 2 * c / (c + std::sqrt(a2 + (1 - a2) * c * c));
}
inline double schlick(double f0, double v_dot_h) {
  const double m = 1 - std::fmax(0.0, v_dot_h);
  return f0 + (1 - f0) * m * m * m * m * m;
}
// Everything of the GGX specular term but D, for the normal n: F G1(l) G1(v) / (4 n.v).
inline double ggx_rest(const Material& m, V3 n, V3 l, V3 v, V3 h) {
  const double nl = dot(n, l), nv = dot(n, v);
  if (nl <= 0 || nv <= 0) return 0;
  return schlick(m.f0, dot(v, h)) * ggx_g1(nl, m.alpha) * ggx_g1(nv, m.alpha) / (4 * nv);
}

// The specular term for a unit normal n (direct shading).
inline double specular(const Material& m, V3 n, V3 l, V3 v, V3 h) {
  const double c = dot(n, h);
  if (m.model == Model::BlinnPhong) return c > 0 ? m.ks * std::pow(c, m.exponent) : 0.0;
  return ggx_d(c, m.alpha) * ggx_rest(m, n, l, v, h);
}

// Radiance for a diffuse normal nd (unit for direct shading, the averaged normal for filtered
// techniques) and a specular value.
inline std::array<double, 3> radiance(const Material& m, const Light& L, V3 nd, double spec) {
  const double nl = std::fmax(0.0, dot(nd, L.dir));
  std::array<double, 3> out{};
  for (int c = 0; c < 3; ++c) out[c] = m.albedo[c] * (m.ambient + L.color[c] * nl) + L.color[c] * spec;
  return out;
}

}  // namespace bl::normalmap
