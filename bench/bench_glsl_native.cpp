// bench_glsl_native: native (float) evaluation of the 7 suite patterns written in GLSL (the traced
// graph run by glsl::NativeProgram) against the C++ templates instantiated with float, through the
// same shaders::shade call the ground truth uses. Prints ns per sample and the GLSL / C++ ratio, one
// run, and what 1024-spp ground truth at 192^2 costs at that speed (one core).
//
//   build/bin/bench_glsl_native [scenes/glsl]
#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "glsl/shader.hpp"
#include "shaders/shader.hpp"

using namespace bl;

namespace {

double ns_per_sample(const shaders::ShaderDef& d, const shaders::Effects& fx,
                     const std::vector<shaders::Inputs<float>>& in, float* sink) {
  const int reps = 5;
  double best = 1e30;
  for (int r = 0; r < reps; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    float acc = 0;
    for (const auto& x : in) {
      const auto c = shaders::shade(d, fx, x);
      acc += c.x + c.y + c.z;
    }
    const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
    best = std::min(best, ns / in.size());
    *sink += acc;
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : "scenes/glsl";
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> U(-8, 8), T(0, 3);
  std::vector<shaders::Inputs<float>> in(200000);
  for (auto& x : in) x = {U(rng), U(rng), T(rng), {0.3f, -0.2f, 0.933f}, {0.4f, 0.3f, 0.866f}};
  float sink = 0;
  std::printf(
      "| pattern | effects | C++ ns/sample | GLSL ns/sample | GLSL / C++ | truth 192^2 x 1024 (GLSL, 1 core) "
      "|\n");
  std::printf("|---|---|---|---|---|---|\n");
  for (const std::string& name : shaders::base_shader_names()) {
    const auto g = glsl::load_shader(dir + "/" + name + ".glsl");
    const shaders::ShaderDef& c = shaders::find_shader(name);
    for (int e = 0; e < 2; ++e) {
      shaders::Effects fx;
      fx.animated = true;
      if (e == 1) fx.parallax = shaders::Parallax::Bumps, fx.lighting = shaders::Lighting::Phong;
      const double tc = ns_per_sample(c, fx, in, &sink), tg = ns_per_sample(*g, fx, in, &sink);
      std::printf("| %s | %s | %.1f | %.1f | %.2f | %.1f s |\n", name.c_str(), e ? "bumps+phong" : "none", tc,
                  tg, tg / tc, tg * 192 * 192 * 1024 * 1e-9);
    }
  }
  std::fprintf(stderr, "(checksum %g)\n", sink);
  return 0;
}
