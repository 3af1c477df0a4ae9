// blrender: render a scene plain, with MSAA, smoothed by a compiled rule assignment, and as ground
// truth; write PNG images, error heatmaps and a report (RMS in display space, PSNR, SSIM, ms per frame).
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

#include "compiler/emit.hpp"
#include "compiler/lower.hpp"
#include "compiler/schedule_csv.hpp"
#include "gl/egl_runner.hpp"
#include "image/image_io.hpp"
#include "image/metrics.hpp"
#include "image/pixel_check.hpp"
#include "image/report.hpp"
#include "image/ssim.hpp"
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
  app.add_option("scene", scene_path, "scene file (JSON)")->required();
  auto* rules_opt = app.add_option(
      "--rules", rules_text, "rule for every node (none, dorn, gaussian, mc8, box, tent, rule1:box, ...)");
  app.add_option("--schedule", schedule_spec,
                 "a tuned schedule instead of --rules: FRONT.csv:LABEL (bltune's front.csv, e.g. front02)")
      ->excludes(rules_opt);
  app.add_option("--msaa", msaa, "MSAA sample counts to render");
  app.add_option("--out", out_dir, "output directory (PNG images, heatmaps, report.md, compiled shader)");
  app.add_option("--cache", cache_dir, "ground-truth cache directory (EXR); empty disables");
  app.add_flag("--glsl", glsl, "also render the emitted GLSL on the headless OpenGL driver and compare");
  CLI11_PARSE(app, argc, argv);
  try {
    const scene::Scene s = scene::load_scene(scene_path);
    const ir::Graph g = shaders::trace(shaders::find_shader(s.shader), s.effects());
    compiler::Schedule schedule;
    std::string banner = s.name + " / " + rules_text;
    if (!schedule_spec.empty()) {
      const compiler::LoadedSchedule l = compiler::load_schedule(schedule_spec, g);
      schedule = l.schedule;
      rules_text = l.label;  // names the method in the report and the image files
      banner = s.name + " / " + l.file + ":" + l.label + ": " + l.text;
    } else {
      schedule = compiler::uniform_schedule(g, rules::parse_rule(rules_text));
    }
    const compiler::Program prog = compiler::lower(g, schedule);
    std::filesystem::create_directories(out_dir);
    std::ofstream(out_dir + "/shader.hpp") << compiler::emit_cpp(prog, "shade", banner);
    std::ofstream(out_dir + "/shader.glsl") << compiler::emit_glsl(prog, "shade", banner);
    std::ofstream report(out_dir + "/report.md");
    report
        << "# " << s.name << " (" << s.shader << ")\n\nDAG nodes: " << g.size() << ", lowered instructions ("
        << rules_text << "): " << prog.insts.size() << ", image " << s.width << "x" << s.height << "\n\n"
        << "RMS and PSNR on the unclamped display curve (values outside [0, 1] count with their distance, a "
           "NaN/inf channel as 1); NaN px / range px: pixels with a NaN or infinite channel / with a channel "
           "outside [0, 1] widened to the ground truth's range; min / max: the finite values (all "
           "channels).\n\n"
        << "| frame | method | ms/frame | RMS (display) | PSNR (dB) | SSIM | NaN px | range px | min | max "
           "|\n|---|---|---|---|---|---|---|---|---|---|\n";
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
      auto row = [&](const std::string& method, const Image& img, double ms) {
        const double rms = rms_display(img, truth), psnr = psnr_display(img, truth),
                     ssim = ssim_display(img, truth);
        const PixelCounts bad = check_pixels(img, range);
        float lo = INFINITY, hi = -INFINITY;
        for (float v : img.pixels)
          if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
        write_png(out_dir + "/" + tag + "_" + method + ".png", img);
        write_error_heatmap(out_dir + "/" + tag + "_" + method + "_error.png", img, truth);
        report << "| " << tag << " | " << method << " | " << ms << " | " << rms << " | " << psnr << " | "
               << ssim << " | " << bad.nonfinite << " | " << bad.out_of_range << " | " << lo << " | " << hi
               << " |\n";
        std::printf(
            "  %s %-12s %9.2f ms  RMS %.5f  PSNR %.2f dB  SSIM %.4f  NaN/inf px %zu  out-of-range px %zu  "
            "[%.3g, %.3g]\n",
            tag, method.c_str(), ms, rms, psnr, ssim, bad.nonfinite, bad.out_of_range, lo, hi);
      };
      Image img;
      double ms = time_ms([&] { img = render::render_native(s, f, 0); });
      row("plain", img, ms);
      for (int n : msaa) {
        ms = time_ms([&] { img = render::render_native(s, f, n); });
        row("msaa" + std::to_string(n), img, ms);
      }
      ms = time_ms([&] { img = render::render_smoothed(s, f, prog); });
      row(rules_text, img, ms);
      if (ctx) {
        Image gimg;
        ms = time_ms([&] { gimg = render::render_glsl(*ctx, s, f, prog); });
        row(rules_text + "_glsl", gimg, ms);
        std::printf("  GLSL vs C++ evaluator: RMS %.2e (display)\n", rms_display(gimg, img));
      }
    }
    std::printf("wrote %s/report.md\n", out_dir.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "blrender: %s\n", e.what());
    return 1;
  }
  return 0;
}
