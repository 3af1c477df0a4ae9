#include "tuner/calibrate.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <sstream>
#include <stdexcept>

#include "compiler/evaluator.hpp"
#include "compiler/functions.hpp"

namespace bl::tuner {

using compiler::Inst;
using compiler::LOp;
using compiler::Program;

std::vector<int> calibration_args(int arity, bool spread_is_var) {
  const int spread0 = spread_is_var ? 5 : 1;
  std::vector<int> a;
  for (int j = 0; j < arity; ++j) {
    if (j == arity - 1 && arity % 2 == 1 && arity > 1)
      a.push_back(4);
    else if (j % 2 == 0)
      a.push_back(j % 4 == 0 ? 0 : 2);
    else
      a.push_back(j % 4 == 1 ? spread0 : 3);
  }
  return a;
}

std::vector<int> calibration_args(const compiler::Function& f) {
  return calibration_args(f.arity, f.stat && !CostModel::sigma_entry(f));
}

namespace {

// Inputs: slot 0 and 1 hold values in [0.05, 3] (positive so log, sqrt and 1/x stay finite) with
// sds in [0.01, 0.5]; slot 2's mean is a small value in [0, 0.3] (correlations, conditions).
constexpr int kSlots = 3;

struct Inputs {
  std::vector<std::vector<float>> mean, sd;
  compiler::Batch batch;
};

// Texture lookups are timed on a 512x512 RGB texture (a typical size; the cost is dominated by
// the four or eight texel reads, not the size, as long as it exceeds the cache).
const texture::Texture& calibration_texture() {
  static const texture::Texture t = [] {
    texture::Level L;
    L.width = L.height = 512;
    L.channels = 3;
    L.texels.resize(std::size_t(512) * 512 * 3);
    for (std::size_t i = 0; i < L.texels.size(); ++i)
      L.texels[i] = static_cast<float>((i * 2654435761u) % 1000) / 1000;
    return texture::make_texture("calibration", "<calibration>", std::move(L));
  }();
  return t;
}

Inputs make_inputs(int n) {
  Inputs in;
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<float> x(0.05f, 3.0f), s(0.01f, 0.5f), small(0.0f, 0.3f);
  in.mean.assign(kSlots, std::vector<float>(n));
  in.sd.assign(kSlots, std::vector<float>(n));
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < 2; ++k) in.mean[k][i] = x(rng), in.sd[k][i] = s(rng);
    in.mean[2][i] = small(rng), in.sd[2][i] = s(rng);
  }
  in.batch.count = n;
  in.batch.textures = {&calibration_texture()};
  for (int k = 0; k < kSlots; ++k) {
    in.batch.mean.push_back(in.mean[k].data());
    in.batch.sd.push_back(in.sd[k].data());
    in.batch.grad_x.push_back(in.sd[k].data());
    in.batch.grad_y.push_back(in.sd[k].data());
  }
  return in;
}

// Base program: mean/sd of slots 0 and 1, the small value, and the variance sd0^2 (indices 0..5).
Program base_program() {
  Program p;
  p.input_count = kSlots;
  p.input_names = {"a", "b", "c"};
  p.texture_names = {"calibration"};
  auto input = [&](LOp op, int slot) {
    Inst in;
    in.op = op;
    in.arg[0] = slot;
    p.insts.push_back(in);
  };
  input(LOp::InMean, 0);  // 0
  input(LOp::InSd, 0);    // 1
  input(LOp::InMean, 1);  // 2
  input(LOp::InSd, 1);    // 3
  input(LOp::InMean, 2);  // 4
  Inst sq;
  sq.op = LOp::Mul;
  sq.arg[0] = 1, sq.arg[1] = 1;
  p.insts.push_back(sq);  // 5: var
  p.outputs = {0};
  p.output_names = {"out"};
  return p;
}

double time_program(const Program& p, Inputs& in, const CalibrationOptions& opt) {
  compiler::Evaluator ev(p);
  std::vector<float> out(in.batch.count);
  const std::vector<float*> outs{out.data()};
  double best = 1e300;
  for (int t = 0; t < opt.trials; ++t) {
    int reps = 0;
    const auto t0 = std::chrono::steady_clock::now();
    double ms = 0;
    do {
      ev.run(in.batch, outs);
      ++reps;
      ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    } while (ms < opt.min_ms);
    best = std::min(best, ms * 1e6 / (static_cast<double>(reps) * in.batch.count));  // ns per pixel
  }
  return best;
}

// ns per pixel of one instruction: (program with `copies` of it - program without) / copies.
double time_inst(Program p, const Inst& inst, int prefix_stat, Inputs& in, const CalibrationOptions& opt) {
  if (prefix_stat >= 0) {  // Mean/Var read a CallStat: time it in both programs
    Inst st;
    st.op = LOp::CallStat;
    st.fn = prefix_stat;
    const auto a = calibration_args(compiler::functions()[prefix_stat].arity, true);
    for (std::size_t j = 0; j < a.size(); ++j) st.arg[j] = a[j];
    p.insts.push_back(st);
  }
  const double base = time_program(p, in, opt);
  Inst copy = inst;
  if (prefix_stat >= 0) copy.arg[0] = static_cast<int>(p.insts.size()) - 1;
  for (int c = 0; c < opt.copies; ++c) p.insts.push_back(copy);
  p.outputs = {static_cast<int>(p.insts.size()) - 1};
  const double with = time_program(p, in, opt);
  return std::max(0.01, (with - base) / opt.copies);
}

}  // namespace

namespace {

CostModel calibrate_evaluator(const CalibrationOptions& opt,
                              const std::function<void(const std::string&, double)>& progress) {
  CostModel m;
  m.machine = cpu_model();
  m.method = "evaluator";
  Inputs in = make_inputs(opt.pixels);
  const Program base = base_program();
  const auto& fns = compiler::functions();
  int first_stat = -1;
  for (std::size_t f = 0; f < fns.size() && first_stat < 0; ++f)
    if (fns[f].stat) first_stat = static_cast<int>(f);
  auto wanted = [&](const std::string& name) {
    return opt.only.empty() || name.find(opt.only) != std::string::npos;
  };
  for (int o = 0; o <= static_cast<int>(LOp::TexStat); ++o) {
    const LOp op = static_cast<LOp>(o);
    if (op == LOp::Call || op == LOp::CallStat || !wanted(lop_name(op))) continue;
    Inst inst;
    inst.op = op;
    int prefix = -1;
    switch (op) {
      case LOp::Const:
        inst.k = 0.5f;
        break;
      case LOp::InMean:
      case LOp::InSd:
      case LOp::InGradX:
      case LOp::InGradY:
        inst.arg[0] = 0;
        break;
      case LOp::Mean:
      case LOp::Var:
        if (first_stat < 0) continue;  // no stat function in the table: never emitted either
        prefix = first_stat;
        break;
      case LOp::TexPlain:
        inst.tex = 0, inst.arg[0] = 0, inst.arg[1] = 2;
        break;
      case LOp::TexStat:
        inst.tex = 0, inst.arg[0] = 0, inst.arg[1] = 2, inst.arg[2] = 1, inst.arg[3] = 3;
        break;
      default:
        inst.arg[0] = 0, inst.arg[1] = 2;
        break;
    }
    const double ns = time_inst(base, inst, prefix, in, opt);
    m.op_ns[lop_name(op)] = ns;
    if (progress) progress(lop_name(op), ns);
  }
  if (first_stat < 0) m.op_ns["mean"] = m.op_ns["var"] = m.op_ns["const"];  // unused but complete
  for (std::size_t f = 0; f < fns.size(); ++f) {
    if (!wanted(fns[f].cpp)) continue;
    Inst inst;
    inst.op = fns[f].stat ? LOp::CallStat : LOp::Call;
    inst.fn = static_cast<int>(f);
    const auto a = calibration_args(fns[f]);
    for (std::size_t j = 0; j < a.size(); ++j) inst.arg[j] = a[j];
    const double ns = time_inst(base, inst, -1, in, opt);
    m.fn_ns[fns[f].cpp] = ns;
    if (progress) progress(fns[f].cpp, ns);
  }
  return m;
}

}  // namespace

CostModel calibrate(const CalibrationOptions& opt,
                    const std::function<void(const std::string&, double)>& progress) {
  if (opt.method == CalibrationOptions::Method::Compiled) {
    try {
      return calibrate_compiled(opt, progress);
    } catch (const jit::Error& e) {
      std::fprintf(stderr,
                   "calibrate: compiled-code calibration unavailable, timing the evaluator instead:\n%s\n",
                   e.what());
    }
  }
  return calibrate_evaluator(opt, progress);
}

CostModel load_or_calibrate(const std::string& path, bool verbose, CalibrationOptions::Method method) {
  const std::string machine = cpu_model();
  CalibrationOptions opt;
  opt.method = method;
  const bool compiled = method == CalibrationOptions::Method::Compiled;
  try {
    CostModel m = load_cost_model(path, machine);
    // A model timed on the evaluator is replaced once a compiler exists (when compiled is asked
    // for), a compiled one when the evaluator is asked for, a compiled one without latencies always.
    if (compiled && m.method != "compiled" && jit::compiler_available())
      throw std::runtime_error("cost model " + path + " was calibrated on the evaluator");
    if (!compiled && m.method != "evaluator")
      throw std::runtime_error("cost model " + path + " was calibrated on compiled code");
    if (m.method == "compiled" && (m.fn_lat_ns.empty() || !(m.window_ns > 0)))
      throw std::runtime_error("cost model " + path + " has no latencies");
    if (m.method == "compiled" && m.kernels != CostModel::kKernels)
      throw std::runtime_error("cost model " + path + " was timed with older calibration kernels");
    // The window is measured (and fitted) under the latency bound's norm: another norm, another window.
    if (m.method == "compiled" && m.latency_norm != CostModel::kLatencyNorm)
      throw std::runtime_error("cost model " + path + " prices latency with another norm (" +
                               std::to_string(m.latency_norm) + ", 0 = max)");
    // The same program costs another time under other flags (-march=native: floor 0.48 against
    // 1.17 ns), and fronts and speed-ups are measured with today's.
    if (m.method == "compiled" && m.jit_flags != jit::flags_text(opt.jit))
      throw std::runtime_error("cost model " + path + " was timed with JIT flags '" + m.jit_flags +
                               "', not '" + jit::flags_text(opt.jit) + "'");
    for (const auto& [name, bands] : m.fn_band_ns)
      if (bands.size() != std::size_t(CostModel::kBands) &&
          bands.size() != std::size_t(CostModel::kBands * CostModel::kSigmaBands))
        throw std::runtime_error("cost model " + path + " has another band layout (" + name + ")");
    if (m.covers_all()) return m;
    // Only what is missing (a new op or table function) is merged from a fresh calibration: the
    // entries already measured keep their values, so fronts computed before stay comparable.
    const std::string missing = m.missing();
    if (verbose)
      std::fprintf(stderr, "cost model %s lacks:%s; timing those\n", path.c_str(), missing.c_str());
    const CostModel part = calibrate(opt);
    std::istringstream names(missing);
    std::string name;
    while (names >> name) {
      if (part.op_ns.count(name)) m.op_ns[name] = part.op_ns.at(name);
      if (part.fn_ns.count(name)) m.fn_ns[name] = part.fn_ns.at(name);
      if (part.fn_band_ns.count(name)) m.fn_band_ns[name] = part.fn_band_ns.at(name);
      if (part.fn_lat_ns.count(name)) m.fn_lat_ns[name] = part.fn_lat_ns.at(name);
      if (part.op_lat_ns.count(name)) m.op_lat_ns[name] = part.op_lat_ns.at(name);
    }
    if (m.covers_all()) {
      save_cost_model(path, m);
      return m;
    }
  } catch (const std::runtime_error& e) {
    if (verbose) std::fprintf(stderr, "%s; calibrating\n", e.what());
  }
  CostModel m =
      calibrate(opt, verbose ? [](const std::string& n,
                                  double ns) { std::fprintf(stderr, "  %-40s %8.2f ns\n", n.c_str(), ns); }
                             : std::function<void(const std::string&, double)>{});
  save_cost_model(path, m);
  return m;
}

}  // namespace bl::tuner
