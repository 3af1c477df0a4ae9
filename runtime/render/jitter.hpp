// Counter-based per-sample jitter: sample k of pixel p in a frame gets its offset from a hash of
// (frame key, pixel, sample) alone, so there is no per-pixel generator to construct, any sample can
// be computed on its own (in any order, on any thread, in emitted code), and the values are the same
// on every platform: splitmix64 bits and a Box-Muller transform written out here, not
// std::normal_distribution (whose algorithm, and so whose output, differs between standard libraries).
// The only platform dependence left is libm's log/sin/cos rounding (<= 1 ulp in double).
#pragma once

#include <cmath>
#include <cstdint>

namespace bl::render {

inline std::uint64_t mix64(std::uint64_t x) {  // splitmix64 finalizer
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// The key of a frame (seed, view, time in microseconds).
inline std::uint64_t frame_key(std::uint64_t seed, int view, double time) {
  return mix64(seed ^ mix64(static_cast<std::uint64_t>(view)) ^
               mix64(static_cast<std::uint64_t>(std::llround(time * 1e6))));
}

struct Offset {
  double x = 0, y = 0;
};

// Offset ~ N(0, sigma^2) per axis of sample `k` of pixel `pixel` (row-major index), by Box-Muller
// over two independent 53-bit uniforms: u1 in (0, 1] (so log(u1) is finite), u2 in [0, 1).
inline Offset gaussian_jitter(std::uint64_t frame, std::uint64_t pixel, std::uint32_t k, double sigma) {
  const std::uint64_t key = mix64(mix64(frame ^ pixel) + k);
  const double u1 = static_cast<double>((mix64(key) >> 11) + 1) * 0x1.0p-53;
  const double u2 = static_cast<double>(mix64(key ^ 0x5851F42D4C957F2Dull) >> 11) * 0x1.0p-53;
  const double r = sigma * std::sqrt(-2.0 * std::log(u1)), a = 6.283185307179586 * u2;
  return {r * std::cos(a), r * std::sin(a)};
}

}  // namespace bl::render
