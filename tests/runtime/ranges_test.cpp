// Value ranges of graph nodes (ir/ranges) against intervals worked out by hand, and Dorn's output
// kept inside its node's range (issue 13: all-Dorn gave up to 10.95 on a [0.05, 0.95] shader).
#include "ir/ranges.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "compiler/evaluator.hpp"
#include "compiler/lower.hpp"
#include "render/frame.hpp"
#include "render/render.hpp"
#include "scene/scene.hpp"
#include "shaders/shader.hpp"

using namespace bl;

TEST(Ranges, HandBuiltGraph) {
  ir::Graph g;
  const int u = g.input("u", true);
  const int s = g.call("saturate", u);  // [0, 1]
  const int p8 = g.call("pow8", s);     // [0, 1]: monotone on [0, 1]
  const int lin = g.add({ir::Op::Add, -1, g.add({ir::Op::Mul, -1, g.constant(0.9), p8}), g.constant(0.05)});
  const int sn = g.call("sin", u);    // [-1, 1]
  const int sq = g.call("pow2", sn);  // [0, 1]: 0 inside [-1, 1]
  const int ex = g.call("exp", sn);   // [e^-1, e]
  const int q = g.add({ir::Op::Div, -1, p8, g.add({ir::Op::Add, -1, sq, g.constant(1)})});  // [0, 1]/[1, 2]
  const int bad = g.add({ir::Op::Div, -1, p8, sn});  // divisor straddles 0: unbounded
  const int sel = g.add({ir::Op::Select, -1, g.add({ir::Op::Less, -1, u, g.constant(0)}), ex, lin});
  const int md = g.add({ir::Op::Mod, -1, u, -1, -1, 2.5});
  const int lg = g.call("log", sq);               // log at 0: the catalog's range
  const int uu = g.add({ir::Op::Mul, -1, u, u});  // a square of an unbounded input: [0, inf)
  const int shifted = g.add({ir::Op::Add, -1, sn, g.constant(2)});
  const int ss = g.add({ir::Op::Mul, -1, shifted, shifted});  // [1, 3]^2 = [1, 9]
  const int sx = g.add({ir::Op::Mul, -1, sn, ex});            // two factors: the hull, [-e, e]
  const auto r = ir::node_ranges(g);
  auto expect = [&](int n, double lo, double hi) {
    EXPECT_NEAR(r[n].lo, lo, 1e-12) << g.to_string();
    EXPECT_NEAR(r[n].hi, hi, 1e-12) << g.to_string();
  };
  EXPECT_TRUE(std::isinf(r[u].lo) && std::isinf(r[u].hi));
  EXPECT_FALSE(r[u].bounded());
  expect(s, 0, 1);
  expect(p8, 0, 1);
  expect(lin, 0.05, 0.95);
  expect(sq, 0, 1);
  expect(ex, std::exp(-1.0), std::exp(1.0));
  expect(q, 0, 1);
  EXPECT_TRUE(std::isinf(r[bad].lo) && std::isinf(r[bad].hi));
  expect(sel, 0.05, std::exp(1.0));
  expect(md, 0, 2.5);
  EXPECT_TRUE(std::isinf(r[lg].lo) && std::isinf(r[lg].hi));
  EXPECT_EQ(r[uu].lo, 0);
  EXPECT_TRUE(std::isinf(r[uu].hi));
  expect(ss, 1, 9);
  expect(sx, -std::exp(1.0), std::exp(1.0));
}

// 0.05 + 0.9 pow8(saturate(u)) with a wide footprint: Dorn's Gaussian mean of pow8 with the capped
// sd 0.5 of saturate is E[X^8] for X ~ N(m, 0.5^2), m = saturate's mean: 3.0 at m = 0.5, 28 at
// m = 1 (Gaussian moments); the plain values, and so any average of them, lie in [0.05, 0.95]
// (measured before the clamp: up to 2.2 on this grid).
TEST(Ranges, DornStaysInsideTheNodeRange) {
  ir::Graph g;
  const int u = g.input("u", true);
  const int p8 = g.call("pow8", g.call("saturate", u));
  const int out = g.add({ir::Op::Add, -1, g.add({ir::Op::Mul, -1, g.constant(0.9), p8}), g.constant(0.05)});
  g.add_output("r", out);
  const compiler::Program p = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("dorn")));
  const int n = 64;
  std::vector<float> m(n), sd(n), zero(n, 0.0f), o(n);
  for (int i = 0; i < n; ++i) m[i] = -1.0f + 3.0f * i / (n - 1), sd[i] = i % 2 ? 5.0f : 0.05f;
  compiler::Batch b;
  b.count = n;
  b.mean = {m.data()};
  b.sd = {sd.data()};
  b.grad_x = b.grad_y = {zero.data()};
  compiler::Evaluator(p).run(b, {o.data()});
  for (int i = 0; i < n; ++i) {
    EXPECT_GE(o[i], 0.05f - 1e-6f) << "u " << m[i] << " sd " << sd[i];
    EXPECT_LE(o[i], 0.95f + 1e-6f) << "u " << m[i] << " sd " << sd[i];
  }
}

// Every suite scene (lit ones included) all-Dorn: every node with a bounded range, evaluated at
// every pixel the plane covers, stays inside it (before the clamp: the Phong specular
// pow8(saturate(.)) reached ~6 on the bumps scenes, ~2 on ripples; scene outputs up to 6.2).
TEST(Ranges, AllDornSuiteNodesInsideTheirRanges) {
  int checked = 0;
  for (const char* pat :
       {"bricks", "checkerboard", "circles", "color_circles", "fire", "quadratic_sine", "zigzag"})
    for (const char* fx : {"none", "bumps", "ripples"}) {
      const std::string name = std::string(pat) + "_" + fx;
      scene::Scene s = scene::load_scene(std::string(BL_SCENES_DIR "/suite/") + name + ".json");
      s.width = s.height = 32;
      ir::Graph g = shaders::trace(shaders::find_shader(s.shader), s.effects());
      const auto r = ir::node_ranges(g);
      std::vector<int> nodes;  // bounded computation nodes, made outputs so their values can be read
      for (int n = 0; n < g.size(); ++n)
        if (r[n].bounded() && g.node(n).op != ir::Op::Const) {
          nodes.push_back(n);
          g.add_output("n" + std::to_string(n), n);
        }
      const compiler::Program p =
          compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("dorn")));
      for (const render::Frame& f : render::frames(s)) {
        camera::PlaneBatch all, hits;
        camera::trace_plane(render::make_camera(s, f.view), render::footprint_options(s), all);
        std::vector<int> idx;
        for (std::size_t i = 0; i < all.size(); ++i)
          if (all.hit[i]) idx.push_back(static_cast<int>(i));
        hits = all.gather(idx);
        render::InputStorage storage;
        const compiler::Batch b = render::bind_inputs(p, hits, s, f, storage);
        std::vector<std::vector<float>> out(p.outputs.size(), std::vector<float>(idx.size()));
        std::vector<float*> ptr;
        for (auto& o : out) ptr.push_back(o.data());
        compiler::Evaluator(p).run(b, ptr);
        for (std::size_t k = 0; k < nodes.size(); ++k) {
          const ir::Interval& want = r[nodes[k]];
          const std::vector<float>& v = out[3 + k];
          const float lo = *std::min_element(v.begin(), v.end()), hi = *std::max_element(v.begin(), v.end());
          // 1e-5: the clamp constants are floats.
          EXPECT_GE(lo, want.lo - 1e-5 * (1 + std::fabs(want.lo))) << name << " node " << nodes[k];
          EXPECT_LE(hi, want.hi + 1e-5 * (1 + std::fabs(want.hi))) << name << " node " << nodes[k];
          ++checked;
        }
      }
    }
  std::printf("%d (scene frame, node) pairs checked\n", checked);
  EXPECT_GT(checked, 1000);
}
