#include "render/value_range.hpp"

#include <algorithm>
#include <cmath>

#include "ir/ranges.hpp"
#include "render/render.hpp"

namespace bl::render {

DeclaredBounds declared_bounds(const scene::Scene& s, const ir::Graph& g) {
  DeclaredBounds d;
  const std::vector<ir::Interval> node = ir::node_ranges(g);
  for (int c = 0; c < Image::kChannels && c < static_cast<int>(g.outputs().size()); ++c) {
    const ir::Interval& out = node[g.outputs()[c]];
    const float bg = static_cast<float>(s.background[c]);
    if (std::isfinite(out.lo)) d.lo[c] = std::min(static_cast<float>(out.lo), bg);
    if (std::isfinite(out.hi)) d.hi[c] = std::max(static_cast<float>(out.hi), bg);
  }
  return d;
}

ValueRange valid_range(const scene::Scene& s, const ir::Graph& g, const std::vector<Image>& truths) {
  std::vector<Image> seen = truths;
  for (const Frame& f : frames(s)) seen.push_back(render_native(s, f, 0));
  return bounded(ValueRange::of(seen), declared_bounds(s, g));
}

}  // namespace bl::render
