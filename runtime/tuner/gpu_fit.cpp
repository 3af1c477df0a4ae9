// See gpu_fit.hpp.
#include "tuner/gpu_fit.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "compiler/functions.hpp"

namespace bl::tuner {

using compiler::LOp;

Features throughput_features(const compiler::Program& p) {
  // CostModel::breakdown_throughput's terms, less what a GPU model has no price for (bands,
  // spills, f^2 pairs): the per-pixel loop, the output stores, each op, each call (a cos beside a
  // sin of one argument at kSincosExtra, as there).
  Features x;
  x["pixel"] = 1;
  x["output"] = static_cast<double>(p.outputs.size());
  const std::vector<char> sincos = CostModel::sincos_partners(p);
  for (std::size_t i = 0; i < p.insts.size(); ++i) {
    const compiler::Inst& in = p.insts[i];
    if (in.op == LOp::Call || in.op == LOp::CallStat) {
      x[compiler::functions().at(in.fn).cpp] += sincos[i] ? CostModel::kSincosExtra : 1.0;
    } else {
      x[lop_name(in.op)] += 1;
    }
  }
  return x;
}

Features repeated(const Features& one, int n) {
  if (n < 1) throw std::invalid_argument("repeated: " + std::to_string(n) + " samples (at least 1)");
  Features x;
  for (const auto& [name, c] : one) x[name] = (name == "pixel" || name == "output") ? c : n * c;
  x["sample"] = n;
  // The samples' sums per output, as CostModel::sequential_cost prices them.
  if (const auto o = one.find("output"); o != one.end() && n > 1) x["add"] += (n - 1) * o->second;
  return x;
}

namespace {

// The prior's price of a feature: its op or function price; "sample" (the per-sample jitter and
// accumulation of MSAA in the shader) four adds.
double prior_price(const CostModel& prior, const std::string& name) {
  if (name == "sample") return 4 * prior.op_ns.at("add");
  if (const auto it = prior.op_ns.find(name); it != prior.op_ns.end()) return it->second;
  if (const auto it = prior.fn_ns.find(name); it != prior.fn_ns.end()) return it->second;
  throw std::invalid_argument("GPU cost fit: the prior cost model (" + prior.machine +
                              ") has no price for '" + name + "'");
}

// A price floor for the prior (a free op, const, stays a small positive unknown).
constexpr double kPriorFloor = 0.01;
// Fitted prices stay at least this share of their prior (non-negative, and no op free).
constexpr double kMinShare = 0.05;

// Solves (M + lambda I) d = v for symmetric positive definite M + lambda I (Cholesky, in place).
std::vector<double> solve_spd(std::vector<double> a, std::vector<double> b, int n) {
  for (int j = 0; j < n; ++j) {
    double s = a[j * n + j];
    for (int k = 0; k < j; ++k) s -= a[j * n + k] * a[j * n + k];
    if (!(s > 0)) throw std::runtime_error("GPU cost fit: the normal equations are not positive definite");
    a[j * n + j] = std::sqrt(s);
    for (int i = j + 1; i < n; ++i) {
      double t = a[i * n + j];
      for (int k = 0; k < j; ++k) t -= a[i * n + k] * a[j * n + k];
      a[i * n + j] = t / a[j * n + j];
    }
  }
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < i; ++k) b[i] -= a[i * n + k] * b[k];
    b[i] /= a[i * n + i];
  }
  for (int i = n - 1; i >= 0; --i) {
    for (int k = i + 1; k < n; ++k) b[i] -= a[k * n + i] * b[k];
    b[i] /= a[i * n + i];
  }
  return b;
}

}  // namespace

double predict(const CostModel& m, const Features& x) {
  double t = 0;
  for (const auto& [name, c] : x) {
    if (c == 0) continue;
    if (name == "sample") {
      const auto it = m.op_ns.find("sample");
      t += c * (it == m.op_ns.end() ? 0.0 : it->second);
      continue;
    }
    const auto op = m.op_ns.find(name);
    if (op != m.op_ns.end()) {
      t += c * op->second;
      continue;
    }
    const auto fn = m.fn_ns.find(name);
    if (fn == m.fn_ns.end())
      throw std::out_of_range("cost model (" + m.machine + ") has no price for '" + name + "'");
    t += c * fn->second;
  }
  return CostModel::floored(t, m.floor_ns, m.floor_norm);
}

GpuFit fit_gpu_cost_model(const std::vector<GpuSample>& samples, const CostModel& prior,
                          const GpuFitOptions& o, const std::string& machine) {
  std::vector<const GpuSample*> used;
  for (const GpuSample& s : samples)
    if (s.measured_ns >= o.min_over_floor * o.floor_ns && s.measured_ns > 0) used.push_back(&s);
  if (used.empty())
    throw std::invalid_argument("GPU cost fit: no draw above " + std::to_string(o.min_over_floor) +
                                " x the floor");
  // The throughput each draw implies: under a soft floor, T = (m^k - floor^k)^(1/k).
  std::vector<double> target;
  for (const GpuSample* s : used)
    target.push_back(
        !(o.floor_norm > 0) || !(o.floor_ns > 0)
            ? s->measured_ns
            : std::pow(std::pow(s->measured_ns, o.floor_norm) - std::pow(o.floor_ns, o.floor_norm),
                       1 / o.floor_norm));
  // The features the draws use, their prior prices, each draw's price under the prior.
  std::map<std::string, int> index;
  std::vector<std::string> names;
  std::vector<double> p;
  for (const GpuSample* s : used)
    for (const auto& [name, c] : s->x)
      if (c != 0 && !index.count(name)) {
        index[name] = static_cast<int>(names.size());
        names.push_back(name);
        p.push_back(std::max(kPriorFloor, prior_price(prior, name)));
      }
  const int n = static_cast<int>(names.size()), m = static_cast<int>(used.size());
  std::vector<double> P(m, 0);
  for (int i = 0; i < m; ++i)
    for (const auto& [name, c] : used[i]->x)
      if (c != 0) P[i] += c * p[index.at(name)];
  // alpha: least squares of the relative error alpha P / measured - 1.
  double num = 0, den = 0;
  for (int i = 0; i < m; ++i) {
    const double r = P[i] / target[i];
    num += r;
    den += r * r;
  }
  const double alpha = num / den;
  // Prices alpha p_j (1 + d_j): the residual of draw i is linear in d,
  // (alpha P_i - m_i) / m_i + sum_j alpha x_ij p_j / m_i d_j. Ridge lambda |d|^2, d_j >= kMinShare - 1
  // by an active set (a d below the bound is fixed there and the rest refitted).
  std::vector<double> d(n, 0.0);
  std::vector<char> fixed(n, 0);
  for (int round = 0; round < n + 1; ++round) {
    std::vector<int> free;
    for (int j = 0; j < n; ++j)
      if (!fixed[j]) free.push_back(j);
    const int f = static_cast<int>(free.size());
    std::vector<int> at(n, -1);
    for (int k = 0; k < f; ++k) at[free[k]] = k;
    std::vector<double> M(static_cast<std::size_t>(f) * f, 0.0), v(f, 0.0);
    for (int i = 0; i < m; ++i) {
      const double mi = target[i];
      double b = (mi - alpha * P[i]) / mi;
      std::vector<std::pair<int, double>> row;
      for (const auto& [name, c] : used[i]->x) {
        if (c == 0) continue;
        const int j = index.at(name);
        const double a = alpha * c * p[j] / mi;
        if (fixed[j])
          b -= a * d[j];
        else
          row.push_back({at[j], a});
      }
      for (const auto& [k, a] : row) {
        v[k] += a * b;
        for (const auto& [l, a2] : row) M[static_cast<std::size_t>(k) * f + l] += a * a2;
      }
    }
    for (int k = 0; k < f; ++k) M[static_cast<std::size_t>(k) * f + k] += o.lambda;
    const std::vector<double> sol = f > 0 ? solve_spd(M, v, f) : std::vector<double>();
    bool clean = true;
    for (int k = 0; k < f; ++k) {
      d[free[k]] = sol[k];
      if (sol[k] < kMinShare - 1) {
        fixed[free[k]] = 1;
        d[free[k]] = kMinShare - 1;
        clean = false;
      }
    }
    if (clean) break;
  }
  GpuFit out;
  out.alpha = alpha;
  out.used = m;
  out.fitted = n;
  CostModel& g = out.model;
  g.machine = machine;
  g.method = "gpu-fit";
  g.floor_ns = o.floor_ns;
  g.floor_norm = o.floor_norm;
  g.kernels = CostModel::kKernels;
  g.latency_norm = CostModel::kLatencyNorm;
  g.window_ns = 0;  // a GPU hides latency with other fragments: throughput only
  for (const auto& [name, c] : prior.op_ns) g.op_ns[name] = alpha * std::max(kPriorFloor, c);
  for (const auto& [name, c] : prior.fn_ns) g.fn_ns[name] = alpha * std::max(kPriorFloor, c);
  g.op_ns["sample"] = alpha * prior_price(prior, "sample");
  for (int j = 0; j < n; ++j) {
    const double price = alpha * p[j] * (1 + d[j]);
    if (g.op_ns.count(names[j]))  // ops, and the sample loop placed there above
      g.op_ns[names[j]] = price;
    else
      g.fn_ns[names[j]] = price;
  }
  return out;
}

}  // namespace bl::tuner
