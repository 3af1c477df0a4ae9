#include "tuner/finalize.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include "compiler/lower.hpp"
#include "compiler/schedule_text.hpp"
#include "compiler/supersample.hpp"
#include "gl/egl_runner.hpp"
#include "image/image_io.hpp"
#include "image/metrics.hpp"
#include "image/report.hpp"
#include "jit/compiled_program.hpp"
#include "render/compiled_frame.hpp"
#include "render/glsl_frame.hpp"
#include "render/render.hpp"
#include "tuner/adaptive_supersampling.hpp"
#include "tuner/lod_pair.hpp"
#include "tuner/lod_polish.hpp"
#include "tuner/polish.hpp"
#include "tuner/report.hpp"

namespace bl::tuner {

namespace {

template <class F>
double best_ms(int runs, F&& f) {
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < runs; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    best = std::min(best,
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

// Indices of at most k front points spread evenly over the front (both ends kept).
std::vector<int> spread(int n, int k) {
  std::vector<int> idx;
  if (n <= k) {
    for (int i = 0; i < n; ++i) idx.push_back(i);
    return idx;
  }
  for (int j = 0; j < k; ++j) {
    const int i = static_cast<int>(std::lround(static_cast<double>(j) * (n - 1) / (k - 1)));
    if (idx.empty() || idx.back() != i) idx.push_back(i);
  }
  return idx;
}

}  // namespace

std::vector<int> pick_front_points(const std::vector<Point>& front, int k,
                                   const std::vector<double>& targets) {
  const int n = static_cast<int>(front.size());
  std::vector<int> idx;
  for (double e : targets)
    for (double m : kAnchorMargins) {
      const int i = cheapest_under(front, m * e);
      if (i >= 0 && std::find(idx.begin(), idx.end(), i) == idx.end() &&
          static_cast<int>(idx.size()) < std::max(0, k - 2))
        idx.push_back(i);
    }
  std::sort(idx.begin(), idx.end());
  idx.erase(std::unique(idx.begin(), idx.end()), idx.end());
  for (int i : spread(n, std::max(2, k - static_cast<int>(idx.size())))) idx.push_back(i);
  std::sort(idx.begin(), idx.end());
  idx.erase(std::unique(idx.begin(), idx.end()), idx.end());
  return idx;
}

namespace {

struct Timer {
  std::unique_ptr<gl::Context> ctx;
  std::string renderer;
  const FinalizeOptions* opt = nullptr;
  std::string jit_error;  // set at the first jit::Error: no further compiles are tried
};

// Times of p on frame 0 over the same pixel inputs: compiled code and evaluator (single thread,
// minimum of opt.trials), GLSL when a context exists. samples > 0: MSAA of p (plain) with that many
// jittered samples per pixel; the evaluator's MSAA time is then samples x its plain time (passed
// in as eval_plain_ms) rather than re-measured, to keep finalize short.
void measure(const SceneTuner& t, const compiler::Program& p, Timer& gl, Measured* m, int samples = 0,
             double eval_plain_ms = 0) {
  const scene::Scene& s = t.scene();
  const render::Frame f = render::frames(s).front();
  const int trials = gl.opt->trials;
  m->eval_ms = samples > 0
                   ? samples * eval_plain_ms
                   : render::time_program(s, f, p, render::evaluator_runner(p), 0, trials).ms_per_frame;
  if (gl.jit_error.empty()) {
    try {
      const jit::CompiledProgram cp(p, gl.opt->jit);
      const render::FrameTiming tc =
          render::time_program(s, f, p, render::compiled_runner(cp), samples, trials);
      m->compiled_ns = tc.ns_per_pixel;
      m->compiled_ms = tc.ms_per_frame;
    } catch (const jit::Error& e) {
      gl.jit_error = e.what();
      std::fprintf(stderr,
                   "finalize: compiled-code timing unavailable, reports fall back to the evaluator:\n%s\n",
                   e.what());
    }
  }
  if (gl.ctx && samples == 0) {
    try {
      const gl::Program prog = gl.ctx->compile(render::glsl_fragment_source(s, p));
      const render::GlTextures textures(*gl.ctx, s, p);
      m->glsl_ms = gl.ctx->time_ms(prog, s.width, s.height,
                                   render::with_textures(render::glsl_frame_uniforms(s, f), textures), 5);
    } catch (const gl::Error& e) {
      std::fprintf(stderr, "finalize: GLSL timing of %s failed: %s\n", m->label.c_str(), e.what());
    }
  }
}

// A footprint pair compiled into one loop (jit::CompiledProgram's LOD form): ns per pixel of frame 0,
// -1 without a compiler.
double time_pair(const SceneTuner& t, const compiler::Program& near, const compiler::Program& far,
                 float limit, Timer& gl) {
  if (!gl.jit_error.empty()) return -1;
  try {
    const jit::CompiledProgram cp(near, far, limit, gl.opt->jit);
    const render::Frame f = render::frames(t.scene()).front();
    return render::time_program(t.scene(), f, near, render::compiled_runner(cp), 0, gl.opt->trials)
        .ns_per_pixel;
  } catch (const jit::Error& e) {
    gl.jit_error = e.what();
    return -1;
  }
}

// A picked pair compiled into one loop and timed (time_pair), logged as `what`.
LodResult timed(const SceneTuner& t, const PickedPair& p, const char* what, double e16, Timer& gl) {
  LodResult r = p.result;
  r.compiled_ns = time_pair(t, p.near, p.far, r.limit, gl);
  std::fprintf(stderr,
               "finalize: %s: %s %s below %.3g, %s above (%.0f%% of pixels near): %.2f ns/px model, %.2f "
               "compiled, error %.5f (MSAA-16 %.5f)\n",
               t.scene().name.c_str(), what, r.near.c_str(), r.limit, r.far.c_str(), 100 * r.near_share,
               r.model_ns, r.compiled_ns, r.error, e16);
  return r;
}

// The fastest footprint-LOD pair at MSAA-16's full error e16 (lod_pair.hpp), kept when it is faster
// by the model than every single front point at that error, then timed. Its points: the measured
// front, and the search's front points that are not among them (labelled searchNN by their place in
// the search front; many lie between the measured ones).
std::optional<LodResult> find_lod(const SceneTuner& t, const std::vector<Measured>& front,
                                  const std::vector<compiler::Schedule>& schedules,
                                  const std::vector<Point>& search_front, double e16, Timer& gl) {
  std::vector<std::pair<std::string, compiler::Schedule>> points;
  std::vector<std::string> texts;
  for (std::size_t i = 0; i < front.size(); ++i) {
    points.emplace_back(front[i].label, schedules[i]);
    texts.push_back(front[i].schedule);
  }
  for (std::size_t i = 0; i < search_front.size(); ++i) {
    const compiler::Schedule sch = t.schedule(search_front[i].genome);
    const std::string text = compiler::schedule_to_text(t.graph(), sch);
    if (std::find(texts.begin(), texts.end(), text) != texts.end() ||
        !std::isfinite(search_front[i].obj.time))
      continue;
    char label[32];
    std::snprintf(label, sizeof label, "search%02zu", i);
    points.emplace_back(label, sch);
    texts.push_back(text);
  }
  std::vector<LodSide> sides = lod_sides(t, points);
  if (sides.size() < 2) return std::nullopt;
  std::optional<PickedPair> p = fastest_pair(t, sides, e16, true);
  // The pair descended as one program (lod_polish.hpp); its sides join the others and the pick runs
  // again on full images (the descent reads the search sample).
  if (p && p->result.near_samples == 1 && p->result.far_samples == 1) {
    const LodResult r = p->result;
    auto schedule_of = [&](const std::string& label) {
      for (const auto& [l, sch] : points)
        if (l == label) return sch;
      return t.plain_schedule();
    };
    // First with the pair's headroom on full images (MSAA-16's error over its own) scaled onto the
    // sample error; when the pick on full images takes none of that descent's sides (the sample
    // misjudged the headroom), again at the start's own sample error.
    const double headroom = e16 / r.error;
    const compiler::Schedule near = schedule_of(r.near), far = schedule_of(r.far);
    const std::size_t before = sides.size();
    for (double scale : {headroom, 1.0}) {
      const PolishedPair q = polish_pair(t, near, far, r.limit, r.near_share, scale);
      std::fprintf(
          stderr,
          "finalize: %s: footprint LOD %s + %s descended as a pair (sample error up to %.3fx): %.2f -> "
          "%.2f ns/px, sample error %.5f -> %.5f (%d steps, %d evaluations)\n",
          t.scene().name.c_str(), r.near.c_str(), r.far.c_str(), scale, q.time_before, q.time_after,
          q.error_before, q.error_after, q.steps, q.evaluations);
      if (q.steps == 0) break;
      sides.erase(sides.begin() + static_cast<std::ptrdiff_t>(before), sides.end());
      for (const auto& [label, sch] : {std::pair{r.near + "-near", q.near}, std::pair{r.far + "-far", q.far}})
        if (std::optional<LodSide> sd = lod_side(t, label, sch)) sides.push_back(std::move(*sd));
      std::optional<PickedPair> again = fastest_pair(t, sides, e16, true);
      if (again && again->result.model_ns < p->result.model_ns) {
        p = std::move(again);
        break;
      }
      if (headroom < 1.01) break;  // the second descent would be the first again
    }
  }
  double single = std::numeric_limits<double>::infinity();
  for (const Measured& m : front)
    if (m.error <= e16) single = std::min(single, m.model_ns);
  if (!p || !(p->result.model_ns < single)) return std::nullopt;
  return timed(t, *p, "footprint LOD", e16, gl);
}

}  // namespace

std::string rule_family(const rules::Rule& r) {
  if (r.kind == rules::Kind::Gaussian)
    return r.rho == rules::Rho::Zero         ? "gaussian(rho=0)"
           : r.rho == rules::Rho::Gradient   ? "gaussian(rho=grad)"
           : r.rho == rules::Rho::Covariance ? "gaussian(rho=cov)"
                                             : "gaussian(rho=const)";
  return rules::kind_name(r.kind);
}

std::map<std::string, double> rule_mix(const SceneTuner& t, const compiler::Schedule& s) {
  std::map<std::string, double> mix;
  const auto& genes = t.problem().space.genes;
  for (int n : genes) mix[rule_family(s[n])] += 1.0 / genes.size();
  return mix;
}

SceneResult finalize(const SceneTuner& t, const std::vector<Point>& front, const FinalizeOptions& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  const scene::Scene& s = t.scene();
  const std::string& cache = t.options().cache_dir;
  const std::vector<render::Frame> frames = render::frames(s);
  SceneResult res;
  res.scene = s.name;
  if (t.cost_model().method == "gpu-fit") res.cost_machine = t.cost_model().machine;
  res.graph_hash = compiler::graph_hash_text(t.graph());
  res.nodes = t.graph().size();
  res.genes = t.problem().space.size();
  res.pixels = s.width * s.height;
  res.frames = static_cast<int>(frames.size());
  Timer gl;
  gl.opt = &opt;
  if (opt.glsl && gl::Context::availability().ok) {
    gl.ctx = std::make_unique<gl::Context>();
    gl.ctx->set_unknown_uniform(gl::UnknownUniform::kIgnore);
    res.gl_renderer = gl.ctx->renderer();
  }
  auto set_error = [](Measured& m, double e) {
    m.error = e;
    m.psnr = -20 * std::log10(std::max(e, 1e-12));
  };
  auto set_score = [&](Measured& m, const PixelSample::Score& sc) {
    set_error(m, sc.rms);
    m.nonfinite = sc.counts.nonfinite;
    m.out_of_range = sc.counts.out_of_range;
  };
  // Baselines first: the plain program and MSAA as n plain evaluations per pixel (their errors pick
  // the front points below); all-Dorn and all-Gaussian after the front.
  auto uniform = [&](const std::string& label, const std::string& rule) {
    const auto p = t.lower(compiler::uniform_schedule(t.graph(), rules::parse_rule(rule)));
    if (!p) {
      std::fprintf(stderr, "finalize: %s: baseline %s is infeasible with this generated table\n",
                   s.name.c_str(), rule.c_str());
      return;
    }
    Measured m;
    m.label = label;
    m.schedule = "all " + rule;
    m.model_ns = t.cost_model().cost(*p);
    m.search_error = std::numeric_limits<double>::quiet_NaN();
    set_score(m, t.full_score(*p));
    m.mix[rule_family(rules::parse_rule(rule))] = 1;
    measure(t, *p, gl, &m);
    res.baselines.push_back(m);
  };
  uniform("plain", "none");
  const Measured plain = res.baselines.front();
  const auto plain_program = t.lower_plain();  // what MSAA-N and ssN run
  std::vector<Image> truth, msaa_frame0;
  for (const render::Frame& f : frames) truth.push_back(render::render_truth(s, f, cache));
  for (int n : {2, 4, 8, 16, 32}) {
    Measured m;
    m.label = "msaa" + std::to_string(n);
    m.schedule = "plain x " + std::to_string(n) + " jittered samples";
    m.msaa = n;
    m.model_ns = t.cost_model().msaa_cost(*plain_program, n);
    m.search_error = std::numeric_limits<double>::quiet_NaN();
    double sq = 0;
    for (std::size_t fi = 0; fi < frames.size(); ++fi) {
      const Image img = render::render_native(s, frames[fi], n);
      const PixelCounts c = check_pixels(img, t.value_range());
      m.nonfinite += c.nonfinite;
      m.out_of_range += c.out_of_range;
      const double e = rms_display(img, truth[fi]);
      sq += e * e;
      if (fi == 0) msaa_frame0.push_back(img);
    }
    set_error(m, std::sqrt(sq / frames.size()));
    measure(t, *plain_program, gl, &m, n, plain.eval_ms);
    m.glsl_ms = plain.glsl_ms >= 0 ? n * plain.glsl_ms : -1;
    m.mix["none"] = 1;
    res.baselines.push_back(m);
  }
  // Stratified supersampling in the shader (compiler/supersample.hpp): a fixed pattern, as GPU MSAA
  // places its samples; 8 of them reach MSAA-16's error on every suite scene (docs/tuning.md, stop 34).
  for (int n : kSupersampleBaselines) {
    const compiler::Program ss = compiler::stratified_samples(*plain_program, n, s.sigma_px);
    Measured m;
    m.label = "ss" + std::to_string(n);
    m.schedule = "plain x " + std::to_string(n) + " stratified samples in the shader";
    m.supersample = n;
    // The model's price: n samples one after another (CostModel::sequential_cost), one sample being
    // the plain program at one offset; cost(ss) would overlap the samples' latency chains.
    m.model_ns = t.cost_model().sequential_cost(compiler::one_sample(*plain_program, n, s.sigma_px), n);
    m.search_error = std::numeric_limits<double>::quiet_NaN();
    set_score(m, t.full_score(ss));
    measure(t, ss, gl, &m);
    m.mix["none"] = 1;
    res.baselines.push_back(m);
  }
  // Front points: refine sd factors, then measure on full images. Refinement minimises the error
  // alone and can raise the time (an sd factor moves an entry into a costlier sigma band: zigzag_none
  // went from 110 to 208 ns/px), so a refined point that costs more than its search point is
  // measured next to the unrefined one and the Pareto filter below keeps whichever is not dominated.
  std::vector<Measured> pts;
  std::vector<compiler::Schedule> schedules;
  auto consider = [&](const compiler::Schedule& sch, const Objectives& o, bool refined) {
    const auto p = t.lower(sch);
    if (!p) return;
    Measured m;
    m.refined = refined;
    m.schedule = compiler::schedule_to_text(t.graph(), sch);
    m.model_ns = o.time;
    m.search_error = o.error;
    set_score(m, t.full_score(*p));
    if (m.nonfinite > 0) {  // NaN/inf off the sample: as infeasible as on it
      std::fprintf(stderr,
                   "finalize: %s: a front point gives NaN/inf on %zu pixel(s) of the full images: dropped\n",
                   s.name.c_str(), m.nonfinite);
      return;
    }
    m.mix = rule_mix(t, sch);
    pts.push_back(m);
    schedules.push_back(sch);
  };
  std::vector<double> msaa_errors;
  double e16 = -1;
  for (const Measured& b : res.baselines) {
    if (b.msaa == 4 || b.msaa == 8 || b.msaa == 16) msaa_errors.push_back(b.error);
    if (b.msaa == 16) e16 = b.error;
  }
  auto refine_and_consider = [&](const Point& pt) {
    const compiler::Schedule sch = t.schedule(pt.genome);
    Objectives o;
    const compiler::Schedule refined = t.refine_sigma(sch, &o);
    const bool changed = !(refined == sch);
    consider(refined, o, changed);
    if (changed && o.time > pt.obj.time) consider(sch, t.evaluate(sch), false);
  };
  const std::vector<int> picked = pick_front_points(front, opt.max_points, msaa_errors);
  for (int i : picked) refine_and_consider(front[i]);
  // The points the speed-up at MSAA-16's error is read from (its anchors), polished: single-gene
  // changes that lower the model time at no more sample error (polish.hpp), and cheaper points moved
  // down to that error (reach).
  if (opt.polish && e16 > 0) {
    // Each anchor (the cheapest point under m e16 for each margin m) may spend up to its margin.
    std::vector<Genome> polished;
    for (double m : kAnchorMargins) {
      const int i = cheapest_under(front, m * e16);
      if (i < 0) continue;
      const Point q = polish(t, front[i], m * e16);
      std::fprintf(stderr,
                   "finalize: %s: polished search point %d: %.2f -> %.2f ns/px, sample error %.5f -> %.5f\n",
                   s.name.c_str(), i, front[i].obj.time, q.obj.time, front[i].obj.error, q.obj.error);
      if (q.genome != front[i].genome &&
          std::find(polished.begin(), polished.end(), q.genome) == polished.end()) {
        polished.push_back(q.genome);
        refine_and_consider(q);
      }
    }
    // From the cheapest uniform rule under each margin too (polish_from_uniform): the search's
    // front can sit in a costlier basin than the one a uniform start descends into.
    const std::vector<Point> uniform = uniform_points(t);
    for (double m : kAnchorMargins) {
      const std::optional<Point> q = polish_from_uniform(t, uniform, m * e16);
      if (!q) continue;
      std::fprintf(
          stderr,
          "finalize: %s: polished the cheapest uniform rule under %.5f: %.2f ns/px, sample error %.5f\n",
          s.name.c_str(), m * e16, q->obj.time, q->obj.error);
      if (std::find(polished.begin(), polished.end(), q->genome) == polished.end()) {
        polished.push_back(q->genome);
        refine_and_consider(*q);
      }
    }
    // And from below: the most accurate point cheaper than each anchor (any point when none is
    // under m e16) moved toward m e16 within the anchor's time (reach).
    for (double m : kAnchorMargins) {
      const int i = cheapest_under(front, m * e16);
      const double budget = i < 0 ? std::numeric_limits<double>::infinity() : front[i].obj.time;
      int j = -1;
      for (int k = 0; k < static_cast<int>(front.size()); ++k)
        if (front[k].obj.time < budget && (j < 0 || front[k].obj.error < front[j].obj.error)) j = k;
      if (j < 0) continue;
      const Point q = reach(t, front[j], m * e16, budget);
      std::fprintf(
          stderr,
          "finalize: %s: reached from search point %d toward %.5f: %.2f -> %.2f ns/px (budget %.2f), "
          "sample error %.5f -> %.5f\n",
          s.name.c_str(), j, m * e16, front[j].obj.time, q.obj.time, budget, front[j].obj.error, q.obj.error);
      if (q.obj.error <= m * e16 && q.obj.time < budget &&
          std::find(polished.begin(), polished.end(), q.genome) == polished.end()) {
        polished.push_back(q.genome);
        refine_and_consider(q);
      }
    }
  }
  // Refinement changes errors (and, through the scale constants, times a little): keep the front.
  std::vector<Objectives> obj;
  for (const Measured& m : pts) obj.push_back({m.model_ns, m.error});
  std::vector<compiler::Schedule> front_schedules;
  for (int i : pareto_front(obj)) {
    res.front.push_back(pts[i]);
    front_schedules.push_back(schedules[i]);
  }
  for (std::size_t i = 0; i < res.front.size(); ++i) {
    char label[32];
    std::snprintf(label, sizeof label, "front%02zu", i);
    res.front[i].label = label;
    measure(t, *t.lower(front_schedules[i]), gl, &res.front[i]);
  }
  if (e16 > 0) res.lod = find_lod(t, res.front, front_schedules, front, e16, gl);
  if (e16 > 0)
    if (const std::optional<PickedPair> a = adaptive_supersampling(t, e16))
      res.adaptive_ss = timed(t, *a, "adaptive supersampling", e16, gl);
  uniform("dorn", "dorn");
  uniform("gaussian", "gaussian");
  // Images of frame 0: truth | variant | MSAA of the nearest model time, for the fastest and the most
  // accurate front points and the fastest one at MSAA-16's error or better.
  if (!opt.out_dir.empty() && !res.front.empty()) {
    const Measured* m16 = nullptr;
    for (const Measured& b : res.baselines)
      if (b.msaa == 16) m16 = &b;
    std::vector<std::size_t> chosen{0, res.front.size() - 1};
    for (std::size_t i = 0; i < res.front.size(); ++i)
      if (m16 && res.front[i].error <= m16->error) {
        chosen.push_back(i);
        break;
      }
    std::sort(chosen.begin(), chosen.end());
    chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
    for (std::size_t i : chosen) {
      const Measured& m = res.front[i];
      std::size_t best = 0;
      for (std::size_t k = 1; k < msaa_frame0.size(); ++k)
        if (std::fabs(std::log(res.baselines[1 + k].model_ns / m.model_ns)) <
            std::fabs(std::log(res.baselines[1 + best].model_ns / m.model_ns)))
          best = k;
      const Image img = render::render_smoothed(s, frames.front(), *t.lower(front_schedules[i]));
      char a[96], b[96];
      std::snprintf(a, sizeof a, "%s %.4f", m.label.c_str(), m.error);
      std::snprintf(b, sizeof b, "%s %.4f", res.baselines[1 + best].label.c_str(),
                    res.baselines[1 + best].error);
      write_side_by_side(opt.out_dir + "/" + m.label + "_vs_truth_msaa.png",
                         {truth.front(), img, msaa_frame0[best]}, {"ground truth", a, b});
    }
  }
  if (!gl.jit_error.empty()) res.compiled_note = gl.jit_error.substr(0, gl.jit_error.find('\n'));
  if (const Speedup s16 = speedup16(res); s16.front_index >= 0) {
    const auto plain = t.lower_plain();
    res.anchor_breakdown =
        "### Where " + res.front[s16.front_index].label +
        "'s model time goes (the fastest point at MSAA-16's error)\n\n" +
        time_breakdown_markdown(t.cost_model(), *t.lower(front_schedules[s16.front_index]), *plain);
  }
  res.finalize_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

}  // namespace bl::tuner
