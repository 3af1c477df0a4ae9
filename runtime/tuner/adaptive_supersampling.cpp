// See adaptive_supersampling.hpp.
#include "tuner/adaptive_supersampling.hpp"

#include "compiler/lower.hpp"
#include "rules/rule.hpp"

namespace bl::tuner {

std::optional<PickedPair> adaptive_supersampling(const SceneTuner& t, double target) {
  const std::vector<LodSide> sides =
      lod_sides(t, {{"plain", compiler::uniform_schedule(t.graph(), rules::parse_rule("none"))}});
  if (sides.empty()) return std::nullopt;
  return fastest_pair(t, sides, target, false);
}

}  // namespace bl::tuner
