// The tuner's time axis: a per-instruction cost model. Every LOp and every generated function (by
// its C++ name) has a cost in ns per pixel, calibrated on this machine by timing compiled code (the
// emitted C++ built with -O3 by bl::jit; the batch evaluator only when no compiler exists), see
// calibrate.hpp. Functions of an atomic's argument x (plain and kernel entries) also have a cost per
// magnitude band of |x| (periodic and trigonometric atomics cost 10-30x more at |x| ~ 1e6 than at 1:
// argument reduction); a scene's observed |x| distribution per atomic (band_share, from
// magnitude_profile) weights them. cost(Program) is a sum over instructions plus a per-pixel
// overhead, so the search is deterministic given the model file and the scene, and the file is keyed
// by machine (the CPU model string) so that one checkout can carry calibrations of several machines.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "compiler/lir.hpp"

namespace bl::tuner {

struct CostModel {
  // Magnitude bands of |x|, one per decade: band k >= 1 is [10^(k-1/2), 10^(k+1/2)), band 0 below
  // 10^(1/2), band 6 everything from 10^5.5 on; calibrated at |x| = 10^k x U[0.5, 2].
  static constexpr int kBands = 7;
  static int band_of(double abs_x);
  static double band_magnitude(int band);  // 10^band
  // Bands of a kernel entry's sigma (its regime and term counts follow sigma / period):
  // [0, 0.01), [0.01, 0.1), [0.1, 1), [1, inf); calibrated at 0.003, 0.03, 0.3, 3 (x U[0.5, 1.5]).
  static constexpr int kSigmaBands = 4;
  static int sigma_band_of(double sigma);
  static double sigma_band_scale(int band);
  // The atomic whose argument a function's first parameter is ("fract" for bl::plain::fract,
  // bl::gaussian::fract, bl::box::fract_sq and bl::gaussian::fract_stat), "" for rule functions
  // (their arguments are moments).
  static std::string atomic_of(const std::string& cpp_name);
  // A kernel entry f(x, sigma) or a one-pass stat entry f_stat(x, sigma): timed and profiled over
  // the (|x|, sigma) bands (rule functions take (mean, sd) of their own kind).
  static bool sigma_entry(const compiler::Function& f);

  std::string machine;              // CPU model string the numbers were measured on
  std::string method = "compiled";  // "compiled" (-O3 via bl::jit) or "evaluator" (fallback)
  std::string jit_flags;            // compiled: the JIT flags the kernels were built with
  // Version of the compiled calibration's kernels; a file measured with other kernels is
  // recalibrated (1: vectorized loops, which made straight-line entries 4x too cheap; 2: scalar
  // loops shaped like a program's, with the per-output cost; 3: the spill cost of values live across
  // a call; 4: an f^2 entry beside its f entry).
  static constexpr int kKernels = 4;
  int kernels = kKernels;
  // LOp name -> ns per pixel; "pixel": per-pixel overhead (the loop), "output": per output stored.
  std::map<std::string, double> op_ns;
  std::map<std::string, double> fn_ns;  // Function::cpp -> ns per pixel at |x| ~ 1 (band 0)
  // Function::cpp -> ns per band: kBands values (plain f(x)), or kBands x kSigmaBands values
  // (kernel entries f(x, sigma), index x_band * kSigmaBands + sigma_band).
  std::map<std::string, std::vector<double>> fn_band_ns;
  // Latencies (ns from an argument to the result, band 0), for the critical path: a program whose
  // calls depend on each other (nested noise) is latency-bound in per-pixel code. A function's
  // latency in band b is its band-b cost x fn_lat_ns / fn_ns. Empty: throughput only.
  std::map<std::string, double> op_lat_ns, fn_lat_ns;
  // Function::cpp -> ns per value live across one call (at most kSpillRegs counted): every xmm
  // register is caller-saved, so a call that is not inlined away (libm's sinf, expf, ...) makes the
  // program store and reload what it keeps in registers. The one-function calibration kernels hold
  // nothing across their call; a large smoothed program holds its (mean, var) pairs (fire_bumps'
  // all-Dorn program: 22 libm calls per pixel).
  static constexpr int kSpillRegs = 16;
  std::map<std::string, double> fn_spill_ns;
  // Function::cpp of an f^2 kernel entry -> ns per pixel it adds when the program also calls its f
  // entry with the same (x, sigma), as every smoothed node does for its mean and variance: the
  // entries share their transcendental calls (sin(x); rulegen writes sin^2 and cos^2 to share them)
  // and the compiler merges them. Absent: the entry's own cost.
  std::map<std::string, double> fn_pair_ns;
  // The f entry of an f^2 kernel entry (bl::tent::sin for bl::tent::sin_sq), -1 for others.
  static int square_sibling(int fn);
  // The out-of-order window in ns of throughput work: a program of throughput T and critical path
  // L overlaps max(1, window / T) pixels, so its chain costs L' = L x min(1, T / window) per pixel
  // and the program (T^k + L'^k)^(1/k), k = kLatencyNorm (latency_bound).
  // The calibration measures it on one kernel (8 chained libm sin calls per pixel: window_kernel_ns);
  // bltune --fit-window replaces it by the window that best prices compiled plain programs of real
  // scenes (window_fit.hpp), which overlap more pixels than that kernel does.
  double window_ns = 0;
  double window_kernel_ns = 0;    // the calibration kernel's window (kept when window_ns is fitted)
  int window_fit_programs = 0;    // > 0: window_ns was fitted on that many measured programs
  std::string window_fit_source;  // what they were (the scene directory)
  // A smooth max of T and L' rather than max(T, L'): a program whose throughput and chain are
  // close is dearer than either (the chain's stalls and the issue slots compete; fire_bumps: T 237,
  // L' 239, compiled 371 ns). k = 4 re-priced stop 31's 434 measured programs from median
  // |model/compiled - 1| 0.119 (max) to 0.101 (k = 3: 0.107, 8: 0.116, 2: 0.143); with the scenes
  // split in halves, k fitted on one half gained 2-13% on the other (docs/tuning.md, stop 31).
  static constexpr double kLatencyNorm = 4;
  // The norm the file's window was fitted or measured under (0: max, files before the p-norm);
  // load_or_calibrate recalibrates a file whose norm is not kLatencyNorm.
  double latency_norm = kLatencyNorm;
  static double latency_bound(double throughput, double path, double window);
  // The least a pixel costs, whatever its program (0: none). A GPU model's (method "gpu-fit",
  // gpu_fit.hpp): the fragment rate of the draw, below which a cheaper shader draws no faster (the
  // H200's 0.284 ns/px, plain on most suite scenes).
  double floor_ns = 0;
  // How a program's throughput T meets the floor: 0, max(floor, T); k > 0, (floor^k + T^k)^(1/k)
  // (a GPU's floor is soft: the H200 drew programs of T 0.26-0.27 ns at 0.31-0.35 against its 0.284).
  double floor_norm = 0;
  static double floored(double t, double floor, double norm);
  // The window at which latency_bound(throughput, path, window) = measured (the inverse, for the
  // calibration's chain kernel); 1e9 when the program runs at its throughput (within 5%).
  static double window_for(double throughput, double path, double measured);
  // Not saved, set per scene (magnitude_profile): per atomic, the share of calls per |x| band
  // (band_share, from the plain program) and per (|x|, sigma) band pair (joint_share, from the
  // all-Gaussian program); rows sum to 1. Without a row: band 0 (and the calibration's default
  // sigma band, 2).
  std::map<std::string, std::vector<double>> band_share, joint_share;

  // ns per pixel of one call of function `fn` (index into compiler::functions()) under band_share.
  double function_cost(int fn) const;

  // ns per pixel of p: floored(latency_bound(T, L, window_ns), floor_ns, floor_norm) with T the sum of
  // per-instruction costs (plus the per-pixel overhead and the output stores) and L the critical path of
  // latencies. Throws std::out_of_range naming an op or function the model lacks.
  double cost(const compiler::Program& p) const;
  double throughput(const compiler::Program& p) const;  // the sum alone (+ overhead)
  // ns per pixel of n copies of `sample` run one after another in one pixel (supersampling in the
  // shader, compiler/supersample.hpp: `sample` is one sample's program, its input shifts included):
  // n x (cost(sample) less the per-pixel loop and output stores), plus those once and the n - 1 sums
  // per output. The samples' latency chains do not overlap: one sample of a latency-bound shader is
  // far longer than the out-of-order window (fire_none: ss4 compiles to 4.1x plain), while cost() of
  // the whole supersampled program would overlap them (216 ns/px for 600 compiled). Throws
  // std::invalid_argument for n < 1.
  // A GPU model (floor_ns > 0) floors the whole, and prices the loop per sample (op "sample").
  double sequential_cost(const compiler::Program& sample, int n) const;
  // MSAA-n in the shader: n plain programs (n x cost(plain)); under a floored model (a GPU's) one
  // fragment's n samples, floored once (sequential_cost). What finalize and --explain quote.
  double msaa_cost(const compiler::Program& plain, int n) const;
  // Where cost(p) goes (bltune --explain): the throughput's parts, which sum to throughput(p), and
  // the latency bound's terms.
  struct Breakdown {
    struct Calls {
      int count = 0;
      double ns = 0;  // their price (a sincos cos, an f^2 entry beside its f: the pair's share)
    };
    std::map<std::string, Calls> functions;        // by C++ name
    int ops = 0;                                   // inline instructions (every LOp but calls)
    double ops_ns = 0, spill_ns = 0, loop_ns = 0;  // loop: per-pixel overhead and output stores
    double throughput_ns = 0, path_ns = 0, chain_ns = 0, cost_ns = 0;  // chain: L' of latency_bound
    // The critical path's instructions by C++ function or op name: how many, and their latencies
    // (they sum to path_ns). What a latency-bound program would have to shorten.
    std::map<std::string, Calls> path;
  };
  Breakdown breakdown(const compiler::Program& p) const;
  double critical_path(const compiler::Program& p) const;  // the latency path alone (0 without latencies)
  // Per call instruction, the values (non-constant instructions) placed before it and read after it
  // or stored as outputs: what the call must keep across itself. Non-call instructions are placed as
  // late as their readers allow (the compiler sinks arithmetic to its use); 0 at non-calls.
  static std::vector<int> live_across(const compiler::Program& p);
  // GCC (-O1 and up) merges sinf(x) and cosf(x) of one x into one sincosf call: in such a pair the
  // cos costs this share of its calibrated price (sincosf 3.11 ns against sinf 2.31 and cosf 2.30
  // ns on the tuning machine: (3.11 - 2.31) / 2.30 = 0.35) and no spill of its own. The ripples
  // parallax computes both of one phase; without this their plain programs were over-predicted.
  static constexpr double kSincosExtra = 0.35;
  // Per instruction of p: 1 at a plain cos whose argument a plain sin of p also takes (priced at
  // kSincosExtra), else 0. Shared by throughput() and the GPU fit's features (gpu_fit.hpp).
  static std::vector<char> sincos_partners(const compiler::Program& p);
  // True when every LOp and every current generated function has an entry.
  bool covers_all() const;
  // The names covers_all() misses (for messages).
  std::string missing() const;

 private:
  // throughput(p), and its parts into *b when b is given (one pass for both: the parts cannot drift
  // from the sum).
  double breakdown_throughput(const compiler::Program& p, Breakdown* b) const;
  // critical_path's one pass; with `path`, the path's instructions by name (Breakdown::path).
  double trace_critical_path(const compiler::Program& p, std::map<std::string, Breakdown::Calls>* path) const;
};

const char* lop_name(compiler::LOp op);
std::string cpu_model();  // "model name" of /proc/cpuinfo, or "unknown-cpu"

// File format: {"machines": {"<cpu>": {"ops": {...}, "functions": {...}}}}. load throws
// std::runtime_error naming the file when it is unreadable, malformed or has no entry for `machine`.
CostModel load_cost_model(const std::string& path, const std::string& machine);
// Adds or replaces the model's machine entry, keeping the other machines' entries.
void save_cost_model(const std::string& path, const CostModel& m);

}  // namespace bl::tuner
