// blglsl_bisect: where the emitted GLSL and the C++ evaluator part ways. Renders a scene's frame 0
// both ways, takes the pixels that differ, and walks from the output through the instructions whose
// GLSL value differs at those pixels down to the first one whose arguments still agree; prints it,
// its arguments' values, and the instructions before it.
//
//   blglsl_bisect scenes/suite/checkerboard_bumps.json gaussian
// (This is how the GLSL NaN of bl_tent_sqrt at x = 8.8e-21 was found.)
#include <cmath>
#include <cstdio>

#include "compiler/emit.hpp"
#include "compiler/lower.hpp"
#include "render/glsl_frame.hpp"
#include "render/render.hpp"
using namespace bl;
int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: blglsl_bisect scene.json [rule]\n");
    return 2;
  }
  scene::Scene s = scene::load_scene(argv[1]);
  const std::string rule = argc > 2 ? argv[2] : "gaussian";
  const ir::Graph g = shaders::trace(s.shader_def(), s.effects());
  const auto prog = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule(rule)));
  gl::Context ctx;
  const render::Frame f = render::frames(s).front();
  auto with_out = [&](int i) {
    compiler::Program p = prog;
    int o = i;
    if (p.pair_valued(i)) {
      compiler::Inst m;
      m.op = compiler::LOp::Mean;
      m.arg[0] = i;
      p.insts.push_back(m);
      o = static_cast<int>(p.insts.size()) - 1;
    }
    p.outputs = {o, o, o};
    return p;
  };
  // bad pixels: NaN or big mismatch in the final output
  const Image cpu = render::render_smoothed(s, f, prog), gpu = render::render_glsl(ctx, s, f, prog);
  std::vector<int> bad;
  for (int k = 0; k < s.width * s.height; ++k) {
    const float a = cpu.pixels[3 * k], b = gpu.pixels[3 * k];
    if (!(std::fabs(a - b) <= 1e-2f * std::max(1.0f, std::fabs(a)))) bad.push_back(k);
  }
  std::printf("%zu bad pixels of %d; first %d\n", bad.size(), s.width * s.height, bad.empty() ? -1 : bad[0]);
  if (bad.empty()) return 0;
  auto diverges = [&](int i) {
    const auto p = with_out(i);
    const Image c = render::render_smoothed(s, f, p), q = render::render_glsl(ctx, s, f, p);
    int n = 0;
    for (int k : bad) {
      const float a = c.pixels[3 * k], b = q.pixels[3 * k];
      if (!(std::fabs(a - b) <= 1e-3f * std::max(1.0f, std::fabs(a)))) ++n;
    }
    return n;
  };
  int lo = 0, hi = static_cast<int>(prog.insts.size()) - 1;  // find the first diverging instruction
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    if (diverges(mid) > 0)
      hi = mid;
    else
      lo = mid + 1;
  }
  // Descend through diverging arguments to an instruction whose arguments all agree.
  for (bool moved = true; moved;) {
    moved = false;
    const auto& in = prog.insts[lo];
    for (int a = 0; a < compiler::lop_arity(in) && !moved; ++a)
      if (diverges(in.arg[a]) > 0) {
        lo = in.arg[a];
        moved = true;
      }
  }
  std::printf("first diverging instruction %d (of %zu)\n", lo, prog.insts.size());
  const std::string glsl = compiler::emit_glsl(with_out(lo), "bl_shade");
  // print the instruction line and its operands
  const std::string key = "  float t" + std::to_string(lo) + " ",
                    key2 = "  vec2 t" + std::to_string(lo) + " ";
  size_t at = glsl.find(key);
  if (at == std::string::npos) at = glsl.find(key2);
  std::printf("%s\n", glsl.substr(at, glsl.find('\n', at) - at).c_str());
  for (int t = 0; t < lo; ++t) {  // the instructions it reads, transitively (last 30 lines)
    const std::string k1 = "  float t" + std::to_string(t) + " ", k2 = "  vec2 t" + std::to_string(t) + " ";
    size_t a2 = glsl.find(k1);
    if (a2 == std::string::npos) a2 = glsl.find(k2);
    if (t >= lo - 30) std::printf("%s\n", glsl.substr(a2, glsl.find('\n', a2) - a2).c_str());
  }
  const auto p = with_out(lo);
  const Image c = render::render_smoothed(s, f, p), q = render::render_glsl(ctx, s, f, p);
  for (int j = 0; j < 5 && j < (int)bad.size(); ++j) {
    const int k = bad[j];
    std::printf("pixel %d: cpu %.9g gpu %.9g\n", k, c.pixels[3 * k], q.pixels[3 * k]);
    const auto& in = prog.insts[lo];
    for (int a = 0; a < compiler::lop_arity(in); ++a) {
      const auto pa = with_out(in.arg[a]);
      const Image ca = render::render_smoothed(s, f, pa), qa = render::render_glsl(ctx, s, f, pa);
      std::printf("   arg t%d: cpu %.9g gpu %.9g\n", in.arg[a], ca.pixels[3 * k], qa.pixels[3 * k]);
    }
  }
}
