// cost_model_check: re-scores a tuned suite's measured points (front points and the uniform
// baselines) with a cost model file, against the compiled-C++ times bltune measured, and prints
// the accuracy: per scene the median and worst |model / compiled - 1|, over all points the median
// and the share within 25%. Re-scoring needs no search and no timing, so a change to the model can
// be judged on ~500 measured programs in a minute (the times are those of the machine that tuned).
// Then the plain programs' throughput and critical path (MSAA-n is n plain programs, so their price
// sets every model speed-up) and the same accuracy at other out-of-order windows (window_ns).
//
//   build/bin/cost_model_check docs/tuning/suite scenes/suite build/cost_model.json [truth cache]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "compiler/schedule_csv.hpp"
#include "compiler/supersample.hpp"
#include "median.hpp"
#include "tuner/report.hpp"
#include "tuner/result_json.hpp"
#include "tuner/scene_tuner.hpp"
#include "tuner/window_fit.hpp"

using namespace bl;
namespace fs = std::filesystem;

namespace {

using bench::median;

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s SUITE_DIR SCENES_DIR COST_MODEL.json [TRUTH_CACHE]\n", argv[0]);
    return 2;
  }
  try {
    const fs::path suite = argv[1], scenes = argv[2];
    const tuner::CostModel cm = tuner::load_cost_model(argv[3], tuner::cpu_model());
    tuner::TuneOptions opt;
    opt.estimate_rho = false;  // the schedules carry their constants
    if (argc > 4) opt.cache_dir = argv[4];
    std::vector<fs::path> dirs;
    for (const auto& e : fs::directory_iterator(suite))
      if (fs::exists(e.path() / "result.json")) dirs.push_back(e.path());
    std::sort(dirs.begin(), dirs.end());
    std::vector<double> all;
    int scenes_within = 0;
    // |model / compiled - 1| of every re-scored program at other out-of-order windows (scan below).
    const std::vector<double> window_factors = {0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0};
    std::vector<std::vector<double>> window_err(window_factors.size());
    std::vector<std::string> plain_lines;
    std::vector<tuner::WindowSample> measured;  // every non-MSAA point: the window fitted on all of them
    std::printf(
        "| scene | points | median model/compiled | median abs(model/compiled - 1) | worst | within 25%% |\n"
        "|---|---|---|---|---|---|\n");
    for (const fs::path& d : dirs) {
      tuner::SceneResult r = tuner::load_result((d / "result.json").string());
      const scene::Scene s = scene::load_scene((scenes / (r.scene + ".json")).string());
      const tuner::SceneTuner t(s, cm, opt);
      std::vector<tuner::CostModel> alts;  // the scene's model (its magnitude profile) at other windows
      for (double w : window_factors) {
        alts.push_back(t.cost_model());
        alts.back().window_ns = w * cm.window_ns;
      }
      // Re-score every measured point with this model (model_accuracy leaves out model_ns <= 0).
      std::vector<double> ratio;
      for (auto* list : {&r.baselines, &r.front})
        for (tuner::Measured& m : *list) {
          if (m.supersample > 0) {
            // ssN: N samples of the plain program one after another, as bltune prices it
            // (finalize.cpp); re-scored for the accuracy, left out of the window scan and fit.
            const auto plain =
                t.lower(compiler::load_schedule((d / "front.csv").string() + ":plain", t.graph()).schedule);
            m.model_ns = plain ? t.cost_model().sequential_cost(
                                     compiler::one_sample(*plain, m.supersample, s.sigma_px), m.supersample)
                               : -1;
            if (m.model_ns > 0 && m.compiled_ns > 0) {
              ratio.push_back(m.model_ns / m.compiled_ns);
              all.push_back(std::fabs(ratio.back() - 1));
            }
            continue;
          }
          // MSAA-n: n times the plain program, as bltune models it.
          const std::string label = m.msaa > 0 ? "plain" : m.label;
          const auto prog =
              t.lower(compiler::load_schedule((d / "front.csv").string() + ":" + label, t.graph()).schedule);
          m.model_ns = prog ? std::max(m.msaa, 1) * t.cost_model().cost(*prog) : -1;
          if (m.model_ns > 0 && m.compiled_ns > 0) {
            if (m.msaa == 0)
              measured.push_back({r.scene + ":" + m.label, t.cost_model().throughput(*prog),
                                  t.cost_model().critical_path(*prog), m.compiled_ns});
            ratio.push_back(m.model_ns / m.compiled_ns);
            all.push_back(std::fabs(ratio.back() - 1));
            if (m.label == "plain") {
              char line[256];
              std::snprintf(line, sizeof line, "| %s | %.1f | %.1f | %.1f | %.1f | %.2f |", r.scene.c_str(),
                            t.cost_model().throughput(*prog), t.cost_model().critical_path(*prog), m.model_ns,
                            m.compiled_ns, m.model_ns / m.compiled_ns);
              plain_lines.push_back(line);
            }
            for (std::size_t w = 0; w < alts.size(); ++w)
              window_err[w].push_back(
                  std::fabs(std::max(m.msaa, 1) * alts[w].cost(*prog) / m.compiled_ns - 1));
          }
        }
      const tuner::ModelAccuracy a = tuner::model_accuracy(r);
      scenes_within += a.median <= tuner::kModelTolerance;
      std::printf("| %s | %d | %.2f | %.0f%% | %.0f%% | %zu |\n", r.scene.c_str(), a.points, median(ratio),
                  100 * a.median, 100 * a.worst, a.points - a.outside.size());
    }
    const long within =
        std::count_if(all.begin(), all.end(), [](double x) { return x <= tuner::kModelTolerance; });
    std::printf(
        "\n%zu points: median abs(model/compiled - 1) %.3f, %.0f%% within 25%%; %d of %zu scenes with "
        "their median within 25%%\n",
        all.size(), median(all), 100.0 * within / all.size(), scenes_within, dirs.size());
    // Where the plain programs (MSAA-n is n of them) sit between throughput and critical path, and
    // how the out-of-order window term (CostModel::cost) would score at other widths: a calibration
    // that misprices the plain programs moves every model speed-up over MSAA.
    std::printf(
        "\n| scene | plain throughput | plain critical path | plain model | plain compiled | model / "
        "compiled |\n"
        "|---|---|---|---|---|---|\n");
    for (const std::string& l : plain_lines) std::printf("%s\n", l.c_str());
    std::printf("\nwindow_ns %.1f (%s; the calibration kernel's %.1f); the same points at other windows:\n",
                cm.window_ns, cm.window_fit_programs > 0 ? "fitted" : "calibrated", cm.window_kernel_ns);
    for (std::size_t w = 0; w < window_factors.size(); ++w) {
      const std::vector<double>& e = window_err[w];
      const long in = std::count_if(e.begin(), e.end(), [](double v) { return v <= tuner::kModelTolerance; });
      std::printf("  %5.1f ns: median abs(model/compiled - 1) %.3f, %.0f%% within 25%%\n",
                  window_factors[w] * cm.window_ns, median(e), 100.0 * in / e.size());
    }
    // A cross-check of bltune --fit-window (plain programs only): the window that best prices every
    // measured program, smoothed ones included.
    if (measured.size() >= 3) {
      const tuner::WindowFit f = tuner::fit_window(measured, cm.window_ns);
      std::printf(
          "the window fitted on all %zu measured non-MSAA programs: %.1f ns (mean abs(log(model/compiled))"
          " %.3f, %d within 25%%; at the model's %.1f ns: %.3f, %d)\n",
          measured.size(), f.window_ns, f.mean_abs_log, f.within, cm.window_ns, f.previous_mean_abs_log,
          f.previous_within);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cost_model_check: %s\n", e.what());
    return 1;
  }
  return 0;
}
