#include "render/value_range.hpp"

#include <algorithm>
#include <cmath>

#include "ir/ranges.hpp"
#include "render/render.hpp"

namespace bl::render {

ValueRange valid_range(const scene::Scene& s, const ir::Graph& g, const std::vector<Image>& truths) {
  std::vector<Image> seen = truths;
  for (const Frame& f : frames(s)) seen.push_back(render_native(s, f, 0));
  ValueRange r = ValueRange::of(seen);
  const std::vector<ir::Interval> node = ir::node_ranges(g);
  for (int c = 0; c < Image::kChannels && c < static_cast<int>(g.outputs().size()); ++c) {
    const ir::Interval& out = node[g.outputs()[c]];
    const float bg = static_cast<float>(s.background[c]);
    if (std::isfinite(out.lo)) r.lo[c] = std::min(static_cast<float>(out.lo), bg);
    if (std::isfinite(out.hi)) r.hi[c] = std::max(static_cast<float>(out.hi), bg);
  }
  return r;
}

}  // namespace bl::render
