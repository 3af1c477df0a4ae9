// cost_model_check: re-scores a tuned suite's measured points (front points and the uniform
// baselines) with a cost model file, against the compiled-C++ times bltune measured, and prints
// the accuracy: per scene the median and worst |model / compiled - 1|, over all points the median
// and the share within 25%. Re-scoring needs no search and no timing, so a change to the model can
// be judged on ~500 measured programs in a minute (the times are those of the machine that tuned).
//
//   build/bin/cost_model_check docs/tuning/suite scenes/suite build/cost_model.json [truth cache]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "compiler/schedule_csv.hpp"
#include "tuner/scene_tuner.hpp"

using namespace bl;
namespace fs = std::filesystem;

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

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
    std::printf(
        "| scene | points | median model/compiled | median abs(model/compiled - 1) | worst | within 25%% |\n"
        "|---|---|---|---|---|---|\n");
    for (const fs::path& d : dirs) {
      std::ifstream in(d / "result.json");
      const nlohmann::json r = nlohmann::json::parse(in);
      const std::string name = r.at("scene");
      const scene::Scene s = scene::load_scene((scenes / (name + ".json")).string());
      const tuner::SceneTuner t(s, cm, opt);
      std::vector<double> dev, ratio;
      auto score = [&](const nlohmann::json& p) {
        if (p.value("compiled_ns", -1.0) <= 0) return;
        // MSAA-n: n times the plain program, as bltune models it.
        const int n = p.at("msaa").get<int>();
        const std::string label = n > 0 ? "plain" : p.at("label").get<std::string>();
        const auto sched = compiler::load_schedule((d / "front.csv").string() + ":" + label, t.graph());
        const auto prog = t.lower(sched.schedule);
        if (!prog) return;
        const double model = std::max(n, 1) * t.cost_model().cost(*prog);
        ratio.push_back(model / p.at("compiled_ns").get<double>());
        dev.push_back(std::fabs(ratio.back() - 1));
      };
      for (const auto& p : r.at("baselines")) score(p);
      for (const auto& p : r.at("front")) score(p);
      const double med = median(dev), worst = *std::max_element(dev.begin(), dev.end());
      const long within = std::count_if(dev.begin(), dev.end(), [](double x) { return x <= 0.25; });
      scenes_within += med <= 0.25;
      all.insert(all.end(), dev.begin(), dev.end());
      std::printf("| %s | %zu | %.2f | %.0f%% | %.0f%% | %ld |\n", name.c_str(), dev.size(), median(ratio), 100 * med,
                  100 * worst, within);
    }
    const long within = std::count_if(all.begin(), all.end(), [](double x) { return x <= 0.25; });
    std::printf("\n%zu points: median abs(model/compiled - 1) %.3f, %.0f%% within 25%%; %d of %zu scenes with "
                "their median within 25%%\n",
                all.size(), median(all), 100.0 * within / all.size(), scenes_within, dirs.size());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cost_model_check: %s\n", e.what());
    return 1;
  }
  return 0;
}
