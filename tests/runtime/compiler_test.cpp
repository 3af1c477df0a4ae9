// The compiler: emitted C++ computes what the evaluator computes; the all-"none" program is the
// native shader; dead code is gone; single-node rules agree with closed forms from the literature.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <random>
#include <set>

#include "compiler/evaluator.hpp"
#include "compiler/functions.hpp"
#include "compiler/lower.hpp"
#include "dsl/math.hpp"
#include "fixtures.hpp"
#include "ir/atomics.hpp"
#include "tests/runtime/fixture_list.hpp"
#include "tests/runtime/one_pixel.hpp"
#include "tests/runtime/quadrature.hpp"
#include "tests/runtime/random_pixels.hpp"

namespace bl {
namespace {

// Random pixel inputs: u, v in [-8, 8], footprint sd in [1e-3, 0.4] (tests/runtime/random_pixels.hpp).
struct Pixels : testing::RandomPixels {
  Pixels(const compiler::Program& p, int count, unsigned seed) : RandomPixels(p, count, seed, 8.0f, 0.4f) {}
};

std::vector<std::vector<float>> evaluate(const compiler::Program& p, const Pixels& px,
                                         const texture::Bindings& textures = {}) {
  std::vector<std::vector<float>> out(p.outputs.size(), std::vector<float>(px.n));
  std::vector<float*> ptr;
  for (auto& o : out) ptr.push_back(o.data());
  compiler::Batch b = px.batch();
  for (const auto& t : textures) b.textures.push_back(t.get());
  compiler::Evaluator(p).run(b, ptr);
  return out;
}

// A small irregular texture per slot a shader declares (its values only need to differ texel to
// texel: the native shader and the evaluator must read the same ones).
texture::Bindings synthetic_textures(const shaders::ShaderDef& def) {
  texture::Bindings out;
  for (const auto& slot : def.textures) {
    texture::Level L;
    L.width = L.height = 16;
    L.channels = slot.channels;
    for (int i = 0; i < 16 * 16 * slot.channels; ++i)
      L.texels.push_back(static_cast<float>((i * 37) % 23) / 22.0f);
    out.push_back(
        std::make_shared<const texture::Texture>(texture::make_texture(slot.name, "<synthetic>", L)));
  }
  return out;
}

TEST(Compiler, EmittedCppMatchesEvaluator) {
  const auto list = test::fixture_list();
  ASSERT_EQ(list.size(), std::size(test::kFixtureFns));
  for (std::size_t f = 0; f < list.size(); ++f) {
    const compiler::Program p = test::compile_fixture(list[f]);
    const Pixels px(p, 300, 17 + static_cast<unsigned>(f));
    const auto ev = evaluate(p, px);
    std::vector<float> m(p.input_count), s(p.input_count), gx(p.input_count), gy(p.input_count);
    float out[3];
    double worst = 0;
    for (int i = 0; i < px.n; ++i) {
      for (int j = 0; j < p.input_count; ++j)
        m[j] = px.mean[j][i], s[j] = px.sd[j][i], gx[j] = px.gx[j][i], gy[j] = px.gy[j][i];
      test::kFixtureFns[f](m.data(), s.data(), gx.data(), gy.data(), out);
      for (int c = 0; c < 3; ++c) {
        if (std::isnan(ev[c][i]) && std::isnan(out[c])) continue;
        worst = std::max(worst, std::fabs(static_cast<double>(out[c]) - ev[c][i]) /
                                    std::max(1.0, std::fabs(static_cast<double>(ev[c][i]))));
      }
    }
    EXPECT_LE(worst, 1e-6) << list[f].label();
  }
}

// The all-"none" program is the plain shader: compare with the native float instantiation of the
// same template (an independent path: no tracing, no lowering).
TEST(Compiler, NoneScheduleIsTheNativeShader) {
  for (const auto& def : shaders::suite())
    for (int p = 0; p < 3; ++p) {
      shaders::Effects fx;
      fx.parallax = static_cast<shaders::Parallax>(p);
      fx.lighting = p ? shaders::Lighting::Phong : shaders::Lighting::None;
      fx.animated = true;
      const ir::Graph g = shaders::trace(def, fx);
      const compiler::Program prog =
          compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("none")));
      const Pixels px(prog, 400, 5);
      const texture::Bindings textures = synthetic_textures(def);
      const auto ev = evaluate(prog, px, textures);
      int bad = 0;
      for (int i = 0; i < px.n; ++i) {
        shaders::Inputs<float> in{0, 0, 0, {0, 0, 1}, {0, 0, 1}};
        in.textures = &textures;
        for (int j = 0; j < prog.input_count; ++j) {
          const std::string& name = prog.input_names[j];
          const float v = px.mean[j][i];
          if (name == "u") in.u = v;
          if (name == "v") in.v = v;
          if (name == "time") in.time = v;
          if (name == "view_x") in.view.x = v;
          if (name == "view_y") in.view.y = v;
          if (name == "view_z") in.view.z = v;
          if (name == "light_x") in.light.x = v;
          if (name == "light_y") in.light.y = v;
          if (name == "light_z") in.light.z = v;
        }
        const auto c = shaders::shade(def, fx, in);
        const float want[3] = {c.x, c.y, c.z};
        for (int k = 0; k < 3; ++k)
          if (!(std::fabs(want[k] - ev[k][i]) <= 1e-4f * std::max(1.0f, std::fabs(want[k])))) ++bad;
      }
      // Constants folded in double may round differently from float arithmetic right at a jump:
      // allow a handful of such samples, not more.
      EXPECT_LE(bad, 3) << def.name << " parallax " << p;
    }
}

// optimize() keeps the naive lowering's values: every suite shader (flat and parallax) under the
// main rules, the optimized program against the unoptimized one, both in the evaluator. Without
// x * 0 -> 0, folding only reassociates constant products and splits sqrt(k y), so outputs agree
// to float rounding (a pixel where the naive program is NaN or infinite is skipped). With it,
// values differ only where the zeroed x was infinite or NaN (see OptimizeOptions): counted, and
// the optimized program must then be finite there.
TEST(Compiler, OptimizeKeepsTheNaiveValues) {
  for (const auto& def : shaders::suite())
    for (int p = 0; p < 2; ++p) {
      shaders::Effects fx;
      fx.parallax = static_cast<shaders::Parallax>(p);
      fx.lighting = p ? shaders::Lighting::Phong : shaders::Lighting::None;
      const ir::Graph g = shaders::trace(def, fx);
      const texture::Bindings textures = synthetic_textures(def);
      for (const char* rule : {"gaussian", "gaussian:rho=grad", "dorn", "box", "rule2", "tent"}) {
        const compiler::Schedule sched = compiler::uniform_schedule(g, rules::parse_rule(rule));
        const compiler::Program naive = compiler::lower_naive(g, sched), opt = compiler::lower(g, sched);
        const compiler::Program strict = compiler::optimize(naive, {false});
        EXPECT_LT(opt.insts.size(), naive.insts.size());
        const Pixels px(naive, 300, 11);
        const auto a = evaluate(naive, px, textures), b = evaluate(strict, px, textures);
        const auto c = evaluate(opt, px, textures);
        int differ = 0;
        for (int k = 0; k < 3; ++k)
          for (int i = 0; i < px.n; ++i)
            if (c[k][i] != b[k][i]) {
              ++differ;
              EXPECT_TRUE(std::isfinite(c[k][i])) << def.name << " parallax " << p << " " << rule;
            }
        double sum2 = 0, worst = 0;
        int n = 0, far = 0;
        for (int k = 0; k < 3; ++k)
          for (int i = 0; i < px.n; ++i) {
            if (!std::isfinite(a[k][i])) continue;
            const double d = std::fabs(static_cast<double>(a[k][i]) - b[k][i]);
            sum2 += d * d, ++n, worst = std::max(worst, d);
            far += !(d <= 1e-4 * std::max(1.0, std::fabs(static_cast<double>(a[k][i]))));
          }
        const double rms = n ? std::sqrt(sum2 / n) : 0;
        EXPECT_LE(rms, 1e-5) << def.name << " parallax " << p << " " << rule;
        EXPECT_LE(far, 3) << def.name << " parallax " << p << " " << rule << " worst " << worst;
        std::printf(
            "%-16s p%d %-18s insts %4zu -> %4zu (%4zu without x * 0 -> 0)  rms %.1e worst %.1e  "
            "x * 0 changed %d of %d values\n",
            def.name.c_str(), p, rule, naive.insts.size(), opt.insts.size(), strict.insts.size(), rms, worst,
            differ, 3 * px.n);
      }
    }
}

ir::Graph one_input(const std::function<dsl::Var(dsl::Var)>& f) {
  ir::Graph g;
  dsl::Tracer t(g);
  const dsl::Var u = dsl::Var::input("u", true);
  const dsl::Var r = f(u);
  g.add_output("r", r.id());
  return g;
}

float run1(const ir::Graph& g, const std::string& rule, float mu, float sigma) {
  const compiler::Program p = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule(rule)));
  return testing::run_one_pixel(p, {mu}, {sigma}, {0}, {0});
}

TEST(Compiler, SingleNodeRulesAgreeWithClosedForms) {
  // E[sin(3X)], X ~ N(mu, s^2) = exp(-9 s^2 / 2) sin(3 mu); E[step(X)] = Phi(mu / s).
  const ir::Graph g_sin = one_input([](dsl::Var u) { return dsl::sin(u * 3.0); });
  const ir::Graph g_step = one_input([](dsl::Var u) { return dsl::step(u); });
  for (const char* rule : {"gaussian", "dorn"})
    for (float mu : {-2.0f, 0.3f, 5.0f})
      for (float s : {0.01f, 0.2f, 1.0f}) {
        EXPECT_NEAR(run1(g_sin, rule, mu, s), std::exp(-4.5 * s * s) * std::sin(3.0 * mu), 2e-6) << rule;
        EXPECT_NEAR(run1(g_step, rule, mu, s), 0.5 * std::erfc(-mu / (s * std::sqrt(2.0))), 2e-6) << rule;
      }
  // Box: E[sin(3X)], X ~ U[mu - h, mu + h], h = sqrt(3) s: sin(3 mu) sin(3h) / (3h).
  for (float s : {0.05f, 0.5f}) {
    const double h = std::sqrt(3.0) * s;
    EXPECT_NEAR(run1(g_sin, "box", 0.7f, s), std::sin(2.1) * std::sin(3 * h) / (3 * h), 2e-6);
  }
  // Monte Carlo with antithetic samples is exact on a linear node; "none" is the plain value.
  const ir::Graph g_lin = one_input([](dsl::Var u) { return u * 3.0 + 1.0; });
  EXPECT_NEAR(run1(g_lin, "mc4", 0.25f, 0.3f), 1.75, 1e-6);
  // mc2: samples at mean +- sd (antithetic, moment-matched): the linear node's sd 3 s is |y0 - y1| / 2,
  // which sin's samples read: sin(3 mu + 1 +- 3 s) average to sin(3 mu + 1) cos(3 s).
  const ir::Graph g_lin_sin = one_input([](dsl::Var u) { return dsl::sin(u * 3.0 + 1.0); });
  EXPECT_NEAR(run1(g_lin_sin, "mc2", 0.25f, 0.3f), std::sin(1.75) * std::cos(0.9), 1e-6);
  EXPECT_NEAR(run1(g_sin, "none", 0.25f, 0.3f), std::sin(0.75), 1e-6);
}

// An indicator atomic (f in {0, 1}: step, square, pulse30; the registry's AtomicInfo::indicator)
// takes its variance as m (1 - m), without calling f^2's entry: sin(2 step(u)) under the Gaussian
// rule is exp(-Var/2) sin(2 m) with m = Phi(mu/s), Var = 4 m (1 - m) (closed form, computed here).
TEST(Compiler, IndicatorVarianceIsMeanTimesOneMinusMean) {
  const ir::Graph g = one_input([](dsl::Var u) { return dsl::sin(dsl::step(u) * 2.0); });
  const compiler::Program p =
      compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("gaussian")));
  for (int fi : p.used_functions())
    EXPECT_EQ(compiler::functions()[static_cast<std::size_t>(fi)].cpp.find("step_sq"), std::string::npos)
        << compiler::functions()[static_cast<std::size_t>(fi)].cpp;
  for (float mu : {-0.3f, 0.0f, 0.05f, 0.4f})
    for (float s : {0.01f, 0.2f, 1.0f}) {
      const double m = 0.5 * std::erfc(-mu / (s * std::sqrt(2.0))), var = 4 * m * (1 - m);
      EXPECT_NEAR(run1(g, "gaussian", mu, s), std::exp(-var / 2) * std::sin(2 * m), 2e-6) << mu << " " << s;
    }
  int n_ind = 0;
  for (int a = 0; a < ir::atomic_count(); ++a) {
    // Independent of the flag's derivation: the plain function on a dense grid is 0 or 1 exactly.
    bool zero_one = true;
    for (int i = -4000; i <= 4000 && zero_one; ++i) {
      const double x = i * 0.00125, y = ir::plain_atomic(a, x);
      zero_one = y == 0.0 || y == 1.0;
    }
    EXPECT_EQ(ir::atomic_indicator(a), zero_one) << ir::atomic_name(a);
    n_ind += zero_one;
  }
  EXPECT_EQ(n_ind, 3);  // step, square, pulse30
}

// A Gaussian fract node whose variance a later rule reads takes both moments from the one-pass
// entry bl::gaussian::fract_stat (no fract_sq call); one whose variance nothing reads calls
// bl::gaussian::fract alone. Values: the closed form of sin(3 F), F ~ (m, v) with m and v from the
// separate double entries fract and fract_sq (another emitted plan than the stat entry's).
TEST(Compiler, StatEntryServesMeanAndVarianceTogether) {
  auto names = [](const compiler::Program& p) {
    std::set<std::string> out;
    for (int fi : p.used_functions()) out.insert(compiler::functions()[static_cast<std::size_t>(fi)].cpp);
    return out;
  };
  const ir::Graph g = one_input([](dsl::Var u) { return dsl::sin(dsl::fract(u) * 3.0); });
  const compiler::Program p =
      compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("gaussian")));
  EXPECT_TRUE(names(p).count("bl::gaussian::fract_stat"));
  EXPECT_FALSE(names(p).count("bl::gaussian::fract_sq"));
  EXPECT_FALSE(names(p).count("bl::gaussian::fract"));
  for (float mu : {-0.3f, 0.0f, 0.05f, 0.4f, 7.99f}) {
    const float s = 0.01f;
    const double m = bl::gaussian::fract(double(mu), double(s));
    const double v = bl::gaussian::fract_sq(double(mu), double(s)) - m * m;
    EXPECT_NEAR(run1(g, "gaussian", mu, s), std::exp(-9 * v / 2) * std::sin(3 * m), 2e-6) << mu << " " << s;
    // From 0.02 periods on the output (a tiling of u) is its damped Fourier series (PeriodicFarField):
    // against 1D quadrature (the closed form above was 0.07 off at s = 0.2, 0.022 at s = 1).
    for (float sw : {0.2f, 1.0f}) {
      const double want =
          testing::gaussian_mean_1d([](double x) { return std::sin(3 * (x - std::floor(x))); }, mu, sw, 8000);
      EXPECT_NEAR(run1(g, "gaussian", mu, sw), want, 2e-3) << mu << " " << sw;
    }
  }
  const ir::Graph mean_only = one_input([](dsl::Var u) { return dsl::fract(u); });
  const compiler::Program q =
      compiler::lower(mean_only, compiler::uniform_schedule(mean_only, rules::parse_rule("gaussian")));
  EXPECT_TRUE(names(q).count("bl::gaussian::fract"));
  EXPECT_FALSE(names(q).count("bl::gaussian::fract_stat"));
  EXPECT_NEAR(run1(mean_only, "gaussian", 0.95f, 0.1f), bl::gaussian::fract(0.95, 0.1), 1e-6);
}

// floor(u + 1/2) - floor(u) (a checkerboard's pulse) under one kernel at one width is one smoothed
// square wave, 1 - square(u): its mean equals the difference of the table's two smoothed floors (the
// reference), its variance is the indicator's m (1 - m), and no floor entry is called.
TEST(Compiler, FloorPairPulseIsOneSquareWave) {
  auto names = [](const compiler::Program& p) {
    std::set<std::string> out;
    for (int fi : p.used_functions()) out.insert(compiler::functions()[static_cast<std::size_t>(fi)].cpp);
    return out;
  };
  const ir::Graph pulse = one_input([](dsl::Var u) { return dsl::floor(u + 0.5) - dsl::floor(u); });
  const ir::Graph neg = one_input([](dsl::Var u) { return dsl::floor(u) - dsl::floor(u + 0.5); });
  const ir::Graph wave =
      one_input([](dsl::Var u) { return dsl::sin((dsl::floor(u + 0.5) - dsl::floor(u)) * 3.0); });
  using Entry = double (*)(double, double);
  const std::vector<std::pair<std::string, Entry>> kernels = {
      {"gaussian", [](double x, double s) { return bl::gaussian::floor(x, s); }},
      {"box", [](double x, double s) { return bl::box::floor(x, s); }},
      {"tent", [](double x, double s) { return bl::tent::floor(x, s); }}};
  for (const auto& [rule, floor_entry] : kernels) {
    const compiler::Program p =
        compiler::lower(pulse, compiler::uniform_schedule(pulse, rules::parse_rule(rule)));
    EXPECT_TRUE(names(p).count("bl::" + rule + "::square")) << rule;
    EXPECT_FALSE(names(p).count("bl::" + rule + "::floor")) << rule;
    for (float mu : {-3.75f, -0.5f, 0.0f, 0.3f, 0.5f, 0.74f, 40.7f})
      for (float s : {0.01f, 0.2f, 0.6f}) {
        const double m = floor_entry(double(mu) + 0.5, double(s)) - floor_entry(double(mu), double(s));
        EXPECT_NEAR(run1(pulse, rule, mu, s), m, 2e-5) << rule << " " << mu << " " << s;
        EXPECT_NEAR(run1(neg, rule, mu, s), -m, 2e-5) << rule << " " << mu << " " << s;
        if (rule == "gaussian")  // sin of N(m, v): e^{-9 v / 2} sin(3 m), v = m (1 - m)
          EXPECT_NEAR(run1(wave, rule, mu, s), std::exp(-4.5 * m * (1 - m)) * std::sin(3 * m), 3e-5)
              << mu << " " << s;
      }
  }
}

// E[1{fract(Y) in [lo, hi]}] for Y = mu + sigma Z under a unit-variance kernel, from the kernel's CDF
// over the intervals [k + lo, k + hi] (independent of the table's fract entries).
double window_reference(const std::string& kernel, double mu, double sigma, double lo, double hi) {
  auto cdf = [&](double t) {  // P(Z <= t)
    if (kernel == "gaussian") return 0.5 * std::erfc(-t / std::sqrt(2.0));
    if (kernel == "box") {
      const double h = std::sqrt(3.0);
      return std::clamp((t + h) / (2 * h), 0.0, 1.0);
    }
    const double w = std::sqrt(6.0);  // tent: half-width sqrt(6)
    if (t <= -w) return 0.0;
    if (t >= w) return 1.0;
    return t <= 0 ? 0.5 * (w + t) * (w + t) / (w * w) : 1 - 0.5 * (w - t) * (w - t) / (w * w);
  };
  double p = 0;
  for (long k = static_cast<long>(std::floor(mu - 12 * sigma)) - 1;
       k <= static_cast<long>(std::ceil(mu + 12 * sigma)) + 1; ++k)
    p += cdf((k + hi - mu) / sigma) - cdf((k + lo - mu) / sigma);
  return p;
}

// step(fract(y) - lo) * step(hi - fract(y)) (either order, and the second pair of a left-to-right
// chain of four) is the indicator of fract(y) in [lo, hi]: two mean-only fract calls under the steps'
// kernel, no step left; its mean is the indicator's exact mean under that kernel.
TEST(Compiler, FractWindowIsTwoFracts) {
  auto names = [](const compiler::Program& p) {
    std::set<std::string> out;
    for (int fi : p.used_functions()) out.insert(compiler::functions()[static_cast<std::size_t>(fi)].cpp);
    return out;
  };
  const double lo = 0.06, hi = 0.94;
  const ir::Graph win = one_input([&](dsl::Var u) {
    const dsl::Var f = dsl::fract(u);
    return dsl::step(f - lo) * dsl::step(hi - f);
  });
  const ir::Graph rev = one_input([&](dsl::Var u) {
    const dsl::Var f = dsl::fract(u * 2.0);
    return dsl::step(0.7 - f) * dsl::step(f - 0.2);
  });
  ir::Graph chain;
  {
    dsl::Tracer t(chain);
    const dsl::Var u = dsl::Var::input("u", true), v = dsl::Var::input("v", true);
    const dsl::Var fu = dsl::fract(u), fv = dsl::fract(v);
    chain.add_output(
        "r", (dsl::step(fu - lo) * dsl::step(hi - fu) * dsl::step(fv - lo) * dsl::step(hi - fv)).id());
  }
  for (const std::string rule : {"gaussian", "box", "tent"}) {
    const compiler::Program p =
        compiler::lower(win, compiler::uniform_schedule(win, rules::parse_rule(rule)));
    EXPECT_TRUE(names(p).count("bl::" + rule + "::fract")) << rule;
    EXPECT_FALSE(names(p).count("bl::" + rule + "::step")) << rule;
    const compiler::Program pc =
        compiler::lower(chain, compiler::uniform_schedule(chain, rules::parse_rule(rule)));
    EXPECT_FALSE(names(pc).count("bl::" + rule + "::step")) << rule;
    for (float mu : {-3.03f, -0.5f, 0.0f, 0.05f, 0.06f, 0.3f, 0.95f, 40.7f})
      for (float s : {0.001f, 0.01f, 0.05f, 0.2f, 0.6f}) {
        const double m = window_reference(rule, mu, s, lo, hi);
        EXPECT_NEAR(run1(win, rule, mu, s), m, 2e-5) << rule << " " << mu << " " << s;
        EXPECT_NEAR(run1(rev, rule, mu, s), window_reference(rule, 2.0 * mu, 2.0 * s, 0.2, 0.7), 2e-5)
            << rule << " " << mu << " " << s;
        const float mv = 0.3f * mu + 0.11f, sv = 0.5f * s;
        const double mc = m * window_reference(rule, mv, sv, lo, hi);
        EXPECT_NEAR(testing::run_one_pixel(pc, {mu, mv}, {s, sv}, {0, 0}, {0, 0}), mc, 3e-5)
            << rule << " " << mu << " " << s;
      }
  }
}

// step(c - fract(y)) = c - fract(y) + fract(y - c) a.e. (and step(fract(y) - c) one minus it): a lone
// step of a fract under a kernel is two mean-only fract calls, its mean the indicator's exact mean.
TEST(Compiler, FractStepIsTwoFracts) {
  const ir::Graph below = one_input([](dsl::Var u) { return dsl::step(0.1 - dsl::fract(u)); });
  const ir::Graph above = one_input([](dsl::Var u) { return dsl::step(dsl::fract(u * 3.0 + 0.25) - 0.7); });
  const ir::Graph less_below = one_input([](dsl::Var u) { return dsl::less(dsl::fract(u), dsl::Var(0.1)); });
  // 0.5 - 5 fract(u) >= 0: fract(u) <= 0.1 (an edge scaled with fract, as mod(y, c) = c fract(y / c))
  const ir::Graph scaled = one_input([](dsl::Var u) { return dsl::step(0.5 - dsl::fract(u) * 5.0); });
  // mod(u, 2) >= 1.4: fract(u / 2) >= 0.7 (GLSL step(1.4, mod(u, 2.0)))
  const ir::Graph modded = one_input([](dsl::Var u) { return dsl::step(dsl::mod(u, 2.0) - 1.4); });
  const ir::Graph less_above =
      one_input([](dsl::Var u) { return dsl::less(dsl::Var(0.7), dsl::fract(u * 3.0 + 0.25)); });
  for (const std::string rule : {"gaussian", "box", "tent"}) {
    for (const ir::Graph* g : {&below, &above, &less_below, &less_above, &scaled, &modded}) {
      const compiler::Program p =
          compiler::lower(*g, compiler::uniform_schedule(*g, rules::parse_rule(rule)));
      int fracts = 0, steps = 0;
      for (int fi : p.used_functions()) {
        const std::string& n = compiler::functions()[static_cast<std::size_t>(fi)].cpp;
        fracts += n == "bl::" + rule + "::fract";
        steps += n.find("step") != std::string::npos;
      }
      EXPECT_EQ(fracts, 1) << rule;  // one entry, called twice
      EXPECT_EQ(steps, 0) << rule;
    }
    for (float mu : {-3.03f, -0.5f, 0.0f, 0.05f, 0.1f, 0.3f, 0.95f, 40.7f})
      for (float s : {0.001f, 0.01f, 0.05f, 0.2f, 0.6f, 3.0f}) {
        EXPECT_NEAR(run1(below, rule, mu, s), window_reference(rule, mu, s, 0.0, 0.1), 2e-5)
            << rule << " " << mu << " " << s;
        EXPECT_NEAR(run1(above, rule, mu, s), window_reference(rule, 3.0 * mu + 0.25, 3.0 * s, 0.7, 1.0),
                    3e-5)
            << rule << " " << mu << " " << s;
        EXPECT_NEAR(run1(less_below, rule, mu, s), window_reference(rule, mu, s, 0.0, 0.1), 2e-5)
            << rule << " " << mu << " " << s;
        EXPECT_NEAR(run1(scaled, rule, mu, s), window_reference(rule, mu, s, 0.0, 0.1), 2e-5)
            << rule << " " << mu << " " << s;
        EXPECT_NEAR(run1(modded, rule, mu, s), window_reference(rule, 0.5 * mu, 0.5 * s, 0.7, 1.0), 2e-5)
            << rule << " " << mu << " " << s;
        EXPECT_NEAR(run1(less_above, rule, mu, s), window_reference(rule, 3.0 * mu + 0.25, 3.0 * s, 0.7, 1.0),
                    3e-5)
            << rule << " " << mu << " " << s;
      }
  }
}

// GLSL fract(y) < c ? a : b: the select's condition is a Bernoulli node whose p is the fract step's
// exact mean, so the select's mean is exact too.
TEST(Compiler, SelectOnAFractEdgeIsExact) {
  const ir::Graph g = one_input([](dsl::Var u) {
    return dsl::select(dsl::less(dsl::fract(u), dsl::Var(0.3)), dsl::Var(2.0), dsl::Var(5.0));
  });
  for (const std::string rule : {"gaussian", "box", "tent"})
    for (float mu : {-3.03f, 0.05f, 0.3f, 0.95f, 40.7f})
      for (float s : {0.001f, 0.05f, 0.6f}) {
        const double p = window_reference(rule, mu, s, 0.0, 0.3);
        EXPECT_NEAR(run1(g, rule, mu, s), 5.0 - 3.0 * p, 1e-4) << rule << " " << mu << " " << s;
      }
}

// A duty cycle that varies over the surface (GLSL step(fract(s), width)): the edge node enters by its
// mean and y - c's variance. With the edge's input at sd 0 the edge is a constant at each pixel and the
// mean exact; with sd > 0 it is close to the expectation over both inputs (quadrature here); an edge
// whose range leaves [0, 1] is not fused (the identity needs 0 <= c <= 1).
TEST(Compiler, FractStepWithAVaryingEdge) {
  auto graph = [](double base, double amp) {
    ir::Graph g;
    dsl::Tracer t(g);
    const dsl::Var u = dsl::Var::input("u", true), v = dsl::Var::input("v", true);
    const dsl::Var width = base + amp * dsl::sin(v);
    g.add_output("r", dsl::step(width - dsl::fract(u)).id());
    return g;
  };
  auto uses_step = [](const compiler::Program& p) {
    for (int fi : p.used_functions())
      if (compiler::functions()[static_cast<std::size_t>(fi)].cpp.find("step") != std::string::npos)
        return true;
    return false;
  };
  const ir::Graph g = graph(0.35, 0.25), wide = graph(0.5, 0.8);
  for (const std::string rule : {"gaussian", "box", "tent"}) {
    const compiler::Program p = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule(rule)));
    EXPECT_FALSE(uses_step(p)) << rule;
    EXPECT_TRUE(uses_step(compiler::lower(wide, compiler::uniform_schedule(wide, rules::parse_rule(rule)))))
        << rule;
    for (float mu : {-3.03f, 0.05f, 0.3f, 0.95f, 40.7f})
      for (float mv : {-1.0f, 0.2f, 2.0f})
        for (float s : {0.001f, 0.05f, 0.6f}) {
          const double c = 0.35 + 0.25 * std::sin(static_cast<double>(mv));
          EXPECT_NEAR(testing::run_one_pixel(p, {mu, mv}, {s, 0.0f}, {0, 0}, {0, 0}),
                      window_reference(rule, mu, s, 0.0, c), 3e-5)
              << rule << " " << mu << " " << mv << " " << s;
        }
  }
  // sd 0.1 on v under the Gaussian rule: the expectation over v (midpoint rule on +-8 sd).
  const compiler::Program p =
      compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("gaussian")));
  for (float mu : {0.05f, 0.3f, 0.62f})
    for (float s : {0.01f, 0.2f}) {
      const float mv = 0.2f, sv = 0.1f;
      const double ref = testing::gaussian_mean_1d(
          [&](double v) { return window_reference("gaussian", mu, s, 0.0, 0.35 + 0.25 * std::sin(v)); }, mv,
          sv, 1600);
      EXPECT_NEAR(testing::run_one_pixel(p, {mu, mv}, {s, sv}, {0, 0}, {0, 0}), ref, 2e-4) << mu << " " << s;
    }
}

TEST(Compiler, DeadCodeIsRemoved) {
  const auto count = [](const compiler::Program& p, compiler::LOp op) {
    int n = 0;
    for (const auto& in : p.insts) n += in.op == op;
    return n;
  };
  shaders::Effects fx;
  const ir::Graph g = shaders::trace(shaders::find_shader("checkerboard"), fx);
  const auto plain = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("none")));
  EXPECT_EQ(count(plain, compiler::LOp::InSd), 0);  // nothing smooths: no footprint read
  EXPECT_EQ(count(plain, compiler::LOp::Sqrt), 0);
  const auto dorn = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("dorn")));
  EXPECT_EQ(count(dorn, compiler::LOp::NonNeg), 0);  // Dorn never forms E[f^2] - E[f]^2
  EXPECT_FALSE(dorn.uses_gradients());
  // Variance is computed only where a later rule consumes it: smoothing only the last node
  // (mean output) needs no variance of anything after the inputs.
  compiler::Schedule sched = compiler::uniform_schedule(g, rules::parse_rule("none"));
  // All-Gaussian checkerboard: its products and sums are rho 0, whose means read no variance, and
  // the output is a mean, so no variance is computed at all (dead-variance elimination).
  const auto gauss = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("gaussian")));
  EXPECT_EQ(count(gauss, compiler::LOp::NonNeg), 0);
  EXPECT_EQ(count(gauss, compiler::LOp::CallStat), 0);
  // With rho=grad the products need the variances (bivariate::mul's mean reads rho sa sb).
  const auto grad = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("gaussian:rho=grad")));
  EXPECT_GT(count(grad, compiler::LOp::NonNeg), 0);
  for (int i = 0; i < g.size(); ++i)
    if (g.node(i).op == ir::Op::Call) sched[i] = rules::parse_rule("gaussian");
  for (int i = 0; i < g.size(); ++i)
    if (g.node(i).op == ir::Op::Input) sched[i] = rules::parse_rule("gaussian");
  const auto calls_only = compiler::lower(g, sched);
  // floor(u), floor(u + 0.5): the inputs' sd is read, but no floor's variance (no consumer).
  EXPECT_GT(count(calls_only, compiler::LOp::InSd), 0);
  EXPECT_EQ(count(calls_only, compiler::LOp::NonNeg), 0);
}

// Appends one instruction (args a, b; constant k) to a hand-built program; its index.
int append(compiler::Program& p, compiler::LOp op, int a, int b, float k) {
  compiler::Inst in;
  in.op = op;
  in.arg[0] = a;
  in.arg[1] = b;
  in.k = k;
  p.insts.push_back(in);
  return static_cast<int>(p.insts.size()) - 1;
}

// optimize() folds what the lowering writes naively: zero covariance and derivative terms (x * 0),
// sqrt(k sd^2) of a scaled sd, constant chains, division by a power of two, a + b against b + a,
// NonNeg of a sum of variances. The values are the closed form's (computed here in double).
TEST(Compiler, FoldingKeepsValuesAndDropsWork) {
  using compiler::LOp;
  compiler::Program p;
  p.input_count = 1;
  p.input_names = {"u"};
  auto put = [&](LOp op, int a = -1, int b = -1, float k = 0) { return append(p, op, a, b, k); };
  const int m = put(LOp::InMean, 0), s = put(LOp::InSd, 0);
  const int zero = put(LOp::Const, -1, -1, 0), four = put(LOp::Const, -1, -1, 4);
  const int scale = put(LOp::Const, -1, -1, 0.774f), half = put(LOp::Const, -1, -1, 0.5f);
  const int var = put(LOp::Mul, s, s);
  const int sd = put(LOp::Mul, put(LOp::Sqrt, put(LOp::Mul, four, var)), scale);           // 2 s 0.774
  const int dead = put(LOp::Mul, zero, put(LOp::Sqrt, put(LOp::Div, m, s)));               // 0 * sqrt(m / s)
  const int sum = put(LOp::Add, put(LOp::Add, m, s), put(LOp::Neg, put(LOp::Add, s, m)));  // 0
  const int nn = put(LOp::NonNeg, put(LOp::Add, put(LOp::NonNeg, var), put(LOp::Mul, var, half)));
  const int quarter = put(LOp::Div, put(LOp::Mul, put(LOp::Mul, m, half), half), four);  // m / 16
  const int out0 = put(LOp::Add, put(LOp::Add, sd, dead), sum);
  p.outputs = {out0, nn, quarter};
  p.output_names = {"a", "b", "c"};
  const compiler::Program o = compiler::optimize(p);
  std::map<LOp, int> count;
  for (const auto& in : o.insts) ++count[in.op];
  EXPECT_EQ(count[LOp::Sqrt], 0);
  EXPECT_EQ(count[LOp::Div], 0);
  EXPECT_EQ(count[LOp::NonNeg], 0);
  EXPECT_EQ(count[LOp::Add], 4);  // m + s once, (m + s) - (m + s), the output's, var + var / 2
  EXPECT_EQ(count[LOp::Mul], 4);  // s s, s 1.548, var 0.5, m 0.0625
  EXPECT_EQ(count[LOp::Neg], 1);
  const float us[] = {-3.5f, 0.0f, 1e-3f, 2.25f}, ss[] = {1e-3f, 0.2f, 0.4f, 1e-12f};
  for (float u : us)
    for (float sv : ss) {
      float out[3];
      std::vector<float*> ptr{&out[0], &out[1], &out[2]};
      compiler::Batch b;
      b.count = 1;
      b.mean = {&u};
      b.sd = {&sv};
      compiler::Evaluator(o).run(b, ptr);
      const double S = sv, U = u;
      EXPECT_NEAR(out[0], 2 * S * 0.774, 1e-6 * (1 + 2 * S)) << u << " " << sv;
      EXPECT_NEAR(out[1], 1.5 * S * S, 1e-6 * 1.5 * S * S) << u << " " << sv;
      EXPECT_EQ(out[2], static_cast<float>(U / 16)) << u << " " << sv;
    }
}

// k - (k - x) folds to x (a complement taken twice), also when k - x has other uses; k' - (k - x)
// with k' != k does not.
TEST(Compiler, DoubleComplementFoldsToItsArgument) {
  using compiler::LOp;
  compiler::Program p;
  p.input_count = 1;
  p.input_names = {"u"};
  auto put = [&](LOp op, int a = -1, int b = -1, float k = 0) { return append(p, op, a, b, k); };
  const int m = put(LOp::InMean, 0), one = put(LOp::Const, -1, -1, 1), two = put(LOp::Const, -1, -1, 2);
  const int c = put(LOp::Sub, one, m);
  p.outputs = {put(LOp::Sub, one, c), c, put(LOp::Sub, two, c)};
  p.output_names = {"a", "b", "c"};
  const compiler::Program o = compiler::optimize(p);
  EXPECT_EQ(o.insts[o.outputs[0]].op, LOp::InMean);
  int subs = 0;
  for (const auto& in : o.insts) subs += in.op == LOp::Sub;
  EXPECT_EQ(subs, 2);  // 1 - u and 2 - (1 - u)
  float u = 1e-9f, out[3];
  std::vector<float*> ptr{&out[0], &out[1], &out[2]};
  compiler::Batch b;
  b.count = 1;
  b.mean = {&u};
  float sd = 0;
  b.sd = {&sd};
  compiler::Evaluator(o).run(b, ptr);
  EXPECT_EQ(out[0], 1e-9f);  // the unfolded 1 - (1 - 1e-9) rounds to 0
  EXPECT_EQ(out[1], 1.0f);
  EXPECT_EQ(out[2], 1.0f);
}

TEST(Compiler, BadScheduleAndNamesAreReported) {
  const ir::Graph g = one_input([](dsl::Var u) { return dsl::sin(u); });
  EXPECT_THROW(compiler::lower(g, compiler::Schedule(1)), std::invalid_argument);
  try {
    rules::parse_rule("mc7");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("mc7"), std::string::npos);
  }
  EXPECT_THROW(rules::parse_rule("gaussian:rho=2"), std::invalid_argument);
  EXPECT_THROW(rules::parse_rule("rule1:cosine"), std::invalid_argument);
  ir::Graph h;
  EXPECT_THROW(h.call("sinc", h.input("u", true)), std::invalid_argument);
  for (const auto& r : rules::all_rules()) EXPECT_EQ(rules::parse_rule(rules::to_string(r)), r);
}

TEST(Dsl, AtomicsMatchTheGeneratedCatalog) {
  // Every catalog atomic is callable from shaders, and nothing else.
  std::set<std::string> dsl(std::begin(dsl::kDslAtomics), std::end(dsl::kDslAtomics));
  std::set<std::string> cat;
  for (int i = 0; i < ir::atomic_count(); ++i) cat.insert(ir::atomic_name(i));
  EXPECT_EQ(dsl, cat);
}

TEST(Dsl, TracingSharesAndFolds) {
  ir::Graph g;
  dsl::Tracer t(g);
  const dsl::Var u = dsl::Var::input("u", true);
  const dsl::Var a = dsl::sin(u * 2.0), b = dsl::sin(u * 2.0);
  EXPECT_EQ(a.id(), b.id());  // identical subexpressions are one node
  const dsl::Var c = dsl::Var(2.0) * dsl::Var(3.0) + dsl::sin(dsl::Var(0.0));
  EXPECT_EQ(g.node(c.id()).op, ir::Op::Const);
  EXPECT_DOUBLE_EQ(g.node(c.id()).value, 6.0);
}

}  // namespace
}  // namespace bl
