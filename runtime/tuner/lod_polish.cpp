// See lod_polish.hpp.
#include "tuner/lod_polish.hpp"

#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace bl::tuner {

namespace {

// One side of the pair: its pixels, its price there, its squared error summed over them.
struct Side {
  PixelSample pixels;
  CostModel cost;
  double share = 0;
  compiler::Schedule schedule;
  double time = 0;  // cost.cost(program), unweighted
  double sq = 0;    // squared display error summed over pixels' channels (+inf on NaN/inf)

  // sq of a program on these pixels: the RMS PixelSample::error gives (+inf on a NaN/inf pixel)
  // back to a sum, so the two sides' sums add to the pair's.
  double error_sq(const compiler::Program& p) const {
    const double e = pixels.error(p);
    return std::isfinite(e) ? e * e * 3.0 * pixels.count() : std::numeric_limits<double>::infinity();
  }
};

// Candidates evaluated together; fixed, so results do not depend on the thread count.
constexpr int kChunk = 16;

struct Move {
  int side;
  compiler::Schedule schedule;
  double cost = 0;                                       // on its side's pixels
  double sq = std::numeric_limits<double>::quiet_NaN();  // its side's error sum; NaN: not evaluated
};

// gene_moves of `cur` as schedules.
std::vector<Move> side_moves(const Problem& prob, const std::vector<std::pair<int, int>>& fused,
                             const compiler::Schedule& cur, int side) {
  auto rule_of = [&](int gene, int r) { return gene_rule(prob.space, prob.palette, gene, r); };
  std::vector<Move> out;
  for (const GeneMove& g : gene_moves(
           prob, fused, [&](int gene, int r) { return cur[prob.space.genes[gene]] == rule_of(gene, r); })) {
    Move m{side, cur};
    m.schedule[prob.space.genes[g.a]] = rule_of(g.a, g.rule);
    if (g.b >= 0) m.schedule[prob.space.genes[g.b]] = rule_of(g.b, g.rule);
    out.push_back(std::move(m));
  }
  return out;
}

PolishedPair descend(const SceneTuner& t, const compiler::Schedule& near, const compiler::Schedule& far,
                     float limit, double near_share, double error_scale, const PolishOptions& opt) {
  if (!(near_share >= 0 && near_share <= 1))
    throw std::invalid_argument("polish_pair: near share " + std::to_string(near_share) + " outside [0, 1]");
  if (!(error_scale >= 1))
    throw std::invalid_argument("polish_pair: error scale " + std::to_string(error_scale) + " below 1");
  const PixelSample& all = t.search_sample();
  Side sides[2] = {{all.subset(limit, true), {}, near_share, near},
                   {all.subset(limit, false), {}, 1 - near_share, far}};
  for (int k = 0; k < 2; ++k) {
    Side& s = sides[k];
    s.cost = t.cost_model_over(s.pixels);
    const auto p = t.lower(s.schedule);
    if (!p)
      throw std::invalid_argument(std::string("polish_pair: the ") + (k ? "far" : "near") +
                                  " schedule does not lower");
    s.time = s.cost.cost(*p);
    s.sq = s.error_sq(*p);
  }
  const double denom = 3.0 * all.count();
  auto pair_time = [&](double t0, double t1) { return sides[0].share * t0 + sides[1].share * t1; };
  auto rms = [&](double sq) { return std::sqrt((all.miss_sq() + sq) / denom); };
  const double start_sq = sides[0].sq + sides[1].sq;
  const double start_rms = rms(start_sq), scaled = error_scale * start_rms;
  const double limit_sq = std::max(start_sq, scaled * scaled * denom - all.miss_sq());
  PolishedPair out;
  out.time_before = pair_time(sides[0].time, sides[1].time);
  out.error_before = start_rms;
  if (!std::isfinite(start_sq)) {
    out.near = near, out.far = far, out.time_after = out.time_before, out.error_after = out.error_before;
    return out;
  }
  const Problem& prob = t.problem();
  const auto fused = fused_gene_pairs(prob);
  // Each side's moves with their price on its pixels, rebuilt only for the side that moved (the
  // other's keep their prices, and the errors already evaluated: a side's error sum depends on its
  // own schedule alone).
  std::vector<Move> moves[2];
  bool dirty[2] = {true, true};
  for (int step = 0; step < opt.max_steps && out.evaluations < opt.max_evals; ++step) {
    for (int k = 0; k < 2; ++k) {
      if (!dirty[k]) continue;
      dirty[k] = false;
      moves[k] = side_moves(prob, fused, sides[k].schedule, k);
      tbb::parallel_for(std::size_t(0), moves[k].size(), [&](std::size_t i) {
        const auto p = t.lower(moves[k][i].schedule);
        moves[k][i].cost = p ? sides[k].cost.cost(*p) : std::numeric_limits<double>::infinity();
      });
    }
    // Every cheaper move on either side, by the pair's time.
    const double now = pair_time(sides[0].time, sides[1].time);
    std::vector<std::pair<double, Move*>> cand;
    for (int k = 0; k < 2; ++k)
      for (Move& m : moves[k]) {
        const double pt = k == 0 ? pair_time(m.cost, sides[1].time) : pair_time(sides[0].time, m.cost);
        if (pt < now) cand.emplace_back(pt, &m);
      }
    std::stable_sort(cand.begin(), cand.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    // The cheapest move that keeps the pair's error, evaluated kChunk at a time in parallel and read
    // in order, so the result and the evaluation count do not depend on the thread count; errors
    // known from an earlier step are not evaluated again.
    const int tries = std::min<int>(static_cast<int>(cand.size()), opt.max_evals_per_step);
    int taken = -1;
    for (int from = 0; from < tries && taken < 0 && out.evaluations < opt.max_evals; from += kChunk) {
      const int to = std::min(tries, from + kChunk);
      for (int i = from; i < to; ++i) out.evaluations += std::isnan(cand[i].second->sq);
      tbb::parallel_for(from, to, [&](int i) {
        Move& m = *cand[i].second;
        if (std::isnan(m.sq)) m.sq = sides[m.side].error_sq(*t.lower(m.schedule));
      });
      for (int i = from; i < to && taken < 0; ++i) {
        const Move& m = *cand[i].second;
        if (sides[0].sq + sides[1].sq - sides[m.side].sq + m.sq <= limit_sq) taken = i;
      }
    }
    if (taken < 0) break;
    Move& m = *cand[taken].second;
    Side& s = sides[m.side];
    s.schedule = std::move(m.schedule);
    s.time = m.cost;
    s.sq = m.sq;
    dirty[m.side] = true;
    ++out.steps;
  }
  out.near = sides[0].schedule;
  out.far = sides[1].schedule;
  out.time_after = pair_time(sides[0].time, sides[1].time);
  out.error_after = rms(sides[0].sq + sides[1].sq);
  return out;
}

}  // namespace

PolishedPair polish_pair(const SceneTuner& t, const compiler::Schedule& near, const compiler::Schedule& far,
                         float limit, double near_share, double error_scale, const PolishOptions& opt) {
  // As bltune --threads (0: every hardware thread); TBB warns above the machine's concurrency.
  const int threads = t.options().search.threads;
  tbb::task_arena arena(threads > 0 ? std::min(threads, tbb::info::default_concurrency())
                                    : tbb::task_arena::automatic);
  return arena.execute([&] { return descend(t, near, far, limit, near_share, error_scale, opt); });
}

}  // namespace bl::tuner
