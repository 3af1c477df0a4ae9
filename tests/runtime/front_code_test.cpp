// Code out (issue 12 item 5): a tiny bltune run over the 7 suite patterns, written in GLSL
// (scenes/glsl/suite: the suite's *_none scenes naming scenes/glsl/<pattern>.glsl), writes front/<label>.glsl
// and .hpp for every front point; each GLSL file compiles with glslangValidator (-l, as 450 and as
// 320 es, wrapped in the renderer's fragment main) and, executed on the headless GL driver, renders
// what the C++ evaluator renders for the schedule read back from front.csv (blrender --schedule's
// path), within the 1e-3 (display space) of runtime_glsl_exec_test. The .hpp files compile.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "compiler/lower.hpp"
#include "compiler/schedule_csv.hpp"
#include "compiler/schedule_text.hpp"
#include "compiler/supersample.hpp"
#include "image/display.hpp"
#include "render/glsl_frame.hpp"
#include "render/render.hpp"
#include "tuner/calibrate.hpp"
#include "tuner/result_json.hpp"

using namespace bl;
namespace fs = std::filesystem;

namespace {

constexpr int kImage = 24;

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The front rows' labels of a front.csv (column 2 of rows whose kind is "front").
std::vector<std::string> front_labels(const std::string& csv) {
  std::ifstream in(csv);
  std::vector<std::string> out;
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line))
    if (line.rfind("front,", 0) == 0) out.push_back(line.substr(6, line.find(',', 6) - 6));
  return out;
}

}  // namespace

TEST(FrontCode, EveryFrontPointCompilesAndMatchesTheEvaluator) {
  const fs::path work = fs::temp_directory_path() / "bl_front_code_test";
  fs::remove_all(work);
  auto t0 = std::chrono::steady_clock::now();
  auto phase = [&](const char* what) {  // wall seconds per phase (the test must stay fast)
    const auto t = std::chrono::steady_clock::now();
    std::printf("phase %s: %.2f s\n", what, std::chrono::duration<double>(t - t0).count());
    t0 = t;
  };
  fs::create_directories(work);
  {  // A quick cost model (noisy but complete): the fronts only need some order of costs.
    tuner::CalibrationOptions o;
    o.pixels = 256;
    o.copies = 2;
    o.min_ms = 0.02;
    o.trials = 1;
    tuner::save_cost_model((work / "cost.json").string(), tuner::calibrate(o));
  }
  phase("cost model");
  const std::string out = (work / "out").string();
  const std::string cmd =
      std::string(BLTUNE) + " --suite " BL_SOURCE_DIR "/scenes/glsl/suite --only _none --out " + out +
      " --cache " + (work / "cache").string() + " --cost-model " + (work / "cost.json").string() +
      " --image 24 --truth-samples 8 --rules none,dorn,mc2,box,rule2"
      " --population 6 --generations 1 --restarts 1 --pixels 120 --nm-evals 3 --max-points 3"
      " --no-glsl > " +
      (work / "bltune.log").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << read((work / "bltune.log").string());
  {  // A suite fits the model's window on its plain programs first (once: the model now has it).
    const std::string log = read((work / "bltune.log").string());
    EXPECT_NE(log.find("fitting the cost model's out-of-order window"), std::string::npos) << log;
    const tuner::CostModel cm = tuner::load_cost_model((work / "cost.json").string(), tuner::cpu_model());
    EXPECT_GE(cm.window_fit_programs, 3);
    EXPECT_GT(cm.window_ns, 0);
  }
  {  // --summarize rebuilds the suite summary from the scenes' result.json; an empty directory is an error.
    fs::remove(fs::path(out) / "summary.md");
    const std::string sum =
        std::string(BLTUNE) + " --summarize " + out + " > " + (work / "sum.log").string() + " 2>&1";
    ASSERT_EQ(std::system(sum.c_str()), 0) << read((work / "sum.log").string());
    EXPECT_NE(read(out + "/summary.md").find("What >= 10x"), std::string::npos);
    fs::create_directories(work / "empty");
    const std::string bad = std::string(BLTUNE) + " --summarize " + (work / "empty").string() + " > " +
                            (work / "bad.log").string() + " 2>&1";
    EXPECT_NE(std::system(bad.c_str()), 0);
    EXPECT_NE(read((work / "bad.log").string()).find("no <scene>/result.json under"), std::string::npos);
  }

  phase("bltune");
  const auto av = gl::Context::availability();
  std::unique_ptr<gl::Context> ctx;
  if (av.ok)
    ctx = std::make_unique<gl::Context>();
  else
    std::printf("no OpenGL driver (%s): GLSL compiled, not executed\n", av.reason.c_str());

  int points = 0, scenes = 0, lods = 0;
  std::string cpp = "// every front point's header in one translation unit\n", es_files;
  // A front file's function `shade` (of program p's signature) as a whole program: validated (-l:
  // linked, so the entry point and every call resolve) in GLSL 450 now, and queued as 320 es (stricter
  // on types) for one validator run over the suite below. Returns the 450 fragment shader.
  auto validate = [&](const std::string& base, const std::string& glsl, const compiler::Program& p) {
    const std::string frag =
        render::glsl_version_line("450") + glsl + "\n" + render::glsl_fragment_main(p, "shade");
    std::ofstream(base + ".frag") << frag;
    EXPECT_EQ(
        std::system((std::string(GLSLANG_VALIDATOR) + " -l -S frag " + base + ".frag > " + base + ".log 2>&1")
                        .c_str()),
        0)
        << read(base + ".log");
    std::ofstream(base + "_es.frag") << render::glsl_version_line("320 es") << glsl << "\n"
                                     << render::glsl_fragment_main(p, "shade");
    es_files += " " + base + "_es.frag";
    return frag;
  };
  for (const char* name : {"bricks_none", "checkerboard_none", "circles_none", "color_circles_none",
                           "fire_none", "quadratic_sine_none", "zigzag_none"}) {
    SCOPED_TRACE(name);
    scene::Scene s = scene::load_scene(std::string(BL_SOURCE_DIR "/scenes/glsl/suite/") + name + ".json");
    s.width = s.height = kImage;
    const ir::Graph g = shaders::trace(s.shader_def(), s.effects());
    const std::string dir = out + "/" + name, csv = dir + "/front.csv";
    const std::vector<std::string> labels = front_labels(csv);
    ASSERT_FALSE(labels.empty()) << csv;
    int files = 0;
    for (const auto& e : fs::directory_iterator(dir + "/front"))
      files += e.path().extension() == ".glsl" && e.path().filename() != "lod.glsl";
    EXPECT_EQ(files, static_cast<int>(labels.size())) << "one .glsl per front point";
    // A footprint-LOD pair (result.json's lod) comes as front/lod.glsl and lod.hpp: validated and
    // compiled like the points (its near program's fragment main: both programs take the same inputs).
    const tuner::SceneResult res = tuner::load_result(dir + "/result.json");
    EXPECT_EQ(fs::exists(dir + "/front/lod.glsl"), res.lod.has_value());
    EXPECT_EQ(fs::exists(dir + "/front/lod.hpp"), res.lod.has_value());
    if (res.lod) {
      const compiler::Program near = compiler::stratified_samples(
          compiler::lower(g, compiler::parse_schedule(g, res.lod->near_schedule, "lod near")),
          res.lod->near_samples, s.sigma_px);
      const std::string glsl = read(dir + "/front/lod.glsl");
      EXPECT_NE(glsl.find("footprint LOD of scene " + std::string(name)), std::string::npos);
      validate((work / (std::string(name) + "_lod")).string(), glsl, near);
      ++lods;
      const std::string n = "shade_lod" + std::to_string(lods);
      cpp += "#define shade " + n + "\n#define shade_near " + n + "_near\n#define shade_far " + n +
             "_far\n#include \"" + dir +
             "/front/lod.hpp\"\n#undef shade\n#undef shade_near\n#undef shade_far\n";
    }
    ++scenes;
    for (const std::string& label : labels) {
      SCOPED_TRACE(label);
      const compiler::LoadedSchedule l = compiler::load_schedule(csv + ":" + label, g);
      const compiler::Program p = compiler::lower(g, l.schedule);
      const std::string glsl = read(dir + "/front/" + label + ".glsl");
      // The banner names the scene, the point, its schedule and its measured error.
      EXPECT_NE(glsl.find("front point " + label + " of scene " + name), std::string::npos);
      EXPECT_NE(glsl.find(l.text), std::string::npos);
      EXPECT_NE(glsl.find("measured: RMS 0."), std::string::npos);
      const std::string frag = validate((work / (std::string(name) + "_" + label)).string(), glsl, p);
      if (ctx) {
        // Unsmoothed nodes evaluate discontinuities and large sin arguments plainly: there a float
        // rounding flips a few values (runtime_glsl_exec_test allows 1/33 over 1e-3 for "none";
        // plain quadratic_sine's far view, where sin's argument reaches ~1e3 and llvmpipe's sin
        // differs from libm's, measured 91 of 1728 = 5.3%; the horizon's partly covered pixels,
        // camera/horizon_coverage.hpp, shade one more row of such far-field points: 161 = 9.3%,
        // allowed 1/8 here); a schedule without
        // plain or Monte Carlo computation nodes is held to 1e-3 everywhere, as in runtime_glsl_exec_test.
        // Monte Carlo nodes count as plain: they evaluate the plain function at sampled points, where
        // the same float rounding flips a discontinuity (circles_none's front01 with mc2 fract: 12 of
        // 1728 values over 1e-3, worst 1.1e-3).
        bool plain_nodes = false;
        for (int n = 0; n < g.size(); ++n)
          plain_nodes =
              plain_nodes ||
              ((l.schedule[n].kind == rules::Kind::None || l.schedule[n].kind == rules::Kind::MonteCarlo) &&
               g.node(n).op != ir::Op::Const && g.node(n).op != ir::Op::Input);
        const gl::Program compiled = ctx->compile(frag);
        for (const render::Frame& f : render::frames(s)) {
          const Image cpu = render::render_smoothed(s, f, p);
          const Image gpu = render::render_glsl_compiled(*ctx, s, f, p, compiled);
          double worst = 0;
          std::size_t over = 0;
          for (std::size_t i = 0; i < cpu.pixels.size(); ++i) {
            const double d = std::fabs(double(to_display(cpu.pixels[i])) - to_display(gpu.pixels[i]));
            worst = std::max(worst, d);
            over += d > 1e-3;
          }
          if (plain_nodes)
            EXPECT_LE(over, cpu.pixels.size() / 8)
                << "view " << f.view << " time " << f.time << " worst " << worst;
          else
            EXPECT_LE(worst, 1e-3) << "view " << f.view << " time " << f.time;
          std::printf("%s %s view %d t %.2f: %s, worst %.2e, %zu of %zu values over 1e-3\n", name,
                      label.c_str(), f.view, f.time, plain_nodes ? "has plain nodes" : "all smoothed", worst,
                      over, cpu.pixels.size());
        }
      }
      ++points;
      cpp += "#define shade shade_" + std::to_string(points) + "\n#include \"" + dir + "/front/" + label +
             ".hpp\"\n#undef shade\n";
    }
  }
  phase("validate, execute");
  EXPECT_EQ(scenes, 7);
  const std::string es_log = (work / "es.log").string();
  EXPECT_EQ(std::system(
                (std::string(GLSLANG_VALIDATOR) + " -S frag" + es_files + " > " + es_log + " 2>&1").c_str()),
            0)
      << read(es_log);
  std::printf("%d front points and %d footprint-LOD pairs over %d scenes checked\n", points, lods, scenes);
  // The headers are self-contained: they compile against the generated library alone.
  const std::string tu = (work / "all_fronts.cpp").string();
  std::ofstream(tu) << cpp;
  const std::string log = tu + ".log";
  EXPECT_EQ(
      std::system((std::string(BL_CXX) +
                   " -std=c++17 -fsyntax-only -I" BL_SOURCE_DIR "/generated -I" BL_SOURCE_DIR "/runtime " +
                   tu + " > " + log + " 2>&1")
                      .c_str()),
      0)
      << read(log);
  phase("compile the headers");
}
