#include "tuner/cost_model.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "compiler/functions.hpp"

namespace bl::tuner {

using compiler::LOp;

const char* lop_name(LOp op) {
  switch (op) {
    case LOp::Const:
      return "const";
    case LOp::InMean:
      return "in_mean";
    case LOp::InSd:
      return "in_sd";
    case LOp::InGradX:
      return "in_grad_x";
    case LOp::InGradY:
      return "in_grad_y";
    case LOp::Add:
      return "add";
    case LOp::Sub:
      return "sub";
    case LOp::Mul:
      return "mul";
    case LOp::Div:
      return "div";
    case LOp::Neg:
      return "neg";
    case LOp::Min:
      return "min";
    case LOp::Max:
      return "max";
    case LOp::Less:
      return "less";
    case LOp::Sqrt:
      return "sqrt";
    case LOp::NonNeg:
      return "nonneg";
    case LOp::Call:
      return "call";
    case LOp::CallStat:
      return "call_stat";
    case LOp::Mean:
      return "mean";
    case LOp::Var:
      return "var";
    case LOp::TexPlain:
      return "tex_plain";
    case LOp::TexStat:
      return "tex_stat";
  }
  return "?";
}

int CostModel::band_of(double ax) {
  if (!(ax >= 3.1622776601683795)) return 0;  // also NaN
  return static_cast<int>(std::min<double>(kBands - 1, std::floor(std::log10(ax) + 0.5)));
}

double CostModel::band_magnitude(int band) {
  return std::pow(10.0, band);
}

int CostModel::sigma_band_of(double sigma) {
  return sigma < 0.01 ? 0 : sigma < 0.1 ? 1 : sigma < 1 ? 2 : 3;
}

double CostModel::sigma_band_scale(int band) {
  static const double m[kSigmaBands] = {0.003, 0.03, 0.3, 3};
  return m[band];
}

std::string CostModel::atomic_of(const std::string& cpp) {
  for (const char* ns : {"bl::plain::", "bl::gaussian::", "bl::box::", "bl::tent::"}) {
    const std::string prefix = ns;
    if (cpp.rfind(prefix, 0) != 0) continue;
    std::string a = cpp.substr(prefix.size());
    // f^2 entries: "fract_sq" is fract's (an atomic named *_sq would have a plain entry of that name)
    for (const std::string suffix : {"_sq", "_stat"})  // f^2 and {E f, Var f} entries: f's
      if (a.size() > suffix.size() && a.compare(a.size() - suffix.size(), suffix.size(), suffix) == 0 &&
          compiler::find_function("bl::plain::" + a) < 0)
        a.resize(a.size() - suffix.size());
    return a;
  }
  return "";
}

bool CostModel::sigma_entry(const compiler::Function& f) {
  if (f.arity != 2 || f.cpp.rfind("bl::plain::", 0) == 0 || atomic_of(f.cpp).empty()) return false;
  return !f.stat || f.mean_entry >= 0;
}

int CostModel::square_sibling(int fn) {
  static const std::vector<int> sib = [] {
    std::vector<int> v(compiler::functions().size(), -1);
    for (std::size_t f = 0; f < v.size(); ++f) {
      const compiler::Function& F = compiler::functions()[f];
      const std::string& n = F.cpp;
      if (F.arity == 2 && !F.stat && n.size() > 3 && n.compare(n.size() - 3, 3, "_sq") == 0)
        v[f] = compiler::find_function(n.substr(0, n.size() - 3));
    }
    return v;
  }();
  return fn >= 0 && fn < static_cast<int>(sib.size()) ? sib[fn] : -1;
}

double CostModel::function_cost(int fn) const {
  const std::string& name = compiler::functions().at(fn).cpp;
  const auto it = fn_ns.find(name);
  if (it == fn_ns.end())
    throw std::out_of_range("cost model (" + machine + ") has no entry for function " + name +
                            ": recalibrate (bltune --calibrate)");
  const auto bands = fn_band_ns.find(name);
  if (bands == fn_band_ns.end()) return it->second;
  const std::vector<double>& c = bands->second;
  const std::string atomic = atomic_of(name);
  double ns = 0;
  if (c.size() == static_cast<std::size_t>(kBands * kSigmaBands)) {
    if (const auto joint = joint_share.find(atomic); joint != joint_share.end()) {
      for (std::size_t b = 0; b < c.size(); ++b) ns += joint->second[b] * c[b];
      return ns;
    }
    if (const auto share = band_share.find(atomic); share != band_share.end()) {
      for (int b = 0; b < kBands; ++b) ns += share->second[b] * c[b * kSigmaBands + 2];
      return ns;
    }
    return it->second;
  }
  const auto share = band_share.find(atomic);
  if (share == band_share.end() || c.size() != static_cast<std::size_t>(kBands)) return it->second;
  for (int b = 0; b < kBands; ++b) ns += share->second[b] * c[b];
  return ns;
}

double CostModel::latency_bound(double t, double path, double window) {
  if (!(window > 0) || !(path > 0)) return t;
  const double chain = path * std::min(1.0, t / window);
  return std::pow(std::pow(t, kLatencyNorm) + std::pow(chain, kLatencyNorm), 1 / kLatencyNorm);
}

double CostModel::window_for(double t, double path, double measured) {
  if (!(measured > t * 1.05) || !(path > 0)) return 1e9;
  const double chain =
      std::pow(std::pow(measured, kLatencyNorm) - std::pow(t, kLatencyNorm), 1 / kLatencyNorm);
  return path * t / chain;
}

double CostModel::floored(double t, double floor, double norm) {
  if (!(floor > 0)) return t;
  if (!(norm > 0)) return std::max(floor, t);
  return std::pow(std::pow(floor, norm) + std::pow(std::max(0.0, t), norm), 1 / norm);
}

double CostModel::cost(const compiler::Program& p) const {
  return floored(latency_bound(throughput(p), critical_path(p), window_ns), floor_ns, floor_norm);
}

double CostModel::sequential_cost(const compiler::Program& sample, int n) const {
  if (n < 1) throw std::invalid_argument("cost model: " + std::to_string(n) + " samples (at least 1)");
  auto op = [&](const char* name) {
    const auto it = op_ns.find(name);
    return it == op_ns.end() ? 0.0 : it->second;
  };
  const double outputs = static_cast<double>(sample.outputs.size());
  const double once = op("pixel") + outputs * op("output");
  // A floored model (a GPU's): the samples' sum against the floor, not each sample's; "sample": a
  // fitted model's price of the shader's sample loop (none in a calibrated one).
  const double body =
      latency_bound(throughput(sample), critical_path(sample), window_ns) - once + op("sample");
  return floored(n * body + once + (n - 1) * outputs * op("add"), floor_ns, floor_norm);
}

double CostModel::msaa_cost(const compiler::Program& plain, int n) const {
  return floor_ns > 0 ? sequential_cost(plain, n) : n * cost(plain);
}

std::vector<char> CostModel::sincos_partners(const compiler::Program& p) {
  static const int sin_fn = compiler::find_function("bl::plain::sin"),
                   cos_fn = compiler::find_function("bl::plain::cos");
  std::vector<int> sin_args;
  for (const compiler::Inst& in : p.insts)
    if (in.op == LOp::Call && in.fn == sin_fn) sin_args.push_back(in.arg[0]);
  std::vector<char> partner(p.insts.size(), 0);
  for (std::size_t i = 0; i < p.insts.size(); ++i) {
    const compiler::Inst& in = p.insts[i];
    partner[i] = in.op == LOp::Call && in.fn == cos_fn &&
                 std::find(sin_args.begin(), sin_args.end(), in.arg[0]) != sin_args.end();
  }
  return partner;
}

double CostModel::critical_path(const compiler::Program& p) const {
  return trace_critical_path(p, nullptr);
}

double CostModel::trace_critical_path(const compiler::Program& p,
                                      std::map<std::string, Breakdown::Calls>* path) const {
  if (fn_lat_ns.empty()) return 0;
  std::vector<double> done(p.insts.size(), 0.0), lat(p.insts.size(), 0.0);
  std::vector<int> from(p.insts.size(), -1);  // the argument the instruction waited for last
  int end = -1;
  for (std::size_t i = 0; i < p.insts.size(); ++i) {
    const compiler::Inst& in = p.insts[i];
    double start = 0;
    for (int a = 0; a < compiler::lop_arity(in); ++a)
      if (in.arg[a] >= 0 && in.op != LOp::InMean && in.op != LOp::InSd && in.op != LOp::InGradX &&
          in.op != LOp::InGradY && done[in.arg[a]] > start) {
        start = done[in.arg[a]];
        from[i] = in.arg[a];
      }
    double l = 0;
    if (in.op == LOp::Call || in.op == LOp::CallStat) {
      const std::string& name = compiler::functions().at(in.fn).cpp;
      const auto fl = fn_lat_ns.find(name);
      const auto ft = fn_ns.find(name);
      if (fl != fn_lat_ns.end() && ft != fn_ns.end() && ft->second > 0)
        l = function_cost(in.fn) * fl->second / ft->second;
      else
        l = function_cost(in.fn);
    } else if (const auto ol = op_lat_ns.find(lop_name(in.op)); ol != op_lat_ns.end()) {
      l = ol->second;
    } else if (in.op == LOp::TexPlain || in.op == LOp::TexStat) {
      l = op_ns.at(lop_name(in.op));
    } else if (in.op == LOp::Neg) {
      l = op_lat_ns.count("sub") ? op_lat_ns.at("sub") : 0;
    }
    lat[i] = l;
    done[i] = start + l;
    if (end < 0 || done[i] > done[end]) end = static_cast<int>(i);
  }
  if (end < 0) return 0;
  if (path)
    for (int i = end; i >= 0; i = from[i]) {
      if (lat[i] <= 0) continue;  // constants, inputs, free ops
      const compiler::Inst& in = p.insts[i];
      Breakdown::Calls& c =
          (*path)[in.op == LOp::Call || in.op == LOp::CallStat ? compiler::functions().at(in.fn).cpp
                                                               : std::string(lop_name(in.op))];
      ++c.count;
      c.ns += lat[i];
    }
  return done[end];
}

std::vector<int> CostModel::live_across(const compiler::Program& p) {
  // The compiler sinks pure arithmetic to its first use, so a value is placed as late as its
  // readers allow: a call stays where it is; any other instruction goes just before the earliest
  // place one of its readers is (a call's index, or the slot of a sunk reader; an output: n).
  // A value is live across call c when it is placed before c and read after c. (Counting in program
  // order instead over-predicted the ripples scenes' plain programs by 1.4-1.7x.)
  const int n = static_cast<int>(p.insts.size());
  auto is_call = [&](int i) { return p.insts[i].op == LOp::Call || p.insts[i].op == LOp::CallStat; };
  std::vector<std::vector<int>> readers(n);
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < compiler::lop_arity(p.insts[i]); ++a)
      if (p.insts[i].arg[a] >= 0) readers[p.insts[i].arg[a]].push_back(i);
  std::vector<char> output(n, 0);
  for (int o : p.outputs)
    if (o >= 0) output[o] = 1;
  // slot[i]: a call's own index; a sunk instruction sits just before slot[i] (n: after every call).
  std::vector<int> slot(n, n);
  for (int i = n - 1; i >= 0; --i) {
    if (is_call(i)) {
      slot[i] = i;
      continue;
    }
    int first = n;  // read by no call-bound reader (an output alone, or dead): after every call
    for (int u : readers[i]) first = std::min(first, slot[u]);
    slot[i] = first;
  }
  // Per value: calls strictly between its placement and its last read. Positions are doubled so a
  // sunk instruction (just before slot s) sits at 2s - 1 and a call c at 2c.
  std::vector<int> delta(2 * n + 2, 0);
  for (int i = 0; i < n; ++i) {
    if (p.insts[i].op == LOp::Const) continue;
    const int def = is_call(i) ? 2 * i : 2 * slot[i] - 1;
    int last = output[i] ? 2 * n : -1;
    for (int u : readers[i]) last = std::max(last, is_call(u) ? 2 * u : 2 * slot[u] - 1);
    if (last <= def + 1) continue;
    ++delta[def + 1];
    --delta[last];
  }
  std::vector<int> live(n, 0);
  int open = 0, at = 0;
  for (int i = 0; i < n; ++i) {
    while (at <= 2 * i) open += delta[at++];
    live[i] = is_call(i) ? open : 0;
  }
  return live;
}

double CostModel::throughput(const compiler::Program& p) const {
  return breakdown_throughput(p, nullptr);
}

CostModel::Breakdown CostModel::breakdown(const compiler::Program& p) const {
  Breakdown b;
  b.throughput_ns = breakdown_throughput(p, &b);
  b.path_ns = trace_critical_path(p, &b.path);
  b.chain_ns = window_ns > 0 ? b.path_ns * std::min(1.0, b.throughput_ns / window_ns) : 0;
  b.cost_ns = floored(latency_bound(b.throughput_ns, b.path_ns, window_ns), floor_ns, floor_norm);
  return b;
}

double CostModel::breakdown_throughput(const compiler::Program& p, Breakdown* b) const {
  double ns = 0;
  if (const auto px = op_ns.find("pixel"); px != op_ns.end()) ns += px->second;
  if (const auto o = op_ns.find("output"); o != op_ns.end()) ns += o->second * p.outputs.size();
  if (b) b->loop_ns = ns;
  const std::vector<int> live = fn_spill_ns.empty() ? std::vector<int>() : live_across(p);
  // Plain sin and cos of one argument: GCC emits one sincosf for the pair, so the cos costs only
  // kSincosExtra of its calibrated price and keeps nothing live of its own.
  const std::vector<char> sincos = sincos_partners(p);
  // f^2 entries beside their f entry on the same (x, sigma): the pair's calibrated extra.
  std::vector<std::array<int, 3>> calls;  // (fn, arg0, arg1) of the two-argument calls
  if (!fn_pair_ns.empty())
    for (const compiler::Inst& in : p.insts)
      if (in.op == LOp::Call) calls.push_back({in.fn, in.arg[0], in.arg[1]});
  auto call = [&](const compiler::Inst& in, double price) {
    ns += price;
    if (!b) return;
    Breakdown::Calls& c = b->functions[compiler::functions().at(in.fn).cpp];
    ++c.count;
    c.ns += price;
  };
  for (std::size_t i = 0; i < p.insts.size(); ++i) {
    const compiler::Inst& in = p.insts[i];
    if (sincos[i]) {
      call(in, kSincosExtra * function_cost(in.fn));
      continue;
    }
    if (in.op == LOp::Call && !calls.empty()) {
      const int sib = square_sibling(in.fn);
      const auto pr = sib < 0 ? fn_pair_ns.end() : fn_pair_ns.find(compiler::functions().at(in.fn).cpp);
      if (pr != fn_pair_ns.end() && std::find(calls.begin(), calls.end(),
                                              std::array<int, 3>{sib, in.arg[0], in.arg[1]}) != calls.end()) {
        call(in, pr->second);
        continue;
      }
    }
    if (in.op == LOp::Call || in.op == LOp::CallStat) {
      call(in, function_cost(in.fn));
      if (!live.empty())
        if (const auto sp = fn_spill_ns.find(compiler::functions().at(in.fn).cpp); sp != fn_spill_ns.end()) {
          const double spill = sp->second * std::min(live[i], kSpillRegs);
          ns += spill;
          if (b) b->spill_ns += spill;
        }
    } else {
      const auto it = op_ns.find(lop_name(in.op));
      if (it == op_ns.end())
        throw std::out_of_range(std::string("cost model (") + machine + ") has no entry for op " +
                                lop_name(in.op) + ": recalibrate (bltune --calibrate)");
      ns += it->second;
      if (b) {
        ++b->ops;
        b->ops_ns += it->second;
      }
    }
  }
  return ns;
}

std::string CostModel::missing() const {
  std::string out;
  for (int o = 0; o <= static_cast<int>(LOp::TexStat); ++o) {
    const LOp op = static_cast<LOp>(o);
    if (op != LOp::Call && op != LOp::CallStat && !op_ns.count(lop_name(op)))
      out += std::string(" ") + lop_name(op);
  }
  if (method == "compiled")
    for (const char* name : {"pixel", "output"})
      if (!op_ns.count(name)) out += std::string(" ") + name;
  for (const compiler::Function& f : compiler::functions())
    if (!fn_ns.count(f.cpp)) out += " " + f.cpp;
  return out;
}

bool CostModel::covers_all() const {
  return missing().empty();
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) {
        std::string m = line.substr(colon + 1);
        m.erase(0, m.find_first_not_of(" \t"));
        return m;
      }
    }
  }
  return "unknown-cpu";
}

CostModel load_cost_model(const std::string& path, const std::string& machine) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cost model: cannot read " + path);
  nlohmann::json j;
  try {
    in >> j;
  } catch (const std::exception& e) {
    throw std::runtime_error("cost model: " + path + " is not valid JSON: " + e.what());
  }
  if (!j.contains("machines") || !j["machines"].contains(machine))
    throw std::runtime_error("cost model: " + path + " has no calibration for machine '" + machine + "'");
  const nlohmann::json& m = j["machines"][machine];
  CostModel cm;
  cm.machine = machine;
  cm.method = m.value("method", std::string("evaluator"));  // files from before compiled calibration
  cm.op_ns = m.at("ops").get<std::map<std::string, double>>();
  cm.fn_ns = m.at("functions").get<std::map<std::string, double>>();
  cm.window_ns = m.value("window_ns", 0.0);
  cm.floor_ns = m.value("floor_ns", 0.0);
  cm.floor_norm = m.value("floor_norm", 0.0);
  cm.window_kernel_ns = m.value("window_kernel_ns", cm.window_ns);
  cm.window_fit_programs = m.value("window_fit_programs", 0);
  cm.window_fit_source = m.value("window_fit_source", std::string());
  cm.latency_norm = m.value("latency_norm", 0.0);
  cm.kernels = m.value("kernels", 0);
  cm.jit_flags = m.value("jit_flags", std::string());
  if (m.contains("op_latency")) cm.op_lat_ns = m.at("op_latency").get<std::map<std::string, double>>();
  if (m.contains("function_latency"))
    cm.fn_lat_ns = m.at("function_latency").get<std::map<std::string, double>>();
  if (m.contains("function_bands"))
    cm.fn_band_ns = m.at("function_bands").get<std::map<std::string, std::vector<double>>>();
  if (m.contains("function_spill"))
    cm.fn_spill_ns = m.at("function_spill").get<std::map<std::string, double>>();
  if (m.contains("function_pair")) cm.fn_pair_ns = m.at("function_pair").get<std::map<std::string, double>>();
  return cm;
}

void save_cost_model(const std::string& path, const CostModel& m) {
  nlohmann::json j = nlohmann::json::object();
  if (std::ifstream in(path); in) {
    try {
      in >> j;
    } catch (const std::exception&) {
      j = nlohmann::json::object();  // a corrupt file is replaced, not merged
    }
  }
  j["machines"][m.machine] = {{"method", m.method},
                              {"ops", m.op_ns},
                              {"functions", m.fn_ns},
                              {"function_bands", m.fn_band_ns},
                              {"op_latency", m.op_lat_ns},
                              {"function_latency", m.fn_lat_ns},
                              {"window_ns", m.window_ns},
                              {"floor_ns", m.floor_ns},
                              {"floor_norm", m.floor_norm},
                              {"window_kernel_ns", m.window_kernel_ns},
                              {"window_fit_programs", m.window_fit_programs},
                              {"window_fit_source", m.window_fit_source},
                              {"latency_norm", m.latency_norm},
                              {"kernels", m.kernels},
                              {"jit_flags", m.jit_flags},
                              {"function_spill", m.fn_spill_ns},
                              {"function_pair", m.fn_pair_ns}};
  const std::filesystem::path p(path);
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
  const std::string tmp = path + ".tmp";
  std::ofstream(tmp) << j.dump(1) << "\n";
  std::filesystem::rename(tmp, path);
}

}  // namespace bl::tuner
