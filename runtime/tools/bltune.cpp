// bltune: the autoscheduler. Genetic search over per-node rule assignments for the Pareto front of
// time (calibrated cost model) against error (RMS in display space vs the cached ground truth),
// Nelder-Mead on sd factors, measured timings (the emitted C++ compiled with -O3 -march=native at run time;
// GLSL with --glsl) and reports against MSAA.
//
//   bltune --calibrate                                   # print (and save) the cost model table
//   bltune scenes/suite/checkerboard_none.json --out out/tune/checkerboard_none
//     (writes report.md, front.csv, result.json and front/<label>.glsl|.hpp per front point;
//      blrender SCENE --schedule out/tune/checkerboard_none/front.csv:front02 renders one)
//   bltune --suite scenes/suite --out out/tune           # every scene + summary.md
//   bltune --fit-window scenes/suite                     # refit the cost model's out-of-order window
//   bltune --summarize out/tune                          # summary.md/csv again from <scene>/result.json
//   bltune SCENE --explain out/tune/SCENE/front.csv:front03 # where that point's model time goes
//   bltune SCENE --cost-model docs/gpu_timing/h200_cost_model.json \
//     --cost-machine "NVIDIA H200 (GLSL, fitted)" --out DIR  # priced for a GPU (bench/gpu_cost_fit)
//   mpirun -np 2 bltune_mpi --suite scenes/suite --out out/tune   # scenes x restarts over ranks
//
// Built twice from this file: bltune, and bltune_mpi (BL_TUNER_MPI) where MPI exists.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include "compiler/schedule_csv.hpp"
#include "tuner/calibrate.hpp"
#include "tuner/checkpoint.hpp"
#include "tuner/front_code.hpp"
#include "tuner/report.hpp"
#include "tuner/result_json.hpp"
#include "tuner/scene_tuner.hpp"
#include "tuner/window_fit.hpp"

#ifdef BL_TUNER_MPI
#include <mpi.h>

#include <nlohmann/json.hpp>
#endif

using namespace bl;
using namespace bl::tuner;

namespace {

struct Config {
  std::vector<std::string> scene_paths;
  std::string out = "tune_out", cost_model = "build/cost_model.json";
  std::string cost_machine;  // --cost-machine: another machine's entry (a fitted GPU model), never calibrated
  TuneOptions tune;
  FinalizeOptions fin;
  bool search_only = false;
  bool suite = false;                // --suite: every scene in OUT/<scene>, even when --only leaves one
  int image = 0, truth_samples = 0;  // overrides (quick runs, tests); 0 keeps the scene's
  int rank = 0, size = 1;
};

scene::Scene load(const Config& c, const std::string& path) {
  scene::Scene s = scene::load_scene(path);
  if (c.image > 0) s.width = s.height = c.image;
  if (c.truth_samples > 0) s.truth_samples = c.truth_samples;
  return s;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string t; std::getline(in, t, sep);)
    if (!t.empty()) out.push_back(t);
  return out;
}

void log_line(const std::string& scene, const std::string& line) {
  std::printf("[%s] %s\n", scene.c_str(), line.c_str());
  std::fflush(stdout);
}

// The search's front (before refinement): the deterministic artefact tests compare.
void write_search_front(const SceneTuner& t, const std::vector<Point>& front, const std::string& dir) {
  std::filesystem::create_directories(dir);
  std::ofstream out(dir + "/front_search.csv");
  out << "time_ns_per_pixel,search_error,genome\n";
  char buf[64];
  for (const Point& p : front) {
    std::snprintf(buf, sizeof buf, "%.17g,%.17g,", p.obj.time, p.obj.error);
    out << buf << genome_key(p.genome) << "\n";
  }
  (void)t;
}

SceneResult finish(const SceneTuner& t, const std::vector<Point>& front, double search_s, int evals,
                   const Config& c, const std::string& dir) {
  write_search_front(t, front, dir);
  // The search's count, before refinement evaluates more (under MPI: this rank's restarts only).
  const long rejected = t.nonfinite_rejections();
  SceneResult r;
  r.scene = t.scene().name;
  if (!c.search_only) {
    FinalizeOptions fo = c.fin;
    fo.out_dir = dir;
    r = finalize(t, front, fo);
  }
  r.search_seconds = search_s;
  r.evaluations = evals;
  r.rejected_nonfinite = rejected;
  if (!c.search_only) {
    write_scene_report(r, dir);
    std::ofstream(dir + "/result.json") << result_to_json(r) << "\n";
    const int n = write_front_code(t, r, dir);
    log_line(t.scene().name,
             "wrote " + std::to_string(n) + " front point(s) as " + dir + "/front/<label>.glsl|.hpp");
  }
  return r;
}

int summarize(const std::string& dir);

// After a run: a suite's summary over every OUT/<scene>/result.json (a scene retuned with --only
// replaces its row, the others keep theirs); several scene files' over this run's.
void write_summary(const Config& c, const std::vector<SceneResult>& results) {
  if (c.suite)
    summarize(c.out);
  else if (results.size() > 1)
    write_suite_summary(results, c.out);
}

std::string scene_dir(const Config& c, const scene::Scene& s) {
  return c.scene_paths.size() == 1 && !c.suite ? c.out : c.out + "/" + s.name;
}

SearchOptions search_options(const Config& c, const scene::Scene& s) {
  SearchOptions so = c.tune.search;
  if (so.checkpoint_dir.empty()) so.checkpoint_dir = scene_dir(c, s) + "/checkpoints";
  so.log = [name = s.name](const std::string& l) { log_line(name, l); };
  return so;
}

int run_single(const Config& c, const CostModel& cm) {
  std::vector<SceneResult> results;
  bool complete = true;
  for (const std::string& path : c.scene_paths) {
    const scene::Scene s = load(c, path);
    const auto t0 = std::chrono::steady_clock::now();
    SceneTuner t(s, cm, c.tune);
    log_line(s.name, std::to_string(t.graph().size()) + " nodes, " +
                         std::to_string(t.problem().space.size()) + " genes, palette of " +
                         std::to_string(t.problem().palette.rules.size()) + " rules");
    const RestartResult r = search(t.problem(), search_options(c, s));
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    log_line(s.name, "search " + std::to_string(secs) + " s, front of " + std::to_string(r.front.size()));
    if (t.nonfinite_rejections() > 0)
      log_line(s.name, std::to_string(t.nonfinite_rejections()) +
                           " evaluation(s) gave NaN/inf on the sampled pixels: infeasible (error +inf)");
    if (!r.complete) {
      complete = false;
      log_line(s.name, "stopped early (--stop-after): run again to resume from the checkpoints");
      continue;
    }
    results.push_back(finish(t, r.front, secs, r.evaluations, c, scene_dir(c, s)));
  }
  if (!c.search_only && complete) write_summary(c, results);
  return complete ? 0 : 3;
}

// The JSON scene files of `dir` whose name contains `only`, sorted.
std::vector<std::string> scene_files(const std::string& dir, const std::string& only = "") {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".json" && e.path().filename().string().find(only) != std::string::npos)
      out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  if (out.empty()) throw std::invalid_argument("no scene matches in " + dir);
  return out;
}

// Fits cm's out-of-order window on the compiled plain programs of every scene in `dir`
// (window_fit.hpp), prints each program and the fit, and saves the model.
void fit_and_save_window(const Config& c, const std::string& dir, CostModel& cm) {
  const std::vector<std::string> files = scene_files(dir);
  if (files.size() < 3) {
    std::printf("window not fitted: %s has %zu scene(s), the fit needs 3 (the calibrated %.1f ns stays)\n",
                dir.c_str(), files.size(), cm.window_ns);
    return;
  }
  std::printf("fitting the cost model's out-of-order window on the compiled plain programs of %s\n",
              dir.c_str());
  std::printf(
      "| scene | throughput ns | critical path ns | compiled ns | model ns (%.1f) |\n|---|---|---|---|---|\n",
      cm.window_ns);
  std::vector<WindowSample> samples;
  for (const std::string& path : files) {
    const SceneTuner t(load(c, path), cm, c.tune);
    samples.push_back(measure_plain(t, c.fin.jit, c.fin.trials));
    const WindowSample& w = samples.back();
    std::printf("| %s | %.1f | %.1f | %.1f | %.1f |\n", w.name.c_str(), w.throughput_ns, w.path_ns,
                w.measured_ns, CostModel::latency_bound(w.throughput_ns, w.path_ns, cm.window_ns));
    std::fflush(stdout);
  }
  const WindowFit f = fit_window(samples, cm.window_ns);
  std::printf(
      "window %.1f ns (was %.1f): mean |log(model/compiled)| %.3f (was %.3f), %d of %zu within 25%% (was "
      "%d)%s\n",
      f.window_ns, cm.window_ns, f.mean_abs_log, f.previous_mean_abs_log, f.within, samples.size(),
      f.previous_within, f.lower_bound_only ? "; every program prices as its throughput: a lower bound" : "");
  cm.window_ns = f.window_ns;
  cm.window_fit_programs = static_cast<int>(samples.size());
  cm.window_fit_source = dir;
  save_cost_model(c.cost_model, cm);
  std::printf("saved %s\n", c.cost_model.c_str());
  std::fflush(stdout);
}

// Where a schedule's model time goes (--explain FRONT.csv:LABEL): the throughput by function,
// inline arithmetic, spill and pixel loop, dearest first; the latency chain; and against the plain
// program, the point as a multiple of it: MSAA-16 costs 16 plain programs, so 10x less time at
// MSAA-16's error asks for a program at most 1.6x plain.
void explain(const Config& c, const std::string& scene_path, const std::string& spec, const CostModel& cm) {
  const scene::Scene s = load(c, scene_path);
  TuneOptions opt = c.tune;
  opt.estimate_rho = false;  // the schedule carries its constants
  const SceneTuner t(s, cm, opt);
  const compiler::LoadedSchedule ls = compiler::load_schedule(spec, t.graph());
  const auto p = t.lower(ls.schedule);
  const auto plain = t.lower_plain();
  if (!p || !plain) throw std::runtime_error(spec + " does not lower on scene " + s.name);
  const CostModel& m = t.cost_model();
  std::printf("# Model time of %s:%s on %s (cost model: %s, %s)\n\n%s", ls.file.c_str(), ls.label.c_str(),
              s.name.c_str(), m.machine.c_str(), m.method.c_str(),
              time_breakdown_markdown(m, *p, *plain).c_str());
}

// DIR/summary.md and summary.csv from the result.json of every scene directory under DIR (a --suite
// run, --only included, ends with it; by hand after copying scene directories together).
int summarize(const std::string& dir) {
  std::vector<std::filesystem::path> scenes;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (std::filesystem::exists(e.path() / "result.json")) scenes.push_back(e.path());
  std::sort(scenes.begin(), scenes.end());
  if (scenes.empty()) throw std::invalid_argument("no <scene>/result.json under " + dir);
  std::vector<SceneResult> results;
  for (const auto& d : scenes) results.push_back(load_result((d / "result.json").string()));
  write_suite_summary(results, dir);
  std::printf("wrote %s/summary.md and summary.csv over %zu scene(s)\n", dir.c_str(), results.size());
  return 0;
}

#ifdef BL_TUNER_MPI
// Strings from every rank to rank 0 (rank order).
std::vector<std::string> gather(const std::string& mine, int rank, int size) {
  int len = static_cast<int>(mine.size());
  std::vector<int> lens(size), offs(size);
  MPI_Gather(&len, 1, MPI_INT, lens.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  int total = 0;
  for (int i = 0; i < size; ++i) offs[i] = total, total += rank == 0 ? lens[i] : 0;
  std::string all(rank == 0 ? total : 0, '\0');
  MPI_Gatherv(mine.data(), len, MPI_CHAR, all.data(), lens.data(), offs.data(), MPI_CHAR, 0, MPI_COMM_WORLD);
  std::vector<std::string> out;
  if (rank == 0)
    for (int i = 0; i < size; ++i) out.push_back(all.substr(offs[i], lens[i]));
  return out;
}

std::string broadcast(std::string s, int rank) {
  int len = static_cast<int>(s.size());
  MPI_Bcast(&len, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (rank != 0) s.assign(len, '\0');
  MPI_Bcast(s.data(), len, MPI_CHAR, 0, MPI_COMM_WORLD);
  return s;
}

// Units (scene, restart) round-robin over ranks; fronts gathered and merged in restart order on
// rank 0 (the single-process merge), then scenes finalized round-robin and results gathered.
int run_mpi(const Config& c, const CostModel& cm) {
  std::vector<scene::Scene> scenes;
  for (const std::string& p : c.scene_paths) scenes.push_back(load(c, p));
  const int restarts = c.tune.search.restarts, units = static_cast<int>(scenes.size()) * restarts;
  std::map<int, std::unique_ptr<SceneTuner>> tuners;
  // Rank 0 renders (and caches) the ground truth first so ranks never write the same file.
  if (c.rank == 0)
    for (std::size_t i = 0; i < scenes.size(); ++i)
      tuners[i] = std::make_unique<SceneTuner>(scenes[i], cm, c.tune);
  MPI_Barrier(MPI_COMM_WORLD);
  auto tuner = [&](int i) -> SceneTuner& {
    if (!tuners[i]) tuners[i] = std::make_unique<SceneTuner>(scenes[i], cm, c.tune);
    return *tuners[i];
  };
  nlohmann::json mine = nlohmann::json::object();
  std::map<int, EvalCache> caches;
  std::map<int, double> seconds;
  for (int u = c.rank; u < units; u += c.size) {
    const int i = u / restarts, r = u % restarts;
    const auto t0 = std::chrono::steady_clock::now();
    const RestartResult res = run_restart(tuner(i).problem(), search_options(c, scenes[i]), r, caches[i]);
    mine[std::to_string(u)] = {
        {"front", points_to_json(res.front)},
        {"evaluations", res.evaluations},
        {"complete", res.complete},
        {"seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()}};
  }
  std::vector<std::string> all = gather(mine.dump(), c.rank, c.size);
  nlohmann::json fronts = nlohmann::json::object();
  bool complete = true;
  if (c.rank == 0) {
    std::vector<nlohmann::json> unit(units);
    for (const std::string& s : all) {
      const nlohmann::json from_rank = nlohmann::json::parse(s);  // items() must not outlive it
      for (const auto& [k, v] : from_rank.items()) unit[std::stoi(k)] = v;
    }
    for (std::size_t i = 0; i < scenes.size(); ++i) {
      std::vector<std::vector<Point>> fs;
      int evals = 0;
      double secs = 0;
      const int pal = static_cast<int>(tuner(i).problem().palette.rules.size());
      for (int r = 0; r < restarts; ++r) {
        const nlohmann::json& v = unit[i * restarts + r];
        fs.push_back(points_from_json(v.at("front").get<std::string>(), pal));
        evals += v.at("evaluations").get<int>();
        secs += v.at("seconds").get<double>();
        complete = complete && v.at("complete").get<bool>();
      }
      fronts[std::to_string(i)] = {
          {"front", points_to_json(merge_fronts(fs))}, {"evaluations", evals}, {"seconds", secs}};
    }
    fronts["complete"] = complete;
  }
  fronts = nlohmann::json::parse(broadcast(fronts.dump(), c.rank));
  if (!fronts.at("complete").get<bool>()) return 3;
  nlohmann::json done = nlohmann::json::array();
  for (int i = c.rank; i < static_cast<int>(scenes.size()); i += c.size) {
    const nlohmann::json& f = fronts.at(std::to_string(i));
    SceneTuner& t = tuner(i);
    const auto front = points_from_json(f.at("front").get<std::string>(),
                                        static_cast<int>(t.problem().palette.rules.size()));
    const SceneResult r = finish(t, front, f.at("seconds").get<double>(), f.at("evaluations").get<int>(), c,
                                 scene_dir(c, scenes[i]));
    done.push_back({{"index", i}, {"result", result_to_json(r)}});
  }
  all = gather(done.dump(), c.rank, c.size);
  if (c.rank == 0 && !c.search_only) {
    std::vector<SceneResult> results(scenes.size());
    for (const std::string& s : all)
      for (const auto& d : nlohmann::json::parse(s))
        results[d.at("index").get<int>()] = result_from_json(d.at("result"));
    write_summary(c, results);
  }
  return 0;
}
#endif

}  // namespace

int main(int argc, char** argv) {
  Config c;
#ifdef BL_TUNER_MPI
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &c.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &c.size);
#endif
  CLI::App app{"bltune: genetic search for the time/error Pareto front of rule assignments"};
  std::string scene_path, suite_dir, rules_csv, only, fit_dir, summary_dir, explain_spec;
  bool calibrate_only = false, glsl = false, no_glsl = false, no_rho = false;
  SearchOptions& so = c.tune.search;
  app.add_option("scene", scene_path, "scene file (JSON)");
  app.add_option("--suite", suite_dir, "tune every *.json scene in this directory (sorted by name)");
  app.add_option("--only", only, "with --suite: only scenes whose file name contains this");
  app.add_option("--out", c.out,
                 "output directory (per scene: report.md, front.csv, result.json, pareto.png, images, "
                 "front/<label>.glsl|.hpp)");
  app.add_option("--cache", c.tune.cache_dir, "ground-truth cache directory (EXR)");
  app.add_option("--cost-model", c.cost_model,
                 "cost model JSON (calibrated and saved when this machine lacks one)");
  app.add_option(
      "--cost-machine", c.cost_machine,
      "price with this machine's entry of --cost-model instead of this CPU's (a GPU model fitted by "
      "bench/gpu_cost_fit; never calibrated here; the compiled-C++ columns still time this CPU)");
  app.add_flag("--calibrate", calibrate_only, "recalibrate the cost model, print the table, and exit");
  app.add_option("--summarize", summary_dir,
                 "write DIR/summary.md and summary.csv from DIR/<scene>/result.json, and exit");
  app.add_option(
      "--explain", explain_spec,
      "with a scene: where the model time of FRONT.csv:LABEL goes (by function, arithmetic, spill, "
      "latency; against plain and MSAA-16), and exit");
  app.add_option("--fit-window", fit_dir,
                 "fit the cost model's out-of-order window on the compiled plain programs of this "
                 "directory's scenes, save it, and exit (--suite does it first when the model has no fit)");
  std::string calibration = "compiled";
  app.add_option("--calibration", calibration,
                 "what the cost model times: compiled (the emitted C++, -O3; default) or evaluator (quick, "
                 "for tests)")
      ->check(CLI::IsMember({"compiled", "evaluator"}));
  app.add_option("--rules", rules_csv,
                 "comma-separated rule palette (default: every rule + gaussian:rho=const)");
  app.add_option("--seed", so.seed, "random seed");
  app.add_option("--population", so.population, "population size");
  app.add_option("--generations", so.generations, "bred generations");
  app.add_option("--restarts", so.restarts, "random restarts");
  app.add_option("--threads", so.threads, "evaluation threads (0: all; results do not depend on it)");
  app.add_option("--checkpoints", so.checkpoint_dir, "checkpoint directory (default <out>/checkpoints)");
  app.add_option("--stop-after", so.stop_after, "stop after this many bred generations (tests resumption)");
  app.add_option("--pixels", c.tune.sample_pixels, "pixels sampled for the search error (over all frames)");
  app.add_option("--nm-evals", c.tune.nm_evals, "Nelder-Mead evaluations per front point (0: off)");
  app.add_option("--max-points", c.fin.max_points, "front points refined and measured");
  app.add_option("--image", c.image, "override the scenes' image size (N x N pixels)");
  app.add_option("--truth-samples", c.truth_samples, "override the scenes' ground-truth samples per pixel");
  app.add_flag("--glsl", glsl,
               "also time the emitted GLSL on the OpenGL driver (opt-in: on llvmpipe compiling a large "
               "shader takes minutes)");
  app.add_flag("--no-glsl", no_glsl, "do not time the GLSL (the default; kept for scripts)");
  app.add_option("--jit-cache", c.fin.jit.cache_dir,
                 "compiled-shader cache directory (default build/jit_cache)");
  app.add_option("--cxx", c.fin.jit.compiler,
                 "C++ compiler for compiled-code timings (default $BL_JIT_CXX, $CXX, g++)");
  app.add_option("--trials", c.fin.trials, "timing trials per measured variant (minimum kept)");
  app.add_flag("--no-rho-estimate", no_rho, "do not estimate constant rhos by sampling (B.1)");
  app.add_flag("--search-only", c.search_only, "write front_search.csv only (no refinement, timing, report)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
#ifdef BL_TUNER_MPI
    MPI_Finalize();
#endif
    return app.exit(e);
  }
  int rc = 0;
  try {
    if (!summary_dir.empty()) {
      if (c.rank == 0) rc = summarize(summary_dir);
    } else if (calibrate_only) {
      if (!c.cost_machine.empty())
        throw std::invalid_argument("--calibrate measures this CPU; drop --cost-machine");
      if (c.rank == 0) {
        CalibrationOptions co;
        co.method = calibration == "evaluator" ? CalibrationOptions::Method::Evaluator
                                               : CalibrationOptions::Method::Compiled;
        const auto t0 = std::chrono::steady_clock::now();
        const CostModel m = calibrate(
            co, [](const std::string& n, double ns) { std::printf("%-44s %9.2f ns/px\n", n.c_str(), ns); });
        save_cost_model(c.cost_model, m);
        std::printf("saved %s (machine '%s', %.0f s wall)\n", c.cost_model.c_str(), m.machine.c_str(),
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      }
    } else {
      c.fin.glsl = glsl && !no_glsl;
      c.tune.estimate_rho = !no_rho;
      if (!rules_csv.empty()) c.tune.rules = split(rules_csv, ',');
      if (!explain_spec.empty() && (scene_path.empty() || !suite_dir.empty()))
        throw std::invalid_argument(
            "--explain FRONT.csv:LABEL needs the scene file the schedule was tuned on");
      if (!suite_dir.empty()) {
        c.scene_paths = scene_files(suite_dir, only);
        c.suite = true;
      } else if (!scene_path.empty()) {
        c.scene_paths.push_back(scene_path);
      } else if (fit_dir.empty()) {
        throw std::invalid_argument("give a scene file, --suite DIR, --fit-window DIR or --calibrate");
      }
      if (c.size > 1 && so.threads == 0)
        so.threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()) / c.size);
      // Rank 0 calibrates when needed; the others then read its file.
      CostModel cm;
      if (!c.cost_machine.empty()) {
        if (!fit_dir.empty())
          throw std::invalid_argument("--fit-window fits this CPU's model, not --cost-machine's");
        cm = load_cost_model(c.cost_model, c.cost_machine);
        if (!cm.covers_all())
          throw std::invalid_argument(c.cost_model + ": machine '" + c.cost_machine + "' prices none of" +
                                      cm.missing() + " (refit it with bench/gpu_cost_fit)");
      } else if (c.rank == 0) {
        cm = load_or_calibrate(c.cost_model, true,
                               calibration == "evaluator" ? CalibrationOptions::Method::Evaluator
                                                          : CalibrationOptions::Method::Compiled);
      }
      if (!explain_spec.empty()) {
        if (c.rank == 0) explain(c, scene_path, explain_spec, cm);
        c.scene_paths.clear();
      }
      // A suite fits the window on all its scenes (not only those --only picks) once per calibration.
      if (c.rank == 0 && !fit_dir.empty()) fit_and_save_window(c, fit_dir, cm);
      if (c.rank == 0 && !suite_dir.empty() && cm.window_fit_programs == 0 && cm.method == "compiled")
        fit_and_save_window(c, suite_dir, cm);
#ifdef BL_TUNER_MPI
      MPI_Barrier(MPI_COMM_WORLD);
      if (c.rank != 0)
        cm = load_cost_model(c.cost_model, c.cost_machine.empty() ? cpu_model() : c.cost_machine);
      if (!c.scene_paths.empty()) rc = run_mpi(c, cm);
#else
      if (!c.scene_paths.empty()) rc = run_single(c, cm);
#endif
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bltune: %s\n", e.what());
    rc = 1;
#ifdef BL_TUNER_MPI
    MPI_Abort(MPI_COMM_WORLD, 1);
#endif
  }
#ifdef BL_TUNER_MPI
  MPI_Finalize();
#endif
  return rc;
}
