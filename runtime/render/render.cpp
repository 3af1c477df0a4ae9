#include "render/render.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "camera/plane_batch.hpp"
#include "compiler/evaluator.hpp"
#include "image/image_io.hpp"
#include "render/frame.hpp"
#include "render/jitter.hpp"
#include "render/parallel.hpp"

namespace bl::render {

namespace {

void set_pixel(Image& img, int x, int y, const double* rgb) {
  for (int c = 0; c < 3; ++c) img.at(x, y, c) = static_cast<float>(rgb[c]);
}

}  // namespace

double uniform_input(const scene::Scene& s, const Frame& f, const std::string& name) {
  if (name == "time") return f.time;
  if (name == "light_x") return s.light_dir[0];
  if (name == "light_y") return s.light_dir[1];
  if (name == "light_z") return s.light_dir[2];
  throw std::invalid_argument("renderer: the program reads an unknown input '" + name + "'");
}

compiler::Batch bind_inputs(const compiler::Program& p, const camera::PlaneBatch& b, const scene::Scene& s,
                            const Frame& f, InputStorage& storage) {
  const int n = static_cast<int>(b.size());
  storage.zeros.assign(n, 0.0f);
  storage.constants.clear();
  storage.constants.reserve(p.input_names.size());  // pointers into it stay valid
  const float* zero = storage.zeros.data();
  compiler::Batch batch;
  batch.count = n;
  for (const std::string& name : p.input_names) {
    const float* mean = nullptr;
    const float *sd = zero, *gx = zero, *gy = zero;
    if (name == "u") {
      mean = b.u.data(), sd = b.sigma_u.data(), gx = b.du_dx.data(), gy = b.du_dy.data();
    } else if (name == "v") {
      mean = b.v.data(), sd = b.sigma_v.data(), gx = b.dv_dx.data(), gy = b.dv_dy.data();
    } else if (name == "view_x") {
      mean = b.view_x.data();
    } else if (name == "view_y") {
      mean = b.view_y.data();
    } else if (name == "view_z") {
      mean = b.view_z.data();
    } else {
      storage.constants.emplace_back(n, static_cast<float>(uniform_input(s, f, name)));
      mean = storage.constants.back().data();
    }
    batch.mean.push_back(mean);
    batch.sd.push_back(sd);
    batch.grad_x.push_back(gx);
    batch.grad_y.push_back(gy);
  }
  batch.textures = s.texture_slots(p.texture_names);
  return batch;
}

std::vector<Frame> frames(const scene::Scene& s) {
  std::vector<Frame> out;
  for (int v = 0; v < static_cast<int>(s.views.size()); ++v)
    for (double t : s.animated() ? s.times : std::vector<double>{s.times.front()}) out.push_back({v, t});
  return out;
}

Image render_native(const scene::Scene& s, const Frame& f, int samples, std::uint64_t seed,
                    const std::string& progress_label) {
  const camera::Camera cam = make_camera(s, f.view);
  const camera::Basis basis = camera::basis(cam);
  const camera::FootprintOptions opt = footprint_options(s);
  const shaders::ShaderDef& shader = s.shader_def();
  const shaders::Effects fx = s.effects();
  Image img(s.width, s.height);
  const std::uint64_t key = frame_key(seed, f.view, f.time);
  parallel_rows(
      s.height,
      [&](int y) {
        for (int x = 0; x < s.width; ++x) {
          double acc[3] = {0, 0, 0};
          const int n = samples > 0 ? samples : 1;
          const std::uint64_t pixel = static_cast<std::uint64_t>(y) * s.width + x;
          for (int k = 0; k < n; ++k) {
            double px = x + 0.5, py = y + 0.5;
            if (samples > 0) {
              const Offset o = gaussian_jitter(key, pixel, static_cast<std::uint32_t>(k), s.sigma_px);
              px += o.x;
              py += o.y;
            }
            const camera::PlaneSample p = camera::trace_pixel(cam, basis, opt, px, py);
            if (!p.hit) {
              for (int c = 0; c < 3; ++c) acc[c] += s.background[c];
              continue;
            }
            const auto rgb = shaders::shade(shader, fx, native_inputs(s, p, f.time));
            acc[0] += rgb.x;
            acc[1] += rgb.y;
            acc[2] += rgb.z;
          }
          for (double& a : acc) a /= n;
          set_pixel(img, x, y, acc);
        }
      },
      progress_label);
  return img;
}

Image render_smoothed(const scene::Scene& s, const Frame& f, const compiler::Program& program) {
  if (program.outputs.size() != 3)
    throw std::invalid_argument("render_smoothed: the program has " + std::to_string(program.outputs.size()) +
                                " outputs, a colour needs 3");
  const camera::Camera cam = make_camera(s, f.view);
  const camera::FootprintOptions opt = footprint_options(s);
  Image img(s.width, s.height);
  // Blocks of rows: one evaluator (its registers) and one camera batch per block.
  const int rows_per_task = 8, tasks = (s.height + rows_per_task - 1) / rows_per_task;
  parallel_rows(tasks, [&](int task) {
    const int y0 = task * rows_per_task, rows = std::min(rows_per_task, s.height - y0);
    camera::PlaneBatch b;
    camera::trace_plane(cam, opt, b, camera::PixelRect{0, y0, s.width, rows});
    const int n = s.width * rows;
    InputStorage storage;
    const compiler::Batch batch = bind_inputs(program, b, s, f, storage);
    std::vector<std::vector<float>> out(3, std::vector<float>(n));
    compiler::Evaluator ev(program);
    ev.run(batch, {out[0].data(), out[1].data(), out[2].data()});
    for (int i = 0; i < n; ++i) {
      double rgb[3];
      for (int c = 0; c < 3; ++c) rgb[c] = covered(b, i, out[c][i], s.background[c]);
      set_pixel(img, i % s.width, y0 + i / s.width, rgb);
    }
  });
  return img;
}

std::string truth_cache_path(const scene::Scene& s, const Frame& f, const std::string& cache_dir) {
  const std::uint64_t shader_hash = shaders::trace(s.shader_def(), s.effects()).hash();
  // The footprint bound sets only a smoothed shader's input widths; the truth (jittered samples of
  // the plain shader) never reads it, so both bounds share one truth, keyed as Dorn's (the default
  // until 419a771) so that existing cache files keep their names.
  scene::Scene key = s;
  key.footprint_bound = scene::FootprintBound::Dorn;
  char name[160];
  std::snprintf(name, sizeof name, "truth_cb_%016llx_%016llx_v%d_t%.6f.exr",
                static_cast<unsigned long long>(key.hash()), static_cast<unsigned long long>(shader_hash),
                f.view, f.time);
  return (std::filesystem::path(cache_dir) / name).string();
}

Image render_truth(const scene::Scene& s, const Frame& f, const std::string& cache_dir) {
  std::string path;
  if (!cache_dir.empty()) {
    path = truth_cache_path(s, f, cache_dir);
    if (std::filesystem::exists(path)) {
      Image img = read_image(path);
      if (img.width == s.width && img.height == s.height) return img;
    }
  }
  // A seed distinct from MSAA renders' default so truth and MSAA noise are independent.
  Image img = render_native(s, f, s.truth_samples, 0xC0FFEEull,
                            "ground truth " + s.name + " view " + std::to_string(f.view));
  if (!path.empty()) {
    std::filesystem::create_directories(cache_dir);
    write_exr(path, img);
  }
  return img;
}

}  // namespace bl::render
