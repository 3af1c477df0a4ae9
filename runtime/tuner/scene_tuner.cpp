#include "tuner/scene_tuner.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <nlopt.hpp>
#include <stdexcept>

#include "compiler/lower.hpp"
#include "ir/hash.hpp"
#include "tuner/magnitude_profile.hpp"
#include "tuner/rho_estimate.hpp"

namespace bl::tuner {

namespace {

std::string model_digest(const CostModel& cm) {  // recalibration invalidates checkpoints
  std::uint64_t h = ir::kFnvOffset;
  auto mix = [&](const std::string& s, double v) {
    h = ir::fnv1a(s, h);
    h = (h ^ static_cast<std::uint64_t>(std::llround(v * 1e6))) * ir::kFnvPrime;
  };
  for (const auto& [k, v] : cm.op_ns) mix(k, v);
  for (const auto& [k, v] : cm.fn_ns) mix(k, v);
  h = ir::fnv1a(cm.method, h);
  mix("window", cm.window_ns);
  for (const auto& [k, v] : cm.fn_lat_ns) mix(k, v);
  for (const auto& [k, v] : cm.op_lat_ns) mix(k, v);
  for (const auto& [k, v] : cm.fn_band_ns)
    for (double b : v) mix(k, b);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

}  // namespace

SceneTuner::SceneTuner(const scene::Scene& s, const CostModel& cm, const TuneOptions& opt)
    : scene_(s), graph_(shaders::trace(s.shader_def(), s.effects())), cm_(cm), opt_(opt) {
  sample_ = std::make_unique<PixelSample>(s, graph_, opt.cache_dir, opt.sample_pixels, opt.sample_seed);
  // The programs the argument profiles are read from, lowered once (finalize prices a footprint LOD's
  // programs over up to ~100 pixel subsets).
  profile_plain_ = lower_plain();
  profile_gaussian_ = lower(compiler::uniform_schedule(graph_, rules::parse_rule("gaussian")));
  // Banded function costs follow this scene's argument magnitudes (observed on the plain program).
  cm_ = cost_model_over(*sample_);
  problem_.graph = &graph_;
  problem_.space = SearchSpace::build(graph_);
  problem_.palette = Palette::parse(opt.rules);
  if (opt.estimate_rho) problem_.space.rho_constant = estimate_rho(graph_, s);
  problem_.evaluate = [this](const compiler::Schedule& sch) { return evaluate(sch); };
  char key[512];
  std::snprintf(key, sizeof key, "scene=%016llx graph=%016llx model=%s/%s sample=%d/%llu rho=%d",
                static_cast<unsigned long long>(s.hash()), static_cast<unsigned long long>(graph_.hash()),
                cm.machine.c_str(), model_digest(cm).c_str(), opt.sample_pixels,
                static_cast<unsigned long long>(opt.sample_seed), opt.estimate_rho ? 1 : 0);
  problem_.key = key;
}

CostModel SceneTuner::cost_model_over(const PixelSample& sample) const {
  CostModel m = cm_;
  m.band_share.clear();
  m.joint_share.clear();
  if (profile_plain_) m.band_share = magnitude_profile(*profile_plain_, sample);
  if (profile_gaussian_) m.joint_share = joint_profile(*profile_gaussian_, sample);
  return m;
}

compiler::Schedule SceneTuner::plain_schedule() const {
  return compiler::uniform_schedule(graph_, rules::parse_rule("none"));
}

std::unique_ptr<compiler::Program> SceneTuner::lower_plain() const {
  return lower(plain_schedule());
}

std::unique_ptr<compiler::Program> SceneTuner::lower(const compiler::Schedule& s) const {
  try {
    return std::make_unique<compiler::Program>(compiler::lower(graph_, s));
  } catch (const std::logic_error& e) {
    if (std::string(e.what()).find("has no function") != std::string::npos) return nullptr;
    throw;
  }
}

Objectives SceneTuner::evaluate(const compiler::Schedule& s) const {
  const auto p = lower(s);
  if (!p) return {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  const double e = sample_->error(*p);
  if (std::isinf(e)) ++nonfinite_;
  return {cm_.cost(*p), e};
}

PixelSample::Score SceneTuner::full_score(const compiler::Program& p) const {
  return full_sample().score(p);
}

const PixelSample& SceneTuner::full_sample() const {
  // Built on first use: the search itself never needs all pixels.
  std::call_once(full_once_,
                 [&] { full_ = std::make_unique<PixelSample>(scene_, graph_, opt_.cache_dir, 0, 0); });
  return *full_;
}

compiler::Schedule SceneTuner::schedule(const Genome& x) const {
  return to_schedule(graph_, problem_.space, problem_.palette, x);
}

compiler::Schedule SceneTuner::refine_sigma(const compiler::Schedule& s, Objectives* obj) const {
  *obj = evaluate(s);
  std::vector<int> nodes;  // smoothed computation nodes, depth-first
  for (int n : problem_.space.genes) {
    const ir::Op op = graph_.node(n).op;
    if (s[n].kind != rules::Kind::None && op != ir::Op::Input && op != ir::Op::Const) nodes.push_back(n);
  }
  if (opt_.nm_evals <= 0 || nodes.empty() || !std::isfinite(obj->error)) return s;
  const int groups = std::min(opt_.nm_groups, static_cast<int>(nodes.size()));
  auto apply = [&](const std::vector<double>& x) {
    compiler::Schedule t = s;
    for (std::size_t k = 0; k < nodes.size(); ++k) {
      const int g = static_cast<int>(k * groups / nodes.size());
      // Rounded to 3 decimals so the schedule's text form reproduces it exactly.
      t[nodes[k]].sigma_scale = s[nodes[k]].sigma_scale * std::round(std::exp2(x[g]) * 1000) / 1000;
    }
    return t;
  };
  struct Ctx {
    const SceneTuner* self;
    decltype(apply)* with_scales;
  } ctx{this, &apply};
  nlopt::opt nm(nlopt::LN_NELDERMEAD, groups);
  nm.set_lower_bounds(std::vector<double>(groups, -2.0));
  nm.set_upper_bounds(std::vector<double>(groups, 2.0));
  nm.set_initial_step(std::vector<double>(groups, 0.5));
  nm.set_maxeval(opt_.nm_evals);
  nm.set_min_objective(
      [](const std::vector<double>& x, std::vector<double>&, void* data) {
        const auto* c = static_cast<Ctx*>(data);
        const double e = c->self->evaluate((*c->with_scales)(x)).error;
        return std::isfinite(e) ? e : 1e9;
      },
      &ctx);
  std::vector<double> x(groups, 0.0);
  double best = 0;
  try {
    nm.optimize(x, best);
  } catch (const nlopt::roundoff_limited&) {
    // The best point so far is in x: still usable.
  }
  const compiler::Schedule t = apply(x);
  const Objectives o = evaluate(t);
  if (o.error < obj->error) {
    *obj = o;
    return t;
  }
  return s;
}

}  // namespace bl::tuner
