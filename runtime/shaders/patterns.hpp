// The base patterns (our implementations of the shaders the papers describe). Each maps surface
// coordinates (after parallax) and time to a linear RGB albedo.
#pragma once

#include "shaders/shader.hpp"

namespace bl::shaders::patterns {

using namespace bl::dsl;

// Dorn et al. Listing 1: checkerboard from floor.
template <class S>
Vec3<S> checkerboard(Vec2<S> uv, S) {
  S ss = floor(uv.x + S(0.5)) - floor(uv.x);
  S tt = floor(uv.y + S(0.5)) - floor(uv.y);
  S c = ss * tt + (S(1) - ss) * (S(1) - tt);
  return splat3(S(0.1) + S(0.8) * c);
}

// Dorn et al. Listing 2: the same checkerboard from fract and step.
template <class S>
Vec3<S> checkerboard_step(Vec2<S> uv, S) {
  S ss = step(S(0.5) - fract(uv.x));
  S tt = step(S(0.5) - fract(uv.y));
  S c = ss * tt + (S(1) - ss) * (S(1) - tt);
  return splat3(S(0.1) + S(0.8) * c);
}

// Dorn et al. Listing 3: tiled greyscale circles.
template <class S>
Vec3<S> circles(Vec2<S> uv, S) {
  S ss = fract(uv.x * S(2)) - S(0.5);
  S tt = fract(uv.y * S(2)) - S(0.5);
  S c = step(S(0.16) - (pow2(ss) + pow2(tt)));
  return splat3(S(0.1) + S(0.8) * c);
}

// Aperiodic coloured circles: three layers of circles with incommensurate periods; a later layer
// covers an earlier one (select), so the pattern never repeats.
template <class S>
Vec3<S> color_circles(Vec2<S> uv, S) {
  const double scale[3] = {1.0, 1.618034, 2.414214};
  const double offset[3] = {0.0, 0.31, 0.77};
  const double radius2[3] = {0.12, 0.09, 0.06};
  const Vec3<S> colour[3] = {{S(0.9), S(0.3), S(0.2)}, {S(0.2), S(0.7), S(0.3)}, {S(0.2), S(0.4), S(0.9)}};
  Vec3<S> c = splat3(S(0.85));
  for (int i = 0; i < 3; ++i) {
    S fu = fract(uv.x * S(scale[i]) + S(offset[i])) - S(0.5);
    S fv = fract(uv.y * S(scale[i]) + S(offset[i] * 1.7)) - S(0.5);
    S inside = less(pow2(fu) + pow2(fv), S(radius2[i]));
    c = select(inside, colour[i], c);
  }
  return c;
}

// Bricks with mortar: running bond (every other row shifted by half a brick) and a per-brick
// brightness from a hash of the brick's row and column ("noise").
template <class S>
Vec3<S> bricks(Vec2<S> uv, S) {
  const double mortar = 0.06;
  S y = uv.y * S(2);
  S row = floor(y);
  // Every other row shifted by half a brick: square(y / 2) is 1 on even rows. (mod(floor(y), 2)
  // would feed floor's near-integer output into mod's jump, where float rounding decides the
  // brick: ill-conditioned under smoothing.)
  S x = uv.x + S(0.5) * square(y * S(0.5));
  S col = floor(x);
  S fx = fract(x), fy = fract(y);
  // 1 inside a brick, 0 on the mortar lines.
  S brick = step(fx - S(mortar)) * step(S(1 - mortar) - fx) * step(fy - S(mortar)) * step(S(1 - mortar) - fy);
  // A smooth hash: the classic fract(sin(.) * 43758) amplifies float rounding (FMA or not) into
  // different bricks on different GPUs; this varies enough between neighbours without that.
  S noise = S(0.5) + S(0.5) * sin(row * S(1.7) + col * S(2.9));
  Vec3<S> brick_colour = Vec3<S>{S(0.6), S(0.22), S(0.12)} * (S(0.75) + S(0.35) * noise);
  return mix(splat3(S(0.75)), brick_colour, brick);
}

// Colourful zigzag: stripes along a triangle-wave-displaced coordinate, two colour pairs.
template <class S>
Vec3<S> zigzag(Vec2<S> uv, S) {
  S y = uv.y + S(0.5) * triangle(uv.x * S(2));
  S band = square(y * S(2));
  S hue = square(y * S(0.5));
  Vec3<S> a = mix(Vec3<S>{S(0.95), S(0.8), S(0.2)}, Vec3<S>{S(0.2), S(0.6), S(0.9)}, hue);
  Vec3<S> b = mix(Vec3<S>{S(0.6), S(0.1), S(0.3)}, Vec3<S>{S(0.1), S(0.3), S(0.2)}, hue);
  return mix(b, a, band);
}

// Animated sine of a quadratic: frequency grows with distance (non-stationary).
template <class S>
Vec3<S> quadratic_sine(Vec2<S> uv, S time) {
  S q = pow2(uv.x) + S(0.5) * pow2(uv.y) + S(0.3) * uv.x * uv.y;
  S w = S(0.5) + S(0.5) * sin(q * S(2) - time * S(3));
  S w2 = S(0.5) + S(0.5) * cos(uv.x * S(3) + time);
  return Vec3<S>{w, S(0.6) * w + S(0.4) * w2, S(1) - w};
}

// Faux fire: turbulence (sum of |sin| octaves, each warped by the previous) rising with time, mapped
// through a black-red-yellow-white ramp.
template <class S>
Vec3<S> fire(Vec2<S> uv, S time) {
  S n = S(0);
  S x = uv.x, y = uv.y - time * S(0.8);
  double amp = 0.5, freq = 1.0;
  for (int o = 0; o < 5; ++o) {
    S warp = sin(y * S(freq * 1.3) + n * S(2) + S(o));
    n = n + S(amp) * abs(sin(x * S(freq) + warp + time * S(0.5 * (o + 1))));
    amp *= 0.5;
    freq *= 2.03;
  }
  S heat = saturate(n * S(1.4) - S(0.2) + S(0.15) * sin(uv.y * S(0.7)));
  S r = smoothstep(0.0, 0.5, heat);
  S g = smoothstep(0.3, 0.8, heat);
  S b = smoothstep(0.7, 1.0, heat);
  return Vec3<S>{r, g, b};
}

// Dorn et al. Table 2's simple ones: a step edge, ridges (fract), and black-and-white stripes.
template <class S>
Vec3<S> step_edge(Vec2<S> uv, S) {
  return splat3(step(uv.x));
}
template <class S>
Vec3<S> ridges(Vec2<S> uv, S) {
  return splat3(fract(uv.x));
}
template <class S>
Vec3<S> pulse(Vec2<S> uv, S) {
  return splat3(step(fract(uv.x) - S(0.5)));
}


// Lattice patterns a user writes (issue 13): a hash of integer cell coordinates (floor) drives the
// value. hash(i, j) = fract(13.37 sin(1.7 i + 2.9 j + 0.3)): a low gain (not 43758) keeps float
// rounding far below a display step, so native, evaluator and GLSL agree; neighbours still differ.
template <class S>
S lattice_hash(S i, S j) {
  return fract(sin(i * S(1.7) + j * S(2.9) + S(0.3)) * S(13.37));
}

// Value noise: hashed values at the lattice corners, blended with smoothstep weights (one octave at
// 4 cells per unit, one at 8.3 with half the weight), through a blue-to-sand ramp.
template <class S>
Vec3<S> value_noise(Vec2<S> uv, S) {
  S n = S(0);
  const double freq[2] = {4.0, 8.3}, amp[2] = {0.67, 0.33};
  for (int o = 0; o < 2; ++o) {
    S x = uv.x * S(freq[o]) + S(o * 0.37), y = uv.y * S(freq[o]) + S(o * 0.61);
    S i = floor(x), j = floor(y);
    S wx = smoothstep(fract(x)), wy = smoothstep(fract(y));
    S bottom = mix(lattice_hash(i, j), lattice_hash(i + S(1), j), wx);
    S top = mix(lattice_hash(i, j + S(1)), lattice_hash(i + S(1), j + S(1)), wx);
    n = n + S(amp[o]) * mix(bottom, top, wy);
  }
  return mix(Vec3<S>{S(0.1), S(0.2), S(0.5)}, Vec3<S>{S(0.95), S(0.85), S(0.6)}, n);
}

// Truchet tiles: per cell (2 per unit) a hashed orientation picks one of the two quarter-arc
// pairings; the arcs (radius 1/2 about opposite corners, half-width 0.08) are drawn dark on light.
template <class S>
Vec3<S> truchet(Vec2<S> uv, S) {
  S x = uv.x * S(2), y = uv.y * S(2);
  S flip = step(lattice_hash(floor(x), floor(y)) - S(0.5));
  S fx = fract(x), fy = fract(y);
  S gx = select(flip, S(1) - fx, fx);
  S d1 = abs(sqrt(pow2(gx) + pow2(fy)) - S(0.5));
  S d2 = abs(sqrt(pow2(gx - S(1)) + pow2(fy - S(1))) - S(0.5));
  S line = step(S(0.08) - min(d1, d2));
  return mix(Vec3<S>{S(0.9), S(0.88), S(0.8)}, Vec3<S>{S(0.15), S(0.25), S(0.35)}, line);
}

}  // namespace bl::shaders::patterns
