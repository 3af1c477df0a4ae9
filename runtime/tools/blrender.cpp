// blrender: render a scene plain, with MSAA, smoothed by a compiled rule assignment, and as ground
// truth; write PNG images, error heatmaps and a report (RMS in display space, PSNR, SSIM, and times:
// the emitted C++ compiled with -O3 -march=native at run time (bl::jit), next to the batch evaluator's).
// Images and errors come from the batch evaluator, the arithmetic the ground truth and bltune use: the
// compiled code contracts multiply-adds, which moves a large-gain hash (fract(sin(x) * 43758.5453))
// to other values; its image is rendered too and its distance from the evaluator's reported.
//
//   blrender scenes/suite/checkerboard_none.json --rules gaussian --msaa 16 --out out/checker
//   blrender scenes/suite/checkerboard_none.json --schedule out/tune/front.csv:front02   # a tuned point
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "compiler/emit.hpp"
#include "compiler/lower.hpp"
#include "compiler/schedule_csv.hpp"
#include "compiler/supersample.hpp"
#include "gl/egl_runner.hpp"
#include "image/image_io.hpp"
#include "image/metrics.hpp"
#include "image/pixel_check.hpp"
#include "image/report.hpp"
#include "image/ssim.hpp"
#include "render/compiled_frame.hpp"
#include "render/glsl_frame.hpp"
#include "render/render.hpp"
#include "render/value_range.hpp"

using namespace bl;

namespace {

template <class F>
double time_ms(F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"blrender: render a bandlimit scene (plain, MSAA, smoothed, ground truth) and measure errors"};
  std::string scene_path, rules_text = "gaussian", schedule_spec, out_dir = "render_out",
                          cache_dir = "build/truth_cache";
  std::vector<int> msaa{16};
  bool glsl = false;
  int trials = 9;
  jit::Options jo;
  app.add_option("scene", scene_path, "scene file (JSON)")->required();
  auto* rules_opt = app.add_option(
      "--rules", rules_text, "rule for every node (none, dorn, gaussian, mc8, box, tent, rule1:box, ...)");
  app.add_option("--schedule", schedule_spec,
                 "a tuned schedule instead of --rules: FRONT.csv:LABEL (bltune's front.csv, e.g. front02)")
      ->excludes(rules_opt);
  app.add_option("--msaa", msaa, "MSAA sample counts to render");
  std::vector<int> supersample;
  app.add_option(
         "--supersample", supersample,
         "sample counts of supersampling in the shader with a fixed stratified pattern (ssN: the plain "
         "program at N offsets along the screen gradients, compiler/supersample.hpp)")
      ->check(CLI::Range(1, 256));
  app.add_option("--out", out_dir, "output directory (PNG images, heatmaps, report.md, compiled shader)");
  app.add_option("--cache", cache_dir, "ground-truth cache directory (EXR); empty disables");
  app.add_flag("--glsl", glsl, "also render the emitted GLSL on the headless OpenGL driver and compare");
  app.add_option("--trials", trials, "timing trials per variant (the minimum is reported)");
  app.add_option("--jit-cache", jo.cache_dir, "compiled-shader cache directory (default build/jit_cache)");
  app.add_option("--cxx", jo.compiler,
                 "C++ compiler for the compiled-code timings (default $BL_JIT_CXX, $CXX, g++)");
  CLI11_PARSE(app, argc, argv);
  try {
    const scene::Scene s = scene::load_scene(scene_path);
    const ir::Graph g = shaders::trace(s.shader_def(), s.effects());
    const compiler::ChosenSchedule chosen = compiler::choose_schedule(g, rules_text, schedule_spec);
    rules_text = chosen.label;  // names the method in the report and the image files
    const std::string banner = s.name + " / " + chosen.what;
    const compiler::Program prog = compiler::lower(g, chosen.schedule);
    std::filesystem::create_directories(out_dir);
    std::ofstream(out_dir + "/shader.hpp") << compiler::emit_cpp(prog, "shade", banner);
    std::ofstream(out_dir + "/shader.glsl") << compiler::emit_glsl(prog, "shade", banner);
    // The plain program (rule none): what plain and MSAA renders run in compiled code.
    const compiler::Program plain =
        compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("none")));
    std::unique_ptr<jit::CompiledProgram> cplain, cprog;
    std::string jit_error;
    try {
      cplain = std::make_unique<jit::CompiledProgram>(plain, jo);
      cprog = std::make_unique<jit::CompiledProgram>(prog, jo);
      std::printf("compiled code: %s (%s), %s (%s)\n", cplain->library().path().c_str(),
                  cplain->library().from_cache() ? "cached" : "compiled", cprog->library().path().c_str(),
                  cprog->library().from_cache() ? "cached" : "compiled");
    } catch (const jit::Error& e) {
      jit_error = e.what();
      std::fprintf(stderr,
                   "blrender: compiled-code timing unavailable, images and times from the evaluator:\n%s\n",
                   e.what());
    }
    // Stratified supersampling in the shader (ssN), compiled like the other programs.
    std::vector<compiler::Program> ss_programs;
    std::vector<std::unique_ptr<jit::CompiledProgram>> ss_compiled;
    for (int n : supersample) {
      ss_programs.push_back(compiler::stratified_samples(plain, n, s.sigma_px));
      ss_compiled.push_back(jit_error.empty() ? std::make_unique<jit::CompiledProgram>(ss_programs.back(), jo)
                                              : nullptr);
    }
    std::ofstream report(out_dir + "/report.md");
    report
        << "# " << s.name << " (" << s.shader << ")\n\nDAG nodes: " << g.size() << ", lowered instructions ("
        << rules_text << "): " << prog.insts.size() << ", plain: " << plain.insts.size() << ", image "
        << s.width << "x" << s.height << "\n\n"
        << "Times are single-threaded over the frame's pixel inputs (camera tracing excluded), the minimum "
           "of "
        << trials << " trials: *compiled* = the emitted C++ (`shader.hpp`) built with -O3 at run time; "
        << "*evaluator* = the batch evaluator on the same inputs. MSAA n runs the plain program n times per "
           "pixel at counter-based Gaussian-jittered positions; ssN runs it at N fixed stratified offsets "
           "inside one shader call (compiler/supersample.hpp). ns/px counts all samples of a pixel.\n\n"
        << "Images, RMS, PSNR and SSIM come from the evaluator, in the ground truth's arithmetic; *compiled "
           "vs evaluator* is the display RMS between the compiled code's image and the evaluator's (0 up to "
           "rounding unless the shader's output depends on rounding, as a large-gain hash does).\n\n"
        << "RMS and PSNR on the unclamped display curve (values outside [0, 1] count with their distance, a "
           "NaN/inf channel as 1); NaN px / range px: pixels with a NaN or infinite channel / with a channel "
           "outside [0, 1] widened to the ground truth's range; min / max: the finite values (all "
           "channels).\n\n"
        << (jit_error.empty()
                ? ""
                : "**Compiled code unavailable** (" + jit_error.substr(0, jit_error.find('\n')) +
                      "): images from the evaluator, compiled columns empty.\n\n")
        << "| frame | method | compiled ns/px | compiled ms/frame | evaluator ns/px | evaluator ms/frame | "
           "RMS "
           "(display) | PSNR (dB) | SSIM | NaN px | range px | min | max | compiled vs evaluator |\n"
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    std::printf("%s: %d nodes, %zu instructions with %s\n", s.name.c_str(), g.size(), prog.insts.size(),
                rules_text.c_str());
    std::unique_ptr<gl::Context> ctx;
    if (glsl) {
      const auto av = gl::Context::availability();
      if (av.ok)
        ctx = std::make_unique<gl::Context>();
      else
        std::printf("GLSL: skipped, no OpenGL driver (%s)\n", av.reason.c_str());
    }
    auto fmt = [](double v) {
      char b[32];
      std::snprintf(b, sizeof b, "%.3f", v);
      return std::string(b);
    };
    // The largest distance between a compiled image and the evaluator's, and the row it was seen on.
    double worst_drift = 0;
    std::string worst_drift_row;
    const std::vector<render::Frame> frames = render::frames(s);
    std::vector<Image> truths;
    for (const render::Frame& f : frames) truths.push_back(render::render_truth(s, f, cache_dir));
    const ValueRange range = render::valid_range(s, g, truths);  // over all frames
    for (std::size_t fi = 0; fi < frames.size(); ++fi) {
      const render::Frame& f = frames[fi];
      char tag[64];
      std::snprintf(tag, sizeof tag, "v%d_t%.3f", f.view, f.time);
      const Image& truth = truths[fi];
      write_png(out_dir + "/" + tag + "_truth.png", truth);
      auto row = [&](const std::string& method, const Image& img, const render::FrameTiming* compiled,
                     const render::FrameTiming& eval, double drift) {
        const double rms = rms_display(img, truth), psnr = psnr_display(img, truth),
                     ssim = ssim_display(img, truth);
        const PixelCounts bad = check_pixels(img, range);
        float lo = INFINITY, hi = -INFINITY;
        for (float v : img.pixels)
          if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
        write_png(out_dir + "/" + tag + "_" + method + ".png", img);
        write_error_heatmap(out_dir + "/" + tag + "_" + method + "_error.png", img, truth);
        report << "| " << tag << " | " << method << " | " << (compiled ? fmt(compiled->ns_per_pixel) : "-")
               << " | " << (compiled ? fmt(compiled->ms_per_frame) : "-") << " | " << fmt(eval.ns_per_pixel)
               << " | " << fmt(eval.ms_per_frame) << " | " << rms << " | " << psnr << " | " << ssim << " | "
               << bad.nonfinite << " | " << bad.out_of_range << " | " << lo << " | " << hi << " | "
               << (compiled ? std::to_string(drift) : "-") << " |\n";
        std::printf(
            "  %s %-12s compiled %9.2f ns/px %8.3f ms  evaluator %9.2f ns/px  RMS %.5f  PSNR %.2f dB  SSIM "
            "%.4f  NaN/inf px %zu  out-of-range px %zu  [%.3g, %.3g]  compiled vs evaluator %.2e\n",
            tag, method.c_str(), compiled ? compiled->ns_per_pixel : NAN,
            compiled ? compiled->ms_per_frame : NAN, eval.ns_per_pixel, rms, psnr, ssim, bad.nonfinite,
            bad.out_of_range, lo, hi, drift);
      };
      // One variant: its image from the evaluator, both timings, and how far the compiled code's image is.
      auto variant = [&](const std::string& method, const compiler::Program& p,
                         const jit::CompiledProgram* cp, int samples) {
        const render::BatchRunner ev = render::evaluator_runner(p);
        const Image img = render::render_program(s, f, p, ev, samples);
        const render::FrameTiming te = render::time_program(s, f, p, ev, samples, trials);
        if (cp) {
          const render::BatchRunner run = render::compiled_runner(*cp);
          const double drift = rms_display(render::render_program(s, f, p, run, samples), img);
          if (!(drift <= worst_drift)) worst_drift = drift, worst_drift_row = std::string(tag) + " " + method;
          const render::FrameTiming tc = render::time_program(s, f, p, run, samples, trials);
          row(method, img, &tc, te, drift);
        } else {
          row(method, img, nullptr, te, NAN);
        }
        return img;
      };
      variant("plain", plain, cplain.get(), 0);
      for (int n : msaa) variant("msaa" + std::to_string(n), plain, cplain.get(), n);
      for (std::size_t k = 0; k < supersample.size(); ++k)
        variant("ss" + std::to_string(supersample[k]), ss_programs[k], ss_compiled[k].get(), 0);
      const Image img = variant(rules_text, prog, cprog.get(), 0);
      if (ctx) {
        Image gimg;
        const double ms = time_ms([&] { gimg = render::render_glsl(*ctx, s, f, prog); });
        report << "| " << tag << " | " << rules_text << "_glsl | - | " << fmt(ms)
               << " (GL driver, incl. upload) | - | - | " << rms_display(gimg, truth) << " | "
               << psnr_display(gimg, truth) << " | " << ssim_display(gimg, truth) << " | "
               << check_pixels(gimg, range).nonfinite << " | " << check_pixels(gimg, range).out_of_range
               << " | | | - |\n";
        write_png(out_dir + "/" + tag + "_" + rules_text + "_glsl.png", gimg);
        std::printf("  %s %-12s GL %9.2f ms  RMS %.5f; GLSL vs evaluator: RMS %.2e (display)\n", tag,
                    (rules_text + "_glsl").c_str(), ms, rms_display(gimg, truth), rms_display(gimg, img));
      }
    }
    // Rounding alone moves a compiled image this far only when the output depends on it: say so where
    // a user compares with images from their own renderer.
    if (worst_drift > 1e-3) {
      char rms[32];
      std::snprintf(rms, sizeof rms, "%.4f", worst_drift);
      const std::string b =
          std::string("The compiled code's image differs from the evaluator's by display RMS ") + rms + " (" +
          worst_drift_row +
          "): this shader's output depends on rounding (a large-gain hash such as fract(sin(x) * 43758.5453) "
          "turns a contracted multiply-add into another value). The errors above are in the evaluator's "
          "arithmetic, the ground truth's; a renderer (or GPU driver) that rounds differently sees its own "
          "hash values.";
      report << "\n" << b << "\n";
      std::printf("note: %s\n", b.c_str());
    }
    std::printf("wrote %s/report.md\n", out_dir.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "blrender: %s\n", e.what());
    return 1;
  }
  return 0;
}
