#include "tuner/rho_estimate.hpp"

#include <cmath>
#include <random>
#include <stdexcept>

#include "camera/plane_batch.hpp"
#include "ir/atomics.hpp"
#include "render/frame.hpp"
#include "render/render.hpp"

namespace bl::tuner {

using ir::Op;

std::vector<double> eval_graph(const ir::Graph& g, const std::vector<double>& inputs,
                               const std::vector<const texture::Texture*>* textures) {
  std::vector<double> v(g.size());
  for (int i = 0; i < g.size(); ++i) {
    const ir::Node& n = g.node(i);
    const double a = n.a >= 0 ? v[n.a] : 0, b = n.b >= 0 ? v[n.b] : 0, c = n.c >= 0 ? v[n.c] : 0;
    switch (n.op) {
      case Op::Const:
        v[i] = n.value;
        break;
      case Op::Input:
        v[i] = inputs.at(static_cast<int>(n.value));
        break;
      case Op::Add:
        v[i] = a + b;
        break;
      case Op::Sub:
        v[i] = a - b;
        break;
      case Op::Mul:
        v[i] = a * b;
        break;
      case Op::Div:
        v[i] = a / b;
        break;
      case Op::Neg:
        v[i] = -a;
        break;
      case Op::Min:
        v[i] = std::min(a, b);
        break;
      case Op::Max:
        v[i] = std::max(a, b);
        break;
      case Op::Less:
        v[i] = a < b ? 1 : 0;
        break;
      case Op::Select:
        v[i] = a * b + (1 - a) * c;
        break;
      case Op::Mod:
        v[i] = a - n.value * std::floor(a / n.value);
        break;
      case Op::Call:
        v[i] = ir::plain_atomic(n.atomic, a);
        break;
      case Op::Texture:
        if (!textures || static_cast<std::size_t>(n.value) >= textures->size() || !(*textures)[int(n.value)])
          throw std::invalid_argument("eval_graph: texture '" + g.textures().at(int(n.value)) +
                                      "' is not bound");
        v[i] = (*textures)[int(n.value)]->plain(static_cast<float>(a), static_cast<float>(b), n.atomic);
        break;
    }
  }
  return v;
}

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
      vals.push_back(eval_graph(g, in, &textures));
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
