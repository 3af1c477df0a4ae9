#include "tuner/rho_estimate.hpp"

#include <cmath>
#include <random>
#include <stdexcept>

#include "camera/plane_batch.hpp"
#include "compiler/plain_eval.hpp"
#include "ir/atomics.hpp"
#include "render/frame.hpp"
#include "render/render.hpp"

namespace bl::tuner {

using ir::Op;

std::vector<double> estimate_rho(const ir::Graph& g, const scene::Scene& s, int pixels, int samples,
                                 std::uint64_t seed) {
  std::vector<double> sum(g.size(), 0.0);
  std::vector<int> count(g.size(), 0);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  const render::Frame f = render::frames(s).front();
  const std::vector<const texture::Texture*> textures = s.texture_slots(g.textures());
  camera::PlaneBatch b;
  camera::trace_plane(render::make_camera(s, f.view), render::footprint_options(s), b);
  std::vector<int> hit;
  for (std::size_t i = 0; i < b.size(); ++i)
    if (b.hit[i]) hit.push_back(static_cast<int>(i));
  if (hit.empty()) return std::vector<double>(g.size(), 0.0);
  for (int p = 0; p < pixels; ++p) {
    const int i = hit[rng() % hit.size()];
    std::vector<std::vector<double>> vals;
    for (int k = 0; k < samples; ++k) {
      // A sample of the footprint: (u, v) jointly Gaussian with the pixel's sds and correlation.
      const double z1 = normal(rng), z2 = normal(rng), r = b.rho[i];
      std::vector<double> in(g.inputs().size());
      for (std::size_t slot = 0; slot < in.size(); ++slot) {
        const std::string& name = g.inputs()[slot].name;
        if (name == "u")
          in[slot] = b.u[i] + b.sigma_u[i] * z1;
        else if (name == "v")
          in[slot] = b.v[i] + b.sigma_v[i] * (r * z1 + std::sqrt(std::max(0.0, 1 - r * r)) * z2);
        else if (name == "view_x")
          in[slot] = b.view_x[i];
        else if (name == "view_y")
          in[slot] = b.view_y[i];
        else if (name == "view_z")
          in[slot] = b.view_z[i];
        else
          in[slot] = render::uniform_input(s, f, name);
      }
      vals.push_back(compiler::plain_values(g, in, &textures));
    }
    for (int node = 0; node < g.size(); ++node) {
      const ir::Node& n = g.node(node);
      if (ir::op_arity(n.op) != 2 || n.op == Op::Mod || n.op == Op::Texture) continue;
      double ma = 0, mb = 0;
      for (const auto& v : vals) ma += v[n.a], mb += v[n.b];
      ma /= samples, mb /= samples;
      double saa = 0, sbb = 0, sab = 0;  // equation (B.1)
      for (const auto& v : vals) {
        const double da = v[n.a] - ma, db = v[n.b] - mb;
        saa += da * da, sbb += db * db, sab += da * db;
      }
      if (!(saa > 1e-20 && sbb > 1e-20) || !std::isfinite(sab)) continue;
      sum[node] += sab / std::sqrt(saa * sbb);
      ++count[node];
    }
  }
  std::vector<double> rho(g.size(), 0.0);
  for (int node = 0; node < g.size(); ++node)
    if (count[node] > 0) rho[node] = std::clamp(std::round(100 * sum[node] / count[node]) / 100, -1.0, 1.0);
  return rho;
}

}  // namespace bl::tuner
