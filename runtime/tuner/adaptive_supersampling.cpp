// See adaptive_supersampling.hpp.
#include "tuner/adaptive_supersampling.hpp"

namespace bl::tuner {

std::optional<PickedPair> adaptive_supersampling(const SceneTuner& t, double target) {
  const std::vector<LodSide> sides = lod_sides(t, {{"plain", t.plain_schedule()}});
  if (sides.empty()) return std::nullopt;
  return fastest_pair(t, sides, target, false);
}

}  // namespace bl::tuner
