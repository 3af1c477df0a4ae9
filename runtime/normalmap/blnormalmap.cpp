// blnormalmap: render a normal-map scene by every technique (direct, Toksvig, LEAN, ours, ours
// multi-lobe, MSAA n) and the supersampled ground truth; time each (ms per frame, best of several,
// all cores) and measure RMS and PSNR (display space) and SSIM (display luma); write the images,
// error heatmaps, a side-by-side strip and report.md.
//
//   blnormalmap scenes/normalmap/blinn_phong.json --out docs/textures/normalmap_blinn_phong
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "image/image_io.hpp"
#include "image/metrics.hpp"
#include "image/report.hpp"
#include "image/ssim.hpp"
#include "normalmap/nm_render.hpp"
#include "render/parallel.hpp"

using namespace bl;
using namespace bl::normalmap;

namespace {

template <class F>
double best_ms(int repeats, F&& f) {
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    best = std::min(best,
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"blnormalmap: normal-map filtering techniques against supersampled ground truth"};
  std::string scene_path, out_dir = "normalmap_out", cache_dir = "build/truth_cache";
  int repeats = 3;
  app.add_option("scene", scene_path, "normal-map scene file (JSON)")->required();
  app.add_option("--out", out_dir, "output directory (PNG images, heatmaps, report.md)");
  app.add_option("--cache", cache_dir, "ground-truth cache directory (EXR); empty disables");
  app.add_option("--repeats", repeats, "timed renders per technique (the best counts)")
      ->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);
  try {
    const NmScene s = load_nm_scene(scene_path);
    const NormalMapData d = load_normal_map(s.texture, s.grid);
    std::filesystem::create_directories(out_dir);
    std::printf("%s: %s (%dx%d), image %dx%d, %d threads\n", s.name.c_str(), s.texture.c_str(), d.width(),
                d.height(), s.camera.width, s.camera.height, render::thread_count());
    const Image truth = render_truth(s, d, cache_dir);
    write_png(out_dir + "/truth.png", truth);

    struct Row {
      std::string method;
      double ms, rms, psnr, ssim;
    };
    std::vector<Row> rows;
    std::map<std::string, Image> images;
    auto measure = [&](const std::string& method, const Image& img, double ms) {
      Row r{method, ms, rms_display(img, truth), psnr_display(img, truth), ssim_display(img, truth)};
      write_png(out_dir + "/" + method + ".png", img);
      write_error_heatmap(out_dir + "/" + method + "_error.png", img, truth);
      std::printf("  %-12s %9.2f ms  RMS %.5f  PSNR %6.2f dB  SSIM %.4f\n", method.c_str(), ms, r.rms, r.psnr,
                  r.ssim);
      rows.push_back(r);
      images[method] = img;
    };
    double multi_fraction = 0;
    {
      Image img;
      const double ms = best_ms(repeats, [&] { img = render_sampled(s, d, 0); });
      measure("direct", img, ms);
    }
    for (Technique t : {Technique::Toksvig, Technique::Lean, Technique::Ours, Technique::OursMulti}) {
      Image img;
      const double ms = best_ms(repeats, [&] { img = render_technique(s, d, t, &multi_fraction); });
      measure(technique_name(t), img, ms);
    }
    for (int n : s.msaa) {
      Image img;
      const double ms = best_ms(repeats, [&] { img = render_sampled(s, d, n); });
      measure("msaa" + std::to_string(n), img, ms);
    }

    std::vector<Image> strip{truth};
    std::vector<std::string> labels{"truth"};
    for (const char* m : {"direct", "toksvig", "lean", "ours", "ours_multi", "msaa16"})
      if (images.count(m)) strip.push_back(images[m]), labels.push_back(m);
    write_side_by_side(out_dir + "/side_by_side.png", strip, labels);
    std::vector<Image> heat;
    for (std::size_t i = 1; i < labels.size(); ++i) {
      const std::string p = out_dir + "/" + labels[i] + "_error.png";
      heat.push_back(read_image(p));
    }
    write_side_by_side(out_dir + "/errors_side_by_side.png", heat,
                       std::vector<std::string>(labels.begin() + 1, labels.end()));

    std::ofstream rep(out_dir + "/report.md");
    rep << "# " << s.name << "\n\nScene `" << scene_path << "`, normal map `" << s.texture_text << "` ("
        << d.width() << "x" << d.height() << "), model "
        << (s.material.model == Model::BlinnPhong ? "Blinn-Phong, s = " + std::to_string(s.material.exponent)
                                                  : "GGX, alpha = " + fmt("%g", s.material.alpha))
        << ", image " << s.camera.width << "x" << s.camera.height << ". Ground truth: " << s.truth_samples
        << " Gaussian-jittered direct samples per pixel (sd " << s.sigma_px << " px). Times: best of "
        << repeats << " renders on " << render::thread_count()
        << " threads (CPU, double precision). Errors against the truth: RMS and PSNR over display-space RGB, "
           "SSIM on display luma (11x11 Gaussian window, sd 1.5).\n\n"
        << "Multi-lobe (" << s.grid.longitude << "x" << s.grid.latitude << " cells, threshold sigma_theta > "
        << s.lobe_threshold << " rad, blended up to twice it) taken at " << fmt("%.1f", 100 * multi_fraction)
        << "% of the pixels.\n\n"
        << "| method | ms/frame | RMS | PSNR (dB) | SSIM |\n|---|---:|---:|---:|---:|\n";
    for (const Row& r : rows)
      rep << "| " << r.method << " | " << fmt("%.1f", r.ms) << " | " << fmt("%.5f", r.rms) << " | "
          << fmt("%.2f", r.psnr) << " | " << fmt("%.4f", r.ssim) << " |\n";
    rep << "\n![side by side](side_by_side.png)\n\nErrors (display space, each heatmap scaled to its own "
           "maximum, "
           "printed under it):\n\n![errors](errors_side_by_side.png)\n";
    std::printf("wrote %s/report.md\n", out_dir.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "blnormalmap: %s\n", e.what());
    return 1;
  }
  return 0;
}
