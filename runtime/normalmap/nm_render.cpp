#include "normalmap/nm_render.hpp"

#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "camera/plane_batch.hpp"
#include "image/image_io.hpp"
#include "render/parallel.hpp"

namespace bl::normalmap {

namespace {

std::uint64_t mix64(std::uint64_t x) {  // splitmix64 finalizer
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

void put(Image& img, int x, int y, const std::array<double, 3>& rgb) {
  for (int c = 0; c < 3; ++c) img.at(x, y, c) = static_cast<float>(rgb[c]);
}

}  // namespace

Image render_technique(const NmScene& s, const NormalMapData& d, Technique t, double* multi_fraction) {
  const Shader shader(s, d);
  const camera::FootprintOptions opt = s.footprint();
  const int w = s.camera.width, hgt = s.camera.height;
  Image img(w, hgt);
  std::atomic<long> hits{0}, multis{0};
  const int rows_per_task = 8, tasks = (hgt + rows_per_task - 1) / rows_per_task;
  render::parallel_rows(tasks, [&](int task) {
    const int y0 = task * rows_per_task, rows = std::min(rows_per_task, hgt - y0);
    camera::PlaneBatch b;
    camera::trace_plane(s.camera, opt, b, camera::PixelRect{0, y0, w, rows});
    long h = 0, mu = 0;
    for (int i = 0; i < int(b.size()); ++i) {
      const int x = i % w, y = y0 + i / w;
      if (!b.hit[i]) {
        put(img, x, y, s.background);
        continue;
      }
      Sample smp;
      smp.u = b.u[i], smp.v = b.v[i], smp.sigma_u = b.sigma_u[i], smp.sigma_v = b.sigma_v[i];
      smp.view = {b.view_x[i], b.view_y[i], b.view_z[i]};
      bool multi = false;
      put(img, x, y, shader.filtered(t, smp, &multi));
      ++h;
      mu += multi;
    }
    hits += h;
    multis += mu;
  });
  if (multi_fraction) *multi_fraction = hits ? double(multis) / double(hits) : 0.0;
  return img;
}

Image render_sampled(const NmScene& s, const NormalMapData& d, int samples, std::uint64_t seed,
                     const std::string& progress_label) {
  const Shader shader(s, d);
  const camera::FootprintOptions opt = s.footprint();
  const camera::Basis basis = camera::basis(s.camera);
  const int w = s.camera.width, hgt = s.camera.height;
  Image img(w, hgt);
  const std::uint64_t key = mix64(seed);
  render::parallel_rows(
      hgt,
      [&](int y) {
        for (int x = 0; x < w; ++x) {
          std::array<double, 3> acc{0, 0, 0};
          const int n = samples > 0 ? samples : 1;
          // Per-pixel stream: splitmix64 from a pixel key, Box-Muller pairs (cheap to seed, so the
          // timing of MSAA n measures the shading, not a generator's set-up).
          std::uint64_t state = mix64(key ^ (static_cast<std::uint64_t>(y) * w + x));
          for (int k = 0; k < n; ++k) {
            double px = x + 0.5, py = y + 0.5;
            if (samples > 0) {
              const double u1 = (double((state = mix64(state)) >> 11) + 0.5) * 0x1.0p-53;
              const double u2 = double((state = mix64(state)) >> 11) * 0x1.0p-53;
              const double r = s.sigma_px * std::sqrt(-2 * std::log(u1));
              px += r * std::cos(2 * M_PI * u2), py += r * std::sin(2 * M_PI * u2);
            }
            const camera::PlaneSample p = camera::trace_pixel(s.camera, basis, opt, px, py);
            const std::array<double, 3> rgb =
                p.hit ? shader.direct(p.u, p.v, {p.view_x, p.view_y, p.view_z}) : s.background;
            for (int c = 0; c < 3; ++c) acc[c] += rgb[c];
          }
          for (double& a : acc) a /= n;
          put(img, x, y, acc);
        }
      },
      progress_label);
  return img;
}

std::string truth_cache_path(const NmScene& s, const NormalMapData& d, const std::string& cache_dir) {
  char name[160];
  std::snprintf(name, sizeof name, "nmtruth_%016llx_%016llx_%s.exr",
                static_cast<unsigned long long>(s.hash()), static_cast<unsigned long long>(d.content_hash),
                kShadingVersion);
  return (std::filesystem::path(cache_dir) / name).string();
}

Image render_truth(const NmScene& s, const NormalMapData& d, const std::string& cache_dir) {
  std::string path;
  if (!cache_dir.empty()) {
    path = truth_cache_path(s, d, cache_dir);
    if (std::filesystem::exists(path)) {
      Image img = read_image(path);
      if (img.width == s.camera.width && img.height == s.camera.height) return img;
    }
  }
  Image img = render_sampled(s, d, s.truth_samples, 0xC0FFEEull, "ground truth " + s.name);
  if (!path.empty()) {
    std::filesystem::create_directories(cache_dir);
    write_exr(path, img);
  }
  return img;
}

}  // namespace bl::normalmap
