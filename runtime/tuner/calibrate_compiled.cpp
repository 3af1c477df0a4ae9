// The compiled-code calibration: one translation unit of loop kernels, compiled with -O3 by bl::jit.
// Every kernel has the shape of a real program's pixel loop (jit::batch_source's bl_run): one pixel
// per iteration, scalar, its inputs read from struct-of-arrays slots and its results stored to
// output arrays. The pixel-loop kernels give the per-pixel overhead, the cost per input read and per
// output stored; an op's cost is its kernel's time (16 chained copies per pixel) minus that loop,
// / 16; a function's is its kernel's time (one call per pixel) minus the loop and its extra inputs.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <random>
#include <set>
#include <sstream>

#include "compiler/functions.hpp"
#include "texture/texture.hpp"
#include "tuner/calibrate.hpp"

namespace bl::tuner {

namespace {

using Kernel = void (*)(int, const float* const*, float* const*);

// Input arrays, as calibrate.cpp's base program: 0 mean0 (x, scaled per band), 1 sd0, 2 mean1,
// 3 sd1, 4 small value in [0, 0.3], 5 var0 = sd0^2.
constexpr int kArrays = 6;
constexpr int kOutputs = 6;    // output arrays of the pixel-loop kernels
constexpr int kScanline = 64;  // pixels per run of ordered inputs (make_arrays)

// (inputs read, outputs written) of the kernels that time loads and stores next to a sin call:
// (1, 1) is the call alone, (1, 6) adds 5 stores, (6, 6) adds 5 loads to that.
constexpr int kIoKernels[][2] = {{1, 1}, {1, kOutputs}, {kArrays, kOutputs}};

std::string arg_list(const std::vector<int>& a) {
  std::string s;
  for (std::size_t j = 0; j < a.size(); ++j)
    s += (j ? ", " : "") + std::string("a[") + std::to_string(a[j]) + "][j]";
  return s;
}

int distinct(const std::vector<int>& a) {
  return static_cast<int>(std::set<int>(a.begin(), a.end()).size());
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

// Every kernel starts on a 64-byte boundary (BL_KERNEL), so where its loop falls against cache lines
// and fetch blocks depends on its own code only, not on the size of the kernels before it in this one
// translation unit: without it, a change to one entry moved others' prices (box fract's unchanged
// pixel-sized path 0.93 -> 1.07 ns between two calibrations of tables that differ in other entries;
// box square 1.09 -> 1.53 when its own out-of-line part grew).
// A kernel: `body` runs once per pixel j inside the scalar pixel loop.
void kernel_def(std::ostringstream& os, const std::string& name, const std::string& body) {
  os << "extern \"C\" BL_KERNEL void " << name << "(int n, const float* const* a, float* const* out) {\n"
     << "  for (int j = 0; j < n; ++j) {\n    BL_SCALAR;\n"
     << body << "  }\n}\n";
}

// A latency kernel: each pixel's result feeds the next pixel's first argument (x + t * 0, which keeps
// x and cannot be folded: t may be NaN or inf), so the pixels run one after another.
void latency_def(std::ostringstream& os, const std::string& name, const std::string& body) {
  os << "extern \"C\" BL_KERNEL void " << name << "(int n, const float* const* a, float* const* out) {\n"
     << "  float t = 0.0f;\n  for (int j = 0; j < n; ++j) {\n"
     << body << "  }\n  out[0][0] = t;\n}\n";
}

// kSpillRegs values computed before a call, pinned in registers there (the empty asm), and read after
// it: what a call costs inside a program that keeps its pairs live across it.
constexpr int kSpillVals = CostModel::kSpillRegs;
std::string spill_pre() {
  std::string s;
  for (int v = 0; v < kSpillVals; ++v) {
    const std::string V = "v" + std::to_string(v);
    s += "    float " + V + " = a[2][j] * " + std::to_string(1.0 + 0.01 * v) + "f + a[4][j];\n";
    s += "    __asm__ volatile(\"\" : \"+x\"(" + V + "));\n";
  }
  return s;
}
std::string spill_post(const std::string& result) {
  std::string s = "    float acc = " + result + ";\n";
  for (int v = 0; v < kSpillVals; ++v) s += "    acc = acc * 0.5f + v" + std::to_string(v) + ";\n";
  return s + "    out[0][j] = acc;\n";
}

std::string source(const std::vector<int>& fns) {
  std::ostringstream os;
  os << "// bandlimit cost-model calibration kernels (runtime/tuner/calibrate_compiled.cpp)\n"
     << "#include <cmath>\n#include <bandlimit/table.hpp>\n#include <bandlimit/rules_bivariate.hpp>\n"
     << "#include <bandlimit/rules_mode.hpp>\n#include <bandlimit/rules_clamped.hpp>\n"
     << "#include <texture/sample.hpp>\n\n"
     // A real program's pixel loop stays scalar: its calls and branches stop the vectorizer. A
     // kernel of one add or one straight-line plain function would run 4 pixels per instruction and
     // cost a quarter of what it costs in a program; this empty statement keeps every loop scalar.
     << "#define BL_SCALAR __asm__ volatile(\"\")\n"
     << "#define BL_KERNEL __attribute__((aligned(64)))\n"
     << "static const bl::texture::Texture* g_tex = nullptr;\n"
     << "extern \"C\" void bl_set_texture(const void* t) { g_tex = static_cast<const "
        "bl::texture::Texture*>(t); }\n";
  // The bare pixel loop (one load, one store), and loads and stores next to a sin call (a
  // program's work, with which they overlap).
  kernel_def(os, "bl_io1_1", "    out[0][j] = a[0][j];\n");
  for (const auto& io : kIoKernels) {
    std::string busy = "    out[0][j] = bl::plain::sin(a[0][j]);\n";
    for (int k = 1; k < io[1]; ++k)
      busy += "    out[" + std::to_string(k) + "][j] = a[" + std::to_string(k % io[0]) + "][j];\n";
    kernel_def(os, "bl_busy" + std::to_string(io[0]) + "_" + std::to_string(io[1]), busy);
  }
  for (const auto& op : kOps) {
    std::string body = "    float t = a[0][j];\n    const float b = a[2][j];\n    (void)b;\n";
    for (int c = 0; c < 16; ++c) body += "    " + std::string(op[1]) + ";\n";
    kernel_def(os, std::string("bl_op_") + op[0], body + "    out[0][j] = t;\n");
  }
  latency_def(os, "bl_latbase", "    t = a[0][j] + t * 0.0f;\n");
  for (const auto& op : kOps) {
    std::string body = "    t = a[0][j] + t * 0.0f;\n    const float b = a[2][j];\n    (void)b;\n";
    for (int c = 0; c < 16; ++c) body += "    " + std::string(op[1]) + ";\n";
    latency_def(os, std::string("bl_lat_") + op[0], body);
  }
  // The out-of-order window: 8 dependent sin calls per pixel, pixels independent, against the
  // same calls fully independent (throughput) and fully chained (latency).
  kernel_def(os, "bl_win_thr", "    out[0][j] = bl::plain::sin(a[0][j]);\n");
  latency_def(os, "bl_win_lat", "    t = bl::plain::sin(a[0][j] + t * 0.0f);\n");
  kernel_def(os, "bl_win_chain",
             "    float t = a[0][j];\n    for (int c = 0; c < 8; ++c) t = bl::plain::sin(t + a[2][j]);\n"
             "    out[0][j] = t;\n");
  kernel_def(os, "bl_sp_base", spill_pre() + spill_post("a[0][j]"));
  kernel_def(os, "bl_op_tex_plain",
             "    out[0][j] = bl::texture::sample_plain(*g_tex, a[0][j], a[2][j], 0);\n");
  kernel_def(os, "bl_op_tex_stat",
             "    const bl::stat<float> s = bl::texture::sample_stat(*g_tex, a[0][j], a[2][j], a[1][j], "
             "a[3][j], 0);\n    out[0][j] = s.mean + s.var;\n");
  const auto& all = compiler::functions();
  for (int f : fns) {
    const compiler::Function& F = all[f];
    const std::vector<int> args = calibration_args(F);
    os << "// " << F.cpp << "\n";
    if (F.stat)
      kernel_def(os, "bl_fn" + std::to_string(f),
                 "    const bl::stat<float> r = " + F.cpp + "(" + arg_list(args) +
                     ");\n    out[0][j] = r.mean + r.var;\n");
    else
      kernel_def(os, "bl_fn" + std::to_string(f), "    out[0][j] = " + F.cpp + "(" + arg_list(args) + ");\n");
    if (F.stat)
      kernel_def(os, "bl_sp" + std::to_string(f),
                 spill_pre() + "    const bl::stat<float> r = " + F.cpp + "(" + arg_list(args) + ");\n" +
                     spill_post("r.mean + r.var"));
    else
      kernel_def(
          os, "bl_sp" + std::to_string(f),
          spill_pre() + "    const float r = " + F.cpp + "(" + arg_list(args) + ");\n" + spill_post("r"));
    // An f^2 entry beside its f entry on the same arguments (a smoothed node's mean and variance).
    if (const int sib = CostModel::square_sibling(f); sib >= 0 && std::count(fns.begin(), fns.end(), sib))
      kernel_def(os, "bl_pair" + std::to_string(f),
                 "    out[0][j] = " + all[sib].cpp + "(" + arg_list(args) + ") + " + F.cpp + "(" +
                     arg_list(args) + ");\n");
    // Latency through x and, for two or more arguments, through the second one (a kernel entry's
    // sigma: in a program the sd of a nested node depends on the node before it).
    for (std::size_t via = 0; via < std::min<std::size_t>(2, args.size()); ++via) {
      std::string chained;
      for (std::size_t k = 0; k < args.size(); ++k)
        chained += (k ? ", a[" : "a[") + std::to_string(args[k]) + "][j]" + (k == via ? " + t * 0.0f" : "");
      const std::string name = "bl_lat" + std::to_string(f) + (via ? "_1" : "");
      if (F.stat)
        latency_def(
            os, name,
            "    const bl::stat<float> r = " + F.cpp + "(" + chained + ");\n    t = r.mean + r.var;\n");
      else
        latency_def(os, name, "    t = " + F.cpp + "(" + chained + ");\n");
    }
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

// scanlines: see below. sigma_scale > 0: the sds (arrays 1, 3) are sigma_scale x U[0.5, 1.5] instead of
// U[0.01, 0.5].
Arrays make_arrays(int n, double magnitude, double sigma_scale, bool scanlines) {
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
  }
  // Scanlines: a program's neighbouring pixels have neighbouring inputs, so its branches (regimes,
  // pieces, signs) mostly repeat from one pixel to the next. Each run of kScanline values is sorted
  // (the same distribution, ordered as along an image row): i.i.d. inputs would mispredict every
  // data-dependent branch half the time, which a rendered frame does not.
  if (scanlines)
    for (int a = 0; a < 5; ++a)
      for (int i = 0; i < n; i += kScanline)
        std::sort(in.v[a].begin() + i, in.v[a].begin() + std::min(n, i + kScanline));
  for (int i = 0; i < n; ++i) in.v[5][i] = in.v[1][i] * in.v[1][i];
  for (auto& a : in.v) in.ptr.push_back(a.data());
  return in;
}

// The output arrays a kernel writes (kOutputs of n floats).
struct Outputs {
  std::vector<std::vector<float>> v;
  std::vector<float*> ptr;
  explicit Outputs(int n) : v(kOutputs, std::vector<float>(n)) {
    for (auto& o : v) ptr.push_back(o.data());
  }
  int size() const { return static_cast<int>(v[0].size()); }
};

// CPU time of the calling thread in ms, as render::time_program measures programs: time the thread
// was descheduled (other jobs on a shared machine) does not count.
double thread_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

double time_kernel(Kernel k, const Arrays& in, Outputs& out, const CalibrationOptions& opt) {
  const int n = out.size();
  auto run = [&](int reps) {
    const double t0 = thread_ms();
    for (int r = 0; r < reps; ++r) k(n, in.ptr.data(), out.ptr.data());
    return thread_ms() - t0;
  };
  // Warm-up, which also sizes a window: the clock is read once per window, not once per call (a
  // read costs about as much as a call of a cheap kernel).
  const double once = std::max(1e-6, run(1));
  const int reps = std::max(1, static_cast<int>(std::ceil(opt.min_ms / once)));
  double best = 1e300;
  for (int t = 0; t < opt.trials; ++t)
    best = std::min(best, run(reps) * 1e6 / (static_cast<double>(reps) * n));
  return best;
}

}  // namespace

CostModel calibrate_compiled(const CalibrationOptions& opt,
                             const std::function<void(const std::string&, double)>& progress) {
  CostModel m;
  m.machine = cpu_model();
  m.method = "compiled";
  m.jit_flags = jit::flags_text(opt.jit);
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
  Outputs out(opt.pixels);
  std::vector<Arrays> bands, joint;
  for (int b = 0; b < CostModel::kBands; ++b) {
    bands.push_back(make_arrays(opt.pixels, CostModel::band_magnitude(b), 0, opt.scanlines));
    for (int sb = 0; sb < CostModel::kSigmaBands; ++sb)
      joint.push_back(make_arrays(opt.pixels, CostModel::band_magnitude(b), CostModel::sigma_band_scale(sb),
                                  opt.scanlines));
  }
  const Arrays& in = bands[0];
  // Many short windows, the fastest kept: on a loaded machine a 0.25 ms window often runs
  // undisturbed where a 4 ms one rarely does. Band timings (7 or 28 per function) use fewer.
  CalibrationOptions main_opt = opt, band_opt = opt;
  main_opt.min_ms = band_opt.min_ms = opt.min_ms / 16;
  main_opt.trials = opt.trials * 5;
  band_opt.trials = opt.trials * 3;
  auto time = [&](const std::string& sym, const Arrays& a, const CalibrationOptions& o) {
    return time_kernel(kernel(sym), a, out, o);
  };
  // The pixel loop. Alone, a load or a store is what the loop waits for (~0.36 ns a store); next to
  // a program's work it overlaps with it (~0.04 ns): the extra loads and stores are timed next to a
  // sin call, the bare loop (one load, one store) alone.
  const double loop = time("bl_io1_1", in, main_opt);
  const double busy = time("bl_busy1_1", in, main_opt);
  const double stores = time("bl_busy1_" + std::to_string(kOutputs), in, main_opt);
  const double loads =
      time("bl_busy" + std::to_string(kArrays) + "_" + std::to_string(kOutputs), in, main_opt);
  const double output_ns = std::max(0.01, (stores - busy) / (kOutputs - 1));
  const double input_ns = std::max(0.01, (loads - stores) / (kArrays - 1));
  // A kernel reading `inputs` arrays and storing one result, less the loop and its inputs.
  auto net = [&](double ns, int inputs) { return std::max(0.01, ns - loop - (inputs - 1) * input_ns); };
  auto record = [&](const std::string& name, double ns, bool fn) {
    ns = std::max(0.01, ns);
    (fn ? m.fn_ns : m.op_ns)[name] = ns;
    if (progress) progress(name, ns);
  };
  // The per-pixel overhead: the loop with one input and one output; the program's inputs beyond the
  // first and outputs beyond the first are in_* and "output" costs (CostModel::throughput).
  if (wanted("pixel")) record("pixel", loop - input_ns - output_ns, false);
  if (wanted("output")) record("output", output_ns, false);
  for (const char* name : {"in_mean", "in_sd", "in_grad_x", "in_grad_y"})
    if (wanted(name)) record(name, input_ns, false);
  // Constants and pair fields are registers in compiled code.
  for (const char* name : {"const", "mean", "var"})
    if (wanted(name)) record(name, 0.01, false);
  for (const auto& op : kOps)
    if (wanted(op[0])) record(op[0], net(time(std::string("bl_op_") + op[0], in, main_opt), 2) / 16, false);
  const double lat_base = time("bl_latbase", in, main_opt);
  {
    // Pixels in flight = window / (throughput cost per pixel): the window at which the latency
    // bound prices the chained kernel as timed (T = 8 thr, L = 8 lat per pixel).
    const double thr = net(time("bl_win_thr", in, main_opt), 1);
    const double lat = std::max(0.01, time("bl_win_lat", in, main_opt) - lat_base);
    const double chain = net(time("bl_win_chain", in, main_opt), 2);
    m.window_ns = CostModel::window_for(8 * thr, 8 * lat, chain);
    m.window_kernel_ns = m.window_ns;
    if (progress) progress("window", m.window_ns);
  }
  for (const auto& op : kOps)
    if (wanted(op[0]))
      m.op_lat_ns[op[0]] =
          std::max(0.01, (time(std::string("bl_lat_") + op[0], in, main_opt) - lat_base) / 16);
  // Negation folds into its user (a - b for -b + a) in compiled code: costed as a subtraction.
  if (wanted("neg") && m.op_ns.count("sub")) record("neg", m.op_ns["sub"], false);
  if (wanted("tex_plain")) record("tex_plain", net(time("bl_op_tex_plain", in, main_opt), 2), false);
  if (wanted("tex_stat")) record("tex_stat", net(time("bl_op_tex_stat", in, main_opt), 4), false);
  // The values alone (no call), against which each function's spill kernel is read.
  const double sp_base = time("bl_sp_base", in, main_opt);
  for (int f : fns) {
    const compiler::Function& F = all[f];
    const std::string sym = "bl_fn" + std::to_string(f);
    const std::vector<int> args = calibration_args(F);
    const int inputs = distinct(args);
    const double alone = time(sym, in, main_opt);
    record(F.cpp, net(alone, inputs), true);
    // Spill: the call among kSpillVals live values, less the call alone and the values alone.
    const double among = time("bl_sp" + std::to_string(f), in, main_opt);
    m.fn_spill_ns[F.cpp] = std::max(0.0, (among - alone - (sp_base - loop)) / kSpillVals);
    double lat = time("bl_lat" + std::to_string(f), in, main_opt);
    if (args.size() >= 2) lat = std::max(lat, time("bl_lat" + std::to_string(f) + "_1", in, main_opt));
    m.fn_lat_ns[F.cpp] = std::max(0.01, lat - lat_base);
    // The pair's extra over its f entry alone (both kernels read the same inputs).
    if (const int sib = CostModel::square_sibling(f); sib >= 0 && std::count(fns.begin(), fns.end(), sib)) {
      const double pair = time("bl_pair" + std::to_string(f), in, main_opt);
      const double sib_alone = time("bl_fn" + std::to_string(sib), in, main_opt);
      // At most the entry alone: a pair that shares nothing costs two calls, and a larger reading
      // is this machine's noise.
      m.fn_pair_ns[F.cpp] = std::clamp(pair - sib_alone, 0.01, m.fn_ns[F.cpp]);
    }
    if (CostModel::atomic_of(F.cpp).empty()) continue;
    std::vector<double> per;
    if (CostModel::sigma_entry(F)) {  // kernel or stat entry f(x, sigma): every (|x|, sigma) band pair
      for (const Arrays& a : joint) per.push_back(net(time(sym, a, band_opt), inputs));
    } else {
      per.push_back(m.fn_ns[F.cpp]);
      for (int b = 1; b < CostModel::kBands; ++b) per.push_back(net(time(sym, bands[b], band_opt), inputs));
    }
    m.fn_band_ns[F.cpp] = per;
  }
  return m;
}

}  // namespace bl::tuner
