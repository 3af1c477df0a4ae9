#include "tuner/window_fit.hpp"

#include <cmath>
#include <stdexcept>

#include "jit/compiled_program.hpp"
#include "render/compiled_frame.hpp"
#include "tuner/report.hpp"

namespace bl::tuner {

WindowSample measure_plain(const SceneTuner& t, const jit::Options& jit, int trials) {
  const auto p = t.lower_plain();
  if (!p) throw std::logic_error("the plain program of " + t.scene().name + " does not lower");
  const jit::CompiledProgram cp(*p, jit);
  const scene::Scene& s = t.scene();
  const render::FrameTiming tc =
      render::time_program(s, render::frames(s).front(), *p, render::compiled_runner(cp), 0, trials);
  return {s.name, t.cost_model().throughput(*p), t.cost_model().critical_path(*p), tc.ns_per_pixel};
}

namespace {

struct Score {
  double mean_abs_log = 0;
  int within = 0;
};

Score score(const std::vector<WindowSample>& samples, double window) {
  Score sc;
  for (const WindowSample& s : samples) {
    const double ratio = CostModel::latency_bound(s.throughput_ns, s.path_ns, window) / s.measured_ns;
    sc.mean_abs_log += std::fabs(std::log(ratio)) / samples.size();
    sc.within += std::fabs(ratio - 1) <= kModelTolerance;
  }
  return sc;
}

}  // namespace

WindowFit fit_window(const std::vector<WindowSample>& samples, double previous_window_ns) {
  if (samples.size() < 3)
    throw std::invalid_argument("fitting the out-of-order window needs at least 3 measured programs, got " +
                                std::to_string(samples.size()));
  for (const WindowSample& s : samples)
    if (!(s.throughput_ns > 0) || !(s.path_ns >= 0) || !(s.measured_ns > 0))
      throw std::invalid_argument("window fit: program of " + s.name +
                                  " has a non-positive time (throughput " + std::to_string(s.throughput_ns) +
                                  ", measured " + std::to_string(s.measured_ns) + " ns)");
  WindowFit f;
  const int steps = 16 * 8;  // 4 .. 1024 ns
  double best = INFINITY;
  for (int k = 0; k <= steps; ++k) {
    const double w = 4.0 * std::exp2(k / 16.0);
    const Score sc = score(samples, w);
    if (sc.mean_abs_log < best - 1e-12) {
      best = sc.mean_abs_log;
      f.window_ns = w;
      f.mean_abs_log = sc.mean_abs_log;
      f.within = sc.within;
    }
  }
  // The chains add under 0.1% to every price: a wider window changes nothing the samples can show.
  f.lower_bound_only = true;
  for (const WindowSample& s : samples)
    f.lower_bound_only =
        f.lower_bound_only &&
        CostModel::latency_bound(s.throughput_ns, s.path_ns, f.window_ns) <= 1.001 * s.throughput_ns;
  const Score prev = score(samples, previous_window_ns);
  f.previous_mean_abs_log = prev.mean_abs_log;
  f.previous_within = prev.within;
  return f;
}

}  // namespace bl::tuner
