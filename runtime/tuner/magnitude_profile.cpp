#include "tuner/magnitude_profile.hpp"

#include <cmath>

#include "compiler/functions.hpp"
#include "tuner/cost_model.hpp"

namespace bl::tuner {

std::map<std::string, std::vector<double>> magnitude_profile(const compiler::Program& plain,
                                                             const PixelSample& sample) {
  // A copy of the program whose outputs are the calls' first arguments.
  compiler::Program q = plain;
  std::vector<std::string> atomic;
  q.outputs.clear();
  q.output_names.clear();
  for (const compiler::Inst& in : plain.insts) {
    if (in.op != compiler::LOp::Call && in.op != compiler::LOp::CallStat) continue;
    const std::string a = CostModel::atomic_of(compiler::functions()[in.fn].cpp);
    if (a.empty() || plain.pair_valued(in.arg[0])) continue;
    q.outputs.push_back(in.arg[0]);
    q.output_names.push_back(a);
    atomic.push_back(a);
  }
  std::map<std::string, std::vector<double>> counts;
  if (q.outputs.empty()) return counts;
  const std::vector<std::vector<float>> values = sample.outputs(q);
  for (std::size_t k = 0; k < atomic.size(); ++k) {
    std::vector<double>& c = counts[atomic[k]];
    c.resize(CostModel::kBands, 0.0);
    for (float v : values[k])
      if (std::isfinite(v)) c[CostModel::band_of(std::fabs(v))] += 1;
  }
  for (auto it = counts.begin(); it != counts.end();) {
    double total = 0;
    for (double c : it->second) total += c;
    if (total == 0) {
      it = counts.erase(it);
      continue;
    }
    for (double& c : it->second) c /= total;
    ++it;
  }
  return counts;
}

}  // namespace bl::tuner
