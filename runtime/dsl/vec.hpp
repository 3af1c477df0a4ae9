// Small vector types for shaders; they lower to scalar operations (the traced DAG is scalar).
#pragma once

#include "dsl/math.hpp"

namespace bl::dsl {

template <class S>
struct Vec2 {
  S x, y;
};
template <class S>
struct Vec3 {
  S x, y, z;
};

template <class S>
Vec2<S> operator+(Vec2<S> a, Vec2<S> b) {
  return {a.x + b.x, a.y + b.y};
}
template <class S>
Vec2<S> operator-(Vec2<S> a, Vec2<S> b) {
  return {a.x - b.x, a.y - b.y};
}
template <class S>
Vec2<S> operator*(Vec2<S> a, S k) {
  return {a.x * k, a.y * k};
}
template <class S>
Vec2<S> operator*(S k, Vec2<S> a) {
  return {a.x * k, a.y * k};
}
template <class S>
S dot(Vec2<S> a, Vec2<S> b) {
  return a.x * b.x + a.y * b.y;
}

template <class S>
Vec3<S> operator+(Vec3<S> a, Vec3<S> b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class S>
Vec3<S> operator-(Vec3<S> a, Vec3<S> b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class S>
Vec3<S> operator*(Vec3<S> a, Vec3<S> b) {
  return {a.x * b.x, a.y * b.y, a.z * b.z};
}
template <class S>
Vec3<S> operator*(Vec3<S> a, S k) {
  return {a.x * k, a.y * k, a.z * k};
}
template <class S>
Vec3<S> operator*(S k, Vec3<S> a) {
  return {a.x * k, a.y * k, a.z * k};
}
template <class S>
S dot(Vec3<S> a, Vec3<S> b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class S>
Vec3<S> mix(Vec3<S> a, Vec3<S> b, S t) {
  return a + (b - a) * t;
}
template <class S>
Vec3<S> splat3(S v) {
  return {v, v, v};
}
template <class S>
Vec3<S> select(S c, Vec3<S> a, Vec3<S> b) {
  return {select(c, a.x, b.x), select(c, a.y, b.y), select(c, a.z, b.z)};
}
// Component-wise floor and fract, lengths, and mix with a scalar or per-component weight.
template <class S>
Vec2<S> floor(Vec2<S> v) {
  return {floor(v.x), floor(v.y)};
}
template <class S>
Vec3<S> floor(Vec3<S> v) {
  return {floor(v.x), floor(v.y), floor(v.z)};
}
template <class S>
Vec2<S> fract(Vec2<S> v) {
  return {fract(v.x), fract(v.y)};
}
template <class S>
Vec3<S> fract(Vec3<S> v) {
  return {fract(v.x), fract(v.y), fract(v.z)};
}
template <class S>
S length(Vec2<S> v) {
  return sqrt(pow2(v.x) + pow2(v.y));
}
template <class S>
S length(Vec3<S> v) {
  return sqrt(pow2(v.x) + pow2(v.y) + pow2(v.z));
}
template <class S>
Vec2<S> mix(Vec2<S> a, Vec2<S> b, S t) {
  return a + (b - a) * t;
}
template <class S>
Vec3<S> mix(Vec3<S> a, Vec3<S> b, Vec3<S> t) {
  return a + (b - a) * t;
}

// Unit vector: v / |v| through the catalog's sqrt and inv (both smoothable atomics).
template <class S>
Vec3<S> normalize(Vec3<S> v) {
  return v * inv(sqrt(dot(v, v)));
}

}  // namespace bl::dsl
