// FNV-1a over bytes: a stable 64-bit hash (independent of the platform's std::hash and of pointer
// values) for cache keys: traced graphs, scenes, cost models.
#pragma once

#include <cstdint>
#include <string_view>

namespace bl::ir {

inline constexpr std::uint64_t kFnvOffset = 1469598103934665603ull;
inline constexpr std::uint64_t kFnvPrime = 1099511628211ull;

// `h` continues an earlier hash, so several pieces chain into one.
inline std::uint64_t fnv1a(std::string_view bytes, std::uint64_t h = kFnvOffset) {
  for (unsigned char ch : bytes) h = (h ^ ch) * kFnvPrime;
  return h;
}

}  // namespace bl::ir
