// gpu_cost_fit: fits a GPU cost model (tuner/gpu_fit.hpp) on draws timed by blgpu_time, judges it by
// leaving each scene out in turn (fit on the others, predict it), against the CPU calibration
// scaled by one ratio, and saves it as a machine entry of a cost model file, which bltune
// --cost-machine then prices with.
//
//   build/bin/gpu_cost_fit --prior build/cost_model.json --out docs/gpu_timing/h200_cost_model.json \
//     --machine "NVIDIA H200 (GLSL, fitted)" \
//     docs/gpu_timing/h200_s41_suite.json=docs/tuning/suite:scenes/suite ...
// A later record file of the same tuning directory replaces its (scene, label) draws (a re-timed
// scene); another directory's draws of a scene (another tuning of it) add to them.
//   build/bin/gpu_cost_fit --judge docs/gpu_timing/h200_cost_model.json --machine "NVIDIA H200 (GLSL,
//   fitted)" \
//     NEW_DRAWS.json=SUITE_DIR:SCENES_DIR     # a saved model against draws it was not fitted on
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <tuple>

#include "compiler/schedule_csv.hpp"
#include "compiler/supersample.hpp"
#include "median.hpp"
#include "scene/scene.hpp"
#include "shaders/shader.hpp"
#include "tuner/gpu_fit.hpp"
#include "tuner/result_json.hpp"

using namespace bl;
namespace fs = std::filesystem;

namespace {

using bench::median;

// Spearman's rank correlation of a and b (no tie correction; -2 for fewer than 3 values).
double spearman(const std::vector<double>& a, const std::vector<double>& b) {
  const std::size_t n = a.size();
  if (n < 3) return -2;
  auto ranks = [&](const std::vector<double>& v) {
    std::vector<std::size_t> idx(n);
    for (std::size_t i = 0; i < n; ++i) idx[i] = i;
    std::sort(idx.begin(), idx.end(), [&](std::size_t x, std::size_t y) { return v[x] < v[y]; });
    std::vector<double> r(n);
    for (std::size_t i = 0; i < n; ++i) r[idx[i]] = static_cast<double>(i);
    return r;
  };
  const std::vector<double> ra = ranks(a), rb = ranks(b);
  double d2 = 0;
  for (std::size_t i = 0; i < n; ++i) d2 += (ra[i] - rb[i]) * (ra[i] - rb[i]);
  return 1 - 6 * d2 / (static_cast<double>(n) * (static_cast<double>(n) * n - 1));
}

struct Source {
  fs::path records, suite, scenes;
};

Source parse_source(const std::string& arg) {
  const auto eq = arg.find('='), colon = arg.rfind(':');
  if (eq == std::string::npos || colon == std::string::npos || colon < eq)
    throw std::invalid_argument("'" + arg + "': expected GPU_TIMES.json=SUITE_DIR:SCENES_DIR");
  return {arg.substr(0, eq), arg.substr(eq + 1, colon - eq - 1), arg.substr(colon + 1)};
}

// The draws of one record file whose programs this checkout lowers: front points, plain and the
// uniform baselines, MSAA-n and ssN (LOD pairs, the adaptive supersampler and the truth are left out).
// Draws by (tuning directory, scene, label): a later file re-timing a tuning's scene replaces its
// draws; another tuning of the scene (another directory) adds its own.
using DrawKey = std::tuple<std::string, std::string, std::string>;

void read_source(const Source& src, std::map<DrawKey, tuner::GpuSample>& out) {
  std::map<std::string, fs::path> dir_of;
  for (const auto& e : fs::directory_iterator(src.suite))
    if (fs::exists(e.path() / "result.json"))
      dir_of[tuner::load_result((e.path() / "result.json").string()).scene] = e.path();
  std::ifstream in(src.records);
  if (!in) throw std::runtime_error("cannot read " + src.records.string());
  const nlohmann::json j = nlohmann::json::parse(in);
  std::map<std::string, std::pair<scene::Scene, ir::Graph>> scenes;
  int skipped = 0;
  for (const auto& r : j.at("programs")) {
    const std::string scene = r.at("scene"), label = r.at("label"), kind = r.at("kind");
    const double ns = r.at("gpu_ns_per_pixel");
    if (kind == "lod" || kind == "adaptive" || kind == "truth" ||
        !r.value("failure", std::string()).empty() || !(ns > 0))
      continue;
    const auto d = dir_of.find(scene);
    if (d == dir_of.end()) {
      ++skipped;
      continue;
    }
    auto sc = scenes.find(scene);
    if (sc == scenes.end()) {
      fs::path file = src.scenes / (scene + ".json");
      if (!fs::exists(file)) file = src.scenes / (d->second.filename().string() + ".json");
      scene::Scene s = scene::load_scene(file.string());
      ir::Graph g = shaders::trace(s.shader_def(), s.effects());
      sc = scenes.emplace(scene, std::make_pair(std::move(s), std::move(g))).first;
    }
    const scene::Scene& s = sc->second.first;
    const ir::Graph& g = sc->second.second;
    const std::string front = (d->second / "front.csv").string();
    tuner::GpuSample smp;
    smp.scene = scene;
    smp.label = label;
    smp.measured_ns = ns;
    const int msaa = r.value("msaa", 0);
    const bool ss =
        label.rfind("ss", 0) == 0 && label.size() > 2 && std::isdigit(static_cast<unsigned char>(label[2]));
    const std::string schedule = msaa > 0 || ss ? "plain" : label;
    const compiler::Program p =
        compiler::lower(g, compiler::load_schedule(front + ":" + schedule, g).schedule);
    if (msaa > 0)
      smp.x = tuner::repeated(tuner::throughput_features(p), msaa);
    else if (ss) {
      const int n = std::stoi(label.substr(2));
      smp.x = tuner::repeated(tuner::throughput_features(compiler::one_sample(p, n, s.sigma_px)), n);
    } else
      smp.x = tuner::throughput_features(p);
    out[{fs::weakly_canonical(src.suite).string(), scene, label}] = std::move(smp);
  }
  std::fprintf(
      stderr, "%s: %zu scenes%s\n", src.records.string().c_str(), scenes.size(),
      skipped ? (", " + std::to_string(skipped) + " draws of scenes not in " + src.suite.string()).c_str()
              : "");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gpu_cost_fit: a GPU cost model fitted on blgpu_time's draws"};
  std::string prior_path = "build/cost_model.json", out, machine = "GPU (GLSL, fitted)", judge_path;
  std::vector<std::string> sources;
  std::vector<double> lambdas = {0.003, 0.01, 0.03, 0.1, 1, 10};
  double floor_ns = 0, min_over_floor = 1.5;
  std::vector<double> norms = {0, 4};
  app.add_option("--prior", prior_path,
                 "the CPU cost model whose prices the fit starts from (this machine's)");
  app.add_option("--out", out, "cost model file to add the fitted machine entry to (none: judge only)");
  app.add_option("--machine", machine, "the fitted entry's machine name (bltune --cost-machine)");
  app.add_option("--lambda", lambdas,
                 "ridge weights to judge, one per --lambda (the best by leave-one-scene-out is saved)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  app.add_option(
      "--judge", judge_path,
      "price the draws with this file's --machine entry (no fit): how a saved model does on new draws");
  app.add_option("--floor", floor_ns, "fragment floor in ns/px (default: the fastest draw)");
  app.add_option("--min-over-floor", min_over_floor, "fit on draws at least this many floors");
  app.add_option(
         "--floor-norm", norms,
         "how T meets the floor, one per --floor-norm (0: max(floor, T); k: (floor^k + T^k)^(1/k)); the best "
         "by leave-one-scene-out is saved")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  app.add_option("sources", sources,
                 "GPU_TIMES.json=SUITE_DIR:SCENES_DIR (later files replace earlier draws)")
      ->required();
  CLI11_PARSE(app, argc, argv);
  try {
    const tuner::CostModel prior = tuner::load_cost_model(prior_path, tuner::cpu_model());
    std::map<DrawKey, tuner::GpuSample> by_key;
    for (const std::string& a : sources) read_source(parse_source(a), by_key);
    std::vector<tuner::GpuSample> all;
    for (auto& [k, s] : by_key) all.push_back(std::move(s));
    if (floor_ns <= 0) {
      floor_ns = 1e30;
      for (const auto& s : all) floor_ns = std::min(floor_ns, s.measured_ns);
    }
    if (!judge_path.empty()) {
      const tuner::CostModel m = tuner::load_cost_model(judge_path, machine);
      std::printf("| scene | draws | median abs(pred/GPU - 1) | worst |\n|---|---|---|---|\n");
      std::vector<double> every;
      std::map<std::string, std::vector<const tuner::GpuSample*>> by_scene;
      for (const auto& s : all) by_scene[s.scene].push_back(&s);
      for (const auto& [scene, v] : by_scene) {
        std::vector<double> e;
        for (const tuner::GpuSample* s : v)
          e.push_back(std::fabs(tuner::predict(m, s->x) / s->measured_ns - 1));
        every.insert(every.end(), e.begin(), e.end());
        std::printf("| %s | %zu | %.3f | %.3f |\n", scene.c_str(), e.size(), median(e),
                    *std::max_element(e.begin(), e.end()));
      }
      const long in = std::count_if(every.begin(), every.end(), [](double v) { return v <= 0.25; });
      std::printf("\n%zu draws: median abs(pred/GPU - 1) %.3f, %.0f%% within 25%%\n", every.size(),
                  median(every), 100.0 * in / every.size());
      return 0;
    }
    std::vector<std::string> scenes;
    for (const auto& s : all)
      if (std::find(scenes.begin(), scenes.end(), s.scene) == scenes.end()) scenes.push_back(s.scene);
    std::printf("%zu draws of %zu scenes; floor %.3f ns/px; fitted on draws >= %.1f floors\n\n", all.size(),
                scenes.size(), floor_ns, min_over_floor);
    // Leave one scene out: fit on the others, price the scene's draws (all of them, floored).
    auto judge = [&](double lambda, double norm, bool print) {
      std::vector<double> err_fit, err_scaled, err_near;  // near: draws under 1.5 floors
      if (print)
        std::printf(
            "| scene | draws | median abs(pred/GPU - 1): fitted | CPU x ratio | rank corr. of the front "
            "points: "
            "fitted | CPU x ratio | CPU model |\n|---|---|---|---|---|---|---|\n");
      for (const std::string& held : scenes) {
        std::vector<tuner::GpuSample> train;
        for (const auto& s : all)
          if (s.scene != held) train.push_back(s);
        tuner::GpuFitOptions o;
        o.lambda = lambda;
        o.floor_ns = floor_ns;
        o.min_over_floor = min_over_floor;
        o.floor_norm = norm;
        const tuner::GpuFit f = tuner::fit_gpu_cost_model(train, prior, o, "held-out");
        tuner::GpuFitOptions o0 = o;
        o0.lambda = 1e12;  // every d = 0: the prior times the ratio
        const tuner::GpuFit f0 = tuner::fit_gpu_cost_model(train, prior, o0, "scaled");
        std::vector<double> ef, es, gpu, pf, ps, pc;
        for (const auto& s : all) {
          if (s.scene != held) continue;
          const double a = tuner::predict(f.model, s.x), b = tuner::predict(f0.model, s.x);
          ef.push_back(std::fabs(a / s.measured_ns - 1));
          es.push_back(std::fabs(b / s.measured_ns - 1));
          if (s.measured_ns < 1.5 * floor_ns) err_near.push_back(ef.back());
          if (s.label.rfind("front", 0) == 0) {
            gpu.push_back(s.measured_ns);
            pf.push_back(a);
            ps.push_back(b);
            tuner::CostModel cpu = prior;  // throughput only, unscaled
            cpu.floor_ns = 0;
            pc.push_back(tuner::predict(cpu, s.x));
          }
        }
        err_fit.insert(err_fit.end(), ef.begin(), ef.end());
        err_scaled.insert(err_scaled.end(), es.begin(), es.end());
        if (print)
          std::printf("| %s | %zu | %.3f | %.3f | %.2f | %.2f | %.2f |\n", held.c_str(), ef.size(),
                      median(ef), median(es), spearman(pf, gpu), spearman(ps, gpu), spearman(pc, gpu));
      }
      auto within = [](const std::vector<double>& e) {
        return 100.0 * std::count_if(e.begin(), e.end(), [](double v) { return v <= 0.25; }) / e.size();
      };
      std::printf(
          "%slambda %g, floor norm %g: held-out draws' median abs(pred/GPU - 1) %.3f fitted (%.0f%% within "
          "25%%; under 1.5 floors %.3f), %.3f CPU x ratio (%.0f%%)\n",
          print ? "\n" : "", lambda, norm, median(err_fit), within(err_fit), median(err_near),
          median(err_scaled), within(err_scaled));
      return median(err_fit);
    };
    double best = lambdas.front(), best_norm = norms.front(), best_err = 1e30;
    for (double k : norms)
      for (double l : lambdas)
        if (const double e = judge(l, k, false); e < best_err) {
          best_err = e;
          best = l;
          best_norm = k;
        }
    std::printf("\nLeaving each scene out at lambda %g, floor norm %g:\n\n", best, best_norm);
    judge(best, best_norm, true);
    tuner::GpuFitOptions o;
    o.lambda = best;
    o.floor_ns = floor_ns;
    o.min_over_floor = min_over_floor;
    o.floor_norm = best_norm;
    const tuner::GpuFit f = tuner::fit_gpu_cost_model(all, prior, o, machine);
    std::printf("\nfitted on all: %d draws, %d prices, GPU / CPU ratio %.5f\n", f.used, f.fitted, f.alpha);
    if (!out.empty()) {
      tuner::save_cost_model(out, f.model);
      std::printf("saved machine '%s' to %s\n", machine.c_str(), out.c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gpu_cost_fit: %s\n", e.what());
    return 1;
  }
  return 0;
}
