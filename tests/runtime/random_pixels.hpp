// Random pixel inputs for a compiled program, by input name: u, v uniform in [-uv, uv] with
// footprint sd uniform in [1e-3, sd_max] and small screen gradients, time in [0, 3], a unit
// view with z >= 0.3, the default light. Shared by the compiler and GLSL-suite tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "compiler/evaluator.hpp"

namespace bl::testing {

struct RandomPixels {
  int n;
  std::vector<std::vector<float>> mean, sd, gx, gy;

  RandomPixels(const compiler::Program& p, int count, unsigned seed, float uv, float sd_max) : n(count) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> U(-uv, uv), S(1e-3f, sd_max), G(-0.05f, 0.05f), T(0, 3),
        D(-0.7f, 0.7f);
    const int k = p.input_count;
    mean.assign(k, std::vector<float>(n));
    sd = gx = gy = mean;
    for (int i = 0; i < n; ++i) {
      const float vx = D(rng), vy = D(rng), vz = std::sqrt(std::max(0.09f, 1 - vx * vx - vy * vy));
      const float len = std::sqrt(vx * vx + vy * vy + vz * vz);
      for (int j = 0; j < k; ++j) {
        const std::string& name = p.input_names[j];
        float m = 0, s = 0, a = 0, c = 0;
        if (name == "u" || name == "v")
          m = U(rng), s = S(rng), a = G(rng), c = G(rng);
        else if (name == "time")
          m = T(rng);
        else if (name == "view_x")
          m = vx / len;
        else if (name == "view_y")
          m = vy / len;
        else if (name == "view_z")
          m = vz / len;
        else if (name == "light_x")
          m = 0.4f;
        else if (name == "light_y")
          m = 0.3f;
        else if (name == "light_z")
          m = 0.866f;
        mean[j][i] = m, sd[j][i] = s, gx[j][i] = a, gy[j][i] = c;
      }
    }
  }

  // A batch pointing into this object's arrays (valid while it lives).
  compiler::Batch batch() const {
    compiler::Batch b;
    b.count = n;
    for (std::size_t j = 0; j < mean.size(); ++j) {
      b.mean.push_back(mean[j].data());
      b.sd.push_back(sd[j].data());
      b.grad_x.push_back(gx[j].data());
      b.grad_y.push_back(gy[j].data());
    }
    return b;
  }
};

}  // namespace bl::testing
