#include "image/colormap.hpp"

#include <algorithm>
#include <cmath>

namespace bl {

std::array<float, 3> viridis(float t) {
  static constexpr float kTable[11][3] = {
      {0.267004f, 0.004874f, 0.329415f}, {0.282623f, 0.140926f, 0.457517f}, {0.253935f, 0.265254f, 0.529983f},
      {0.206756f, 0.371758f, 0.553117f}, {0.163625f, 0.471133f, 0.558148f}, {0.127568f, 0.566949f, 0.550556f},
      {0.134692f, 0.658636f, 0.517649f}, {0.266941f, 0.748751f, 0.440573f}, {0.477504f, 0.821444f, 0.318195f},
      {0.741388f, 0.873449f, 0.149561f}, {0.993248f, 0.906157f, 0.143936f}};
  const float s = (std::isnan(t) ? 0.0f : std::clamp(t, 0.0f, 1.0f)) * 10.0f;
  const int i = std::min(int(s), 9);
  const float f = s - i;
  return {kTable[i][0] + f * (kTable[i + 1][0] - kTable[i][0]),
          kTable[i][1] + f * (kTable[i + 1][1] - kTable[i][1]),
          kTable[i][2] + f * (kTable[i + 1][2] - kTable[i][2])};
}

}  // namespace bl
