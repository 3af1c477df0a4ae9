// The compiled-code calibration: one translation unit of loop kernels, compiled with -O3 by bl::jit.
// A kernel runs one operation over n pixels' inputs (struct of arrays, the calibration inputs of
// calibrate.cpp); an op's or a function's cost is its kernel's time per pixel minus that of a kernel
// reading the same inputs and doing nothing else (for ops, 16 chained copies per pixel, / 16).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <sstream>

#include "compiler/functions.hpp"
#include "texture/texture.hpp"
#include "tuner/calibrate.hpp"

namespace bl::tuner {

namespace {

using Kernel = void (*)(int, const float* const*, float*);

// Input arrays, as calibrate.cpp's base program: 0 mean0 (x, scaled per band), 1 sd0, 2 mean1,
// 3 sd1, 4 small value in [0, 0.3], 5 var0 = sd0^2.
constexpr int kArrays = 6;

std::string arg_list(const std::vector<int>& a) {
  std::string s;
  for (std::size_t j = 0; j < a.size(); ++j)
    s += (j ? ", " : "") + std::string("a[") + std::to_string(a[j]) + "][j]";
  return s;
}

const char* kOps[][2] = {{"add", "t = t + b"},
                         {"sub", "t = t - b"},
                         {"mul", "t = t * b"},
                         {"div", "t = t / b"},
                         {"min", "t = t < b ? t : b"},
                         {"max", "t = t < b ? b : t"},
                         {"less", "t = t < b ? 1.0f : 0.0f"},
                         {"sqrt", "t = std::sqrt(t)"},
                         {"nonneg", "t = t > 0.0f ? t : 0.0f"}};

std::string source(const std::vector<int>& fns) {
  std::ostringstream os;
  os << "// bandlimit cost-model calibration kernels (runtime/tuner/calibrate_compiled.cpp)\n"
     << "#include <cmath>\n#include <bandlimit/table.hpp>\n#include <bandlimit/rules_bivariate.hpp>\n"
     << "#include <bandlimit/rules_mode.hpp>\n#include <bandlimit/rules_clamped.hpp>\n"
     << "#include <texture/sample.hpp>\n\n"
     << "static const bl::texture::Texture* g_tex = nullptr;\n"
     << "extern \"C\" void bl_set_texture(const void* t) { g_tex = static_cast<const "
        "bl::texture::Texture*>(t); }\n";
  // Base kernels: read k inputs, write their sum.
  for (int k = 1; k <= 6; ++k) {
    os << "extern \"C\" void bl_base" << k << "(int n, const float* const* a, float* out) {\n"
       << "  for (int j = 0; j < n; ++j) out[j] = ";
    const auto args = calibration_args(k, false);
    for (int i = 0; i < k; ++i) os << (i ? " + " : "") << "a[" << args[i] << "][j]";
    os << ";\n}\n";
  }
  for (const auto& op : kOps) {
    os << "extern \"C\" void bl_op_" << op[0] << "(int n, const float* const* a, float* out) {\n"
       << "  for (int j = 0; j < n; ++j) {\n    float t = a[0][j];\n    const float b = a[2][j];\n    "
          "(void)b;\n";
    for (int c = 0; c < 16; ++c) os << "    " << op[1] << ";\n";
    os << "    out[j] = t;\n  }\n}\n";
  }
  // Latency kernels: the result feeds the next pixel's first argument (x + t * 0, which keeps x
  // and cannot be folded: t may be NaN or inf), so the pixels run one after another.
  os << "extern \"C\" void bl_latbase(int n, const float* const* a, float* out) {\n"
     << "  float t = 0.0f;\n  for (int j = 0; j < n; ++j) t = a[0][j] + t * 0.0f;\n  out[0] = t;\n}\n";
  for (const auto& op : kOps) {
    os << "extern \"C\" void bl_lat_" << op[0] << "(int n, const float* const* a, float* out) {\n"
       << "  float t = 0.0f;\n  for (int j = 0; j < n; ++j) {\n    t = a[0][j] + t * 0.0f;\n"
       << "    const float b = a[2][j];\n    (void)b;\n";
    for (int c = 0; c < 16; ++c) os << "    " << op[1] << ";\n";
    os << "  }\n  out[0] = t;\n}\n";
  }
  // The out-of-order window: 8 dependent sin calls per pixel, pixels independent, against the
  // same calls fully independent (throughput) and fully chained (latency).
  os << "extern \"C\" void bl_win_thr(int n, const float* const* a, float* out) {\n"
     << "  for (int j = 0; j < n; ++j) out[j] = bl::plain::sin(a[0][j]);\n}\n"
     << "extern \"C\" void bl_win_lat(int n, const float* const* a, float* out) {\n"
     << "  float t = 0.0f;\n  for (int j = 0; j < n; ++j) t = bl::plain::sin(a[0][j] + t * 0.0f);\n  out[0] "
        "= t;\n}\n"
     << "extern \"C\" void bl_win_chain(int n, const float* const* a, float* out) {\n"
     << "  for (int j = 0; j < n; ++j) {\n    float t = a[0][j];\n"
     << "    for (int c = 0; c < 8; ++c) t = bl::plain::sin(t + a[2][j]);\n    out[j] = t;\n  }\n}\n";
  os << "extern \"C\" void bl_op_tex_plain(int n, const float* const* a, float* out) {\n"
     << "  for (int j = 0; j < n; ++j) out[j] = bl::texture::sample_plain(*g_tex, a[0][j], a[2][j], 0);\n}\n"
     << "extern \"C\" void bl_op_tex_stat(int n, const float* const* a, float* out) {\n"
     << "  for (int j = 0; j < n; ++j) {\n"
     << "    const bl::stat<float> s = bl::texture::sample_stat(*g_tex, a[0][j], a[2][j], a[1][j], a[3][j], "
        "0);\n"
     << "    out[j] = s.mean + s.var;\n  }\n}\n";
  const auto& all = compiler::functions();
  for (int f : fns) {
    const compiler::Function& F = all[f];
    os << "extern \"C\" void bl_fn" << f << "(int n, const float* const* a, float* out) {  // " << F.cpp
       << "\n"
       << "  for (int j = 0; j < n; ++j) {\n";
    if (F.stat)
      os << "    const bl::stat<float> r = " << F.cpp << "(" << arg_list(calibration_args(F.arity, true))
         << ");\n"
         << "    out[j] = r.mean + r.var;\n";
    else
      os << "    out[j] = " << F.cpp << "(" << arg_list(calibration_args(F.arity, false)) << ");\n";
    os << "  }\n}\n";
    std::vector<int> args = calibration_args(F.arity, F.stat);
    std::string chained = "a[" + std::to_string(args[0]) + "][j] + t * 0.0f";
    std::string rest;
    for (std::size_t k = 1; k < args.size(); ++k) rest += ", a[" + std::to_string(args[k]) + "][j]";
    os << "extern \"C\" void bl_lat" << f << "(int n, const float* const* a, float* out) {\n"
       << "  float t = 0.0f;\n  for (int j = 0; j < n; ++j) {\n";
    if (F.stat)
      os << "    const bl::stat<float> r = " << F.cpp << "(" << chained << rest
         << ");\n    t = r.mean + r.var;\n";
    else
      os << "    t = " << F.cpp << "(" << chained << rest << ");\n";
    os << "  }\n  out[0] = t;\n}\n";
  }
  return os.str();
}

// The texture calibrate.cpp times lookups on (512x512 RGB).
const texture::Texture& kernel_texture() {
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

struct Arrays {
  std::vector<std::vector<float>> v;
  std::vector<const float*> ptr;
};

// sigma_scale > 0: the sds (arrays 1, 3) are sigma_scale x U[0.5, 1.5] instead of U[0.01, 0.5].
Arrays make_arrays(int n, double magnitude, double sigma_scale = 0) {
  Arrays in;
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<float> x(0.05f, 3.0f), s(0.01f, 0.5f), small(0.0f, 0.3f), half(0.5f, 1.5f),
      decade(0.5f, 2.0f);
  auto sd = [&] { return sigma_scale > 0 ? static_cast<float>(sigma_scale * half(rng)) : s(rng); };
  in.v.assign(kArrays, std::vector<float>(n));
  for (int i = 0; i < n; ++i) {
    in.v[0][i] = static_cast<float>(decade(rng) * magnitude);
    in.v[1][i] = sd();
    in.v[2][i] = x(rng);
    in.v[3][i] = sd();
    in.v[4][i] = small(rng);
    in.v[5][i] = in.v[1][i] * in.v[1][i];
  }
  for (auto& a : in.v) in.ptr.push_back(a.data());
  return in;
}

double time_kernel(Kernel k, const Arrays& in, std::vector<float>& out, const CalibrationOptions& opt) {
  const int n = static_cast<int>(out.size());
  k(n, in.ptr.data(), out.data());  // warm-up
  double best = 1e300;
  for (int t = 0; t < opt.trials; ++t) {
    int reps = 0;
    double ms = 0;
    const auto t0 = std::chrono::steady_clock::now();
    do {
      k(n, in.ptr.data(), out.data());
      ++reps;
      ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    } while (ms < opt.min_ms);
    best = std::min(best, ms * 1e6 / (static_cast<double>(reps) * n));
  }
  return best;
}

}  // namespace

CostModel calibrate_compiled(const CalibrationOptions& opt,
                             const std::function<void(const std::string&, double)>& progress) {
  CostModel m;
  m.machine = cpu_model();
  m.method = "compiled";
  auto wanted = [&](const std::string& name) {
    return opt.only.empty() || name.find(opt.only) != std::string::npos;
  };
  const auto& all = compiler::functions();
  std::vector<int> fns;
  for (std::size_t f = 0; f < all.size(); ++f)
    if (wanted(all[f].cpp)) fns.push_back(static_cast<int>(f));
  const auto lib = jit::compile(source(fns), opt.jit);
  reinterpret_cast<void (*)(const void*)>(lib->symbol("bl_set_texture"))(&kernel_texture());
  auto kernel = [&](const std::string& sym) { return reinterpret_cast<Kernel>(lib->symbol(sym)); };
  std::vector<float> out(opt.pixels);
  std::vector<Arrays> bands, joint;
  for (int b = 0; b < CostModel::kBands; ++b) {
    bands.push_back(make_arrays(opt.pixels, CostModel::band_magnitude(b)));
    for (int sb = 0; sb < CostModel::kSigmaBands; ++sb)
      joint.push_back(make_arrays(opt.pixels, CostModel::band_magnitude(b), CostModel::sigma_band_scale(sb)));
  }
  const Arrays& in = bands[0];
  // Many short windows, the fastest kept: on a loaded machine a 0.25 ms window often runs
  // undisturbed where a 4 ms one rarely does. Band timings (7 or 28 per function) use fewer.
  CalibrationOptions main_opt = opt, band_opt = opt;
  main_opt.min_ms = band_opt.min_ms = opt.min_ms / 16;
  main_opt.trials = opt.trials * 5;
  band_opt.trials = opt.trials * 3;
  double base[7] = {0};
  for (int k = 1; k <= 6; ++k)
    base[k] = time_kernel(kernel("bl_base" + std::to_string(k)), in, out, main_opt);
  auto record = [&](const std::string& name, double ns, bool fn) {
    ns = std::max(0.01, ns);
    (fn ? m.fn_ns : m.op_ns)[name] = ns;
    if (progress) progress(name, ns);
  };
  // Per-pixel overhead (the loop, one input read, one output written) and the inputs.
  if (wanted("pixel")) record("pixel", base[1], false);
  const double input_ns = (base[6] - base[1]) / 5;
  for (const char* name : {"in_mean", "in_sd", "in_grad_x", "in_grad_y"})
    if (wanted(name)) record(name, input_ns, false);
  // Constants and pair fields are registers in compiled code.
  for (const char* name : {"const", "mean", "var"})
    if (wanted(name)) record(name, 0.01, false);
  for (const auto& op : kOps)
    if (wanted(op[0]))
      record(op[0], (time_kernel(kernel(std::string("bl_op_") + op[0]), in, out, main_opt) - base[1]) / 16,
             false);
  const double lat_base = time_kernel(kernel("bl_latbase"), in, out, main_opt);
  {
    // Pixels in flight = window / (throughput cost per pixel): from time = L x T / window when the
    // chain binds (T = 8 thr, L = 8 lat per pixel).
    const double thr = std::max(0.01, time_kernel(kernel("bl_win_thr"), in, out, main_opt) - base[1]);
    const double lat = std::max(0.01, time_kernel(kernel("bl_win_lat"), in, out, main_opt) - lat_base);
    const double chain = time_kernel(kernel("bl_win_chain"), in, out, main_opt) - base[2];
    m.window_ns = chain > 8 * thr * 1.05 ? (8 * lat) * (8 * thr) / chain : 1e9;
    if (progress) progress("window", m.window_ns);
  }
  for (const auto& op : kOps)
    if (wanted(op[0]))
      m.op_lat_ns[op[0]] = std::max(
          0.01, (time_kernel(kernel(std::string("bl_lat_") + op[0]), in, out, main_opt) - lat_base) / 16);
  // Negation folds into its user (a - b for -b + a) in compiled code: costed as a subtraction.
  if (wanted("neg") && m.op_ns.count("sub")) record("neg", m.op_ns["sub"], false);
  if (wanted("tex_plain"))
    record("tex_plain", time_kernel(kernel("bl_op_tex_plain"), in, out, main_opt) - base[2], false);
  if (wanted("tex_stat"))
    record("tex_stat", time_kernel(kernel("bl_op_tex_stat"), in, out, main_opt) - base[4], false);
  for (int f : fns) {
    const compiler::Function& F = all[f];
    const Kernel k = kernel("bl_fn" + std::to_string(f));
    const double b0 = base[F.arity];
    record(F.cpp, time_kernel(k, in, out, main_opt) - b0, true);
    m.fn_lat_ns[F.cpp] =
        std::max(0.01, time_kernel(kernel("bl_lat" + std::to_string(f)), in, out, main_opt) - lat_base);
    if (CostModel::atomic_of(F.cpp).empty()) continue;
    std::vector<double> per;
    if (F.arity == 2 && !F.stat) {  // kernel entry f(x, sigma): every (|x|, sigma) band pair
      for (const Arrays& a : joint) per.push_back(std::max(0.01, time_kernel(k, a, out, band_opt) - b0));
    } else {
      per.push_back(m.fn_ns[F.cpp]);
      for (int b = 1; b < CostModel::kBands; ++b)
        per.push_back(std::max(0.01, time_kernel(k, bands[b], out, band_opt) - b0));
    }
    m.fn_band_ns[F.cpp] = per;
  }
  return m;
}

}  // namespace bl::tuner
