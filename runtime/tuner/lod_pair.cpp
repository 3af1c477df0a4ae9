// See lod_pair.hpp.
#include "tuner/lod_pair.hpp"

#include "compiler/schedule_text.hpp"
#include "compiler/supersample.hpp"
#include "tuner/lod_pricing.hpp"

namespace bl::tuner {

namespace {

// lod_candidates keeps this many pairs for fastest_on_own_pixels to re-price.
constexpr int kRepriced = 48;

}  // namespace

double LodSide::price(const CostModel& m) const {
  return samples > 1 ? m.sequential_cost(one, samples) : m.cost(program);
}

std::optional<LodSide> lod_side(const SceneTuner& t, const std::string& label,
                                const compiler::Schedule& schedule) {
  const auto p = t.lower(schedule);
  if (!p) return std::nullopt;
  LodSide sd;
  sd.label = label;
  sd.schedule = compiler::schedule_to_text(t.graph(), schedule);
  sd.smoothed = sd.schedule != compiler::schedule_to_text(t.graph(), t.plain_schedule());
  sd.program = *p;
  return sd;
}

std::vector<LodSide> lod_sides(const SceneTuner& t,
                               const std::vector<std::pair<std::string, compiler::Schedule>>& points) {
  const auto plain = t.lower_plain();
  if (!plain) return {};
  const std::string plain_text = compiler::schedule_to_text(t.graph(), t.plain_schedule());
  std::vector<LodSide> sides;
  for (const auto& [label, schedule] : points) {
    std::optional<LodSide> sd = lod_side(t, label, schedule);
    if (!sd) return {};
    sides.push_back(std::move(*sd));
  }
  const double sigma_px = t.scene().sigma_px;
  for (int n : kSupersampleCounts) {
    if (n == 1) continue;  // plain itself is a side only as a point
    LodSide sd;
    sd.label = "ss" + std::to_string(n);
    sd.schedule = plain_text;
    sd.samples = n;
    sd.smoothed = false;
    sd.program = compiler::stratified_samples(*plain, n, sigma_px);
    sd.one = compiler::one_sample(*plain, n, sigma_px);
    sides.push_back(std::move(sd));
  }
  return sides;
}

std::optional<PickedPair> fastest_pair(const SceneTuner& t, const std::vector<LodSide>& sides, double target,
                                       bool smoothed_far) {
  const PixelSample& all = t.full_sample();
  std::vector<std::vector<double>> sq;
  std::vector<double> model_ns;
  for (const LodSide& sd : sides) {
    sq.push_back(all.pixel_sq(sd.program));
    model_ns.push_back(sd.price(t.cost_model()));
  }
  const double dispatch = lod_dispatch_ns(t.cost_model());
  std::vector<LodChoice> cands;
  for (const LodChoice& c :
       lod_candidates(sq, all.footprints(), model_ns, all.miss_sq(), all.count(), target, dispatch, 64, -1)) {
    if (!smoothed_far || sides[c.far].smoothed) cands.push_back(c);
    if (static_cast<int>(cands.size()) == kRepriced) break;
  }
  const LodChoice c = fastest_on_own_pixels(
      t, cands, [&](const CostModel& m, int k) { return sides[k].price(m); }, dispatch);
  if (c.near < 0) return std::nullopt;
  const LodSide &near = sides[c.near], &far = sides[c.far];
  PickedPair p{{}, near.program, far.program};
  LodResult& r = p.result;
  r.near = near.label;
  r.far = far.label;
  r.near_schedule = near.schedule;
  r.far_schedule = far.schedule;
  r.near_samples = near.samples;
  r.far_samples = far.samples;
  r.limit = c.limit;
  r.near_share = c.near_share;
  r.model_ns = c.model_ns;
  r.error = c.error;
  return p;
}

}  // namespace bl::tuner
