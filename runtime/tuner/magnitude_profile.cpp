#include "tuner/magnitude_profile.hpp"

#include <cmath>

#include "compiler/functions.hpp"
#include "tuner/cost_model.hpp"

namespace bl::tuner {

namespace {

// Counts per band -> shares per band; atomics never seen (all counts 0) are dropped.
void normalize(std::map<std::string, std::vector<double>>& counts) {
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
}

}  // namespace

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
  normalize(counts);
  return counts;
}

std::map<std::string, std::vector<double>> joint_profile(const compiler::Program& smoothed,
                                                         const PixelSample& sample) {
  compiler::Program q = smoothed;
  std::vector<std::string> atomic;
  q.outputs.clear();
  q.output_names.clear();
  for (const compiler::Inst& in : smoothed.insts) {
    if (in.op != compiler::LOp::Call && in.op != compiler::LOp::CallStat) continue;
    const compiler::Function& f = compiler::functions()[in.fn];
    if (!CostModel::sigma_entry(f)) continue;
    const std::string a = CostModel::atomic_of(f.cpp);
    q.outputs.push_back(in.arg[0]);
    q.outputs.push_back(in.arg[1]);
    q.output_names.push_back(a + ".x");
    q.output_names.push_back(a + ".sigma");
    atomic.push_back(a);
  }
  std::map<std::string, std::vector<double>> counts;
  if (q.outputs.empty()) return counts;
  const std::vector<std::vector<float>> values = sample.outputs(q);
  for (std::size_t k = 0; k < atomic.size(); ++k) {
    std::vector<double>& c = counts[atomic[k]];
    c.resize(CostModel::kBands * CostModel::kSigmaBands, 0.0);
    const std::vector<float>&x = values[2 * k], &s = values[2 * k + 1];
    for (std::size_t i = 0; i < x.size(); ++i)
      if (std::isfinite(x[i]) && std::isfinite(s[i]))
        c[CostModel::band_of(std::fabs(x[i])) * CostModel::kSigmaBands + CostModel::sigma_band_of(s[i])] += 1;
  }
  normalize(counts);
  return counts;
}

}  // namespace bl::tuner
