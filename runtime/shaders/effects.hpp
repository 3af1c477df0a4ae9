// Parallax mapping and lighting shared by the suite (Yang & Barnes: bumps, ripples, Phong).
#pragma once

#include "shaders/shader.hpp"

namespace bl::shaders {

// Surface after parallax: shifted coordinates and the shading normal (tangent frame).
template <class S>
struct Surface {
  Vec2<S> uv;
  Vec3<S> normal;
};

// Spherical bumps: a grid of sphere caps of radius R in unit cells; offset parallax mapping
// (uv += view.xy / view.z * height * scale) and the sphere's normal inside a cap.
template <class S>
Surface<S> bumps(const Inputs<S>& in) {
  using namespace dsl;
  const double R = 0.4, depth = 0.08, freq = 2.0;
  S fu = fract(in.u * S(freq)) - S(0.5);
  S fv = fract(in.v * S(freq)) - S(0.5);
  S r2 = pow2(fu) + pow2(fv);
  S inside = less(r2, S(R * R));
  S h = sqrt(saturate(S(R * R) - r2));  // cap height, 0 outside
  S k = h * S(depth / freq) * inv(in.view.z);
  Surface<S> s;
  s.uv = {in.u + in.view.x * k, in.v + in.view.y * k};
  Vec3<S> cap = {fu * S(1 / R), fv * S(1 / R), h * S(1 / R)};
  s.normal = select(inside, cap, Vec3<S>{S(0), S(0), S(1)});
  return s;
}

// Animated ripples: concentric waves around the origin; the normal from the height's gradient.
template <class S>
Surface<S> ripples(const Inputs<S>& in) {
  using namespace dsl;
  const double freq = 3.0, speed = 2.0, amp = 0.05;
  S r = sqrt(pow2(in.u) + pow2(in.v));
  S phase = r * S(freq) - in.time * S(speed);
  S h = S(amp) * (S(1) + sin(phase));
  S dh = S(amp * freq) * cos(phase) * inv(r);  // dh/dr / r: gradient = dh * (u, v)
  S k = h * inv(in.view.z);
  Surface<S> s;
  s.uv = {in.u + in.view.x * k, in.v + in.view.y * k};
  s.normal = normalize(Vec3<S>{-dh * in.u, -dh * in.v, S(1)});
  return s;
}

template <class S>
Surface<S> surface(const Inputs<S>& in, const Effects& fx) {
  switch (fx.parallax) {
    case Parallax::Bumps:
      return bumps(in);
    case Parallax::Ripples:
      return ripples(in);
    case Parallax::None:
      break;
  }
  return {{in.u, in.v}, {S(0), S(0), S(1)}};
}

// Phong: ambient + diffuse + white specular (exponent 8 through pow8).
template <class S>
Vec3<S> light(const Vec3<S>& albedo, const Surface<S>& s, const Inputs<S>& in, const Effects& fx) {
  using namespace dsl;
  if (fx.lighting == Lighting::None) return albedo;
  S ndl = dot(s.normal, in.light);
  S diffuse = max(ndl, S(0));
  Vec3<S> refl = s.normal * (S(2) * ndl) - in.light;  // reflect(-l, n)
  S spec = pow8(saturate(dot(refl, in.view)));
  return albedo * (S(0.25) + S(0.75) * diffuse) + splat3(S(0.4) * spec);
}

}  // namespace bl::shaders
