// Greedy descent from a search-front point: single-gene rule changes (and joint changes of the gene
// pairs the compiler fuses, below) that lower the model time while the sample error stays at most the
// point's own. The genetic search stops after 20 generations with fronts that still hold such moves
// (quadratic_sine_none's point at MSAA-16's error kept smoothing nodes whose plain rule costs less and
// changes nothing visible); finalize polishes the points it reads the speed-up at MSAA-16's error from.
#pragma once

#include <optional>

#include "tuner/genetic.hpp"
#include "tuner/scene_tuner.hpp"

namespace bl::tuner {

struct PolishOptions {
  int max_steps = 20;            // accepted changes
  int max_evals_per_step = 160;  // sample-error evaluations tried per step, cheapest model time first
  int max_evals = 1000;          // in all: bounds the time on large lattice shaders (bricks: ~5 ms each)
};

// The point after descent (the input itself when no change helps): every step lowers the model time
// of all single-gene changes (lowering only, no pixels), then evaluates the sample error of the
// cheaper ones in order of model time and takes the first whose error is <= limit (the start's own
// error when limit < 0).
Point polish(const SceneTuner& t, const Point& start, double limit = -1, const PolishOptions& opt = {});

// The other side of the same descent: from a point cheaper than `budget` whose sample error is above
// `target`, greedy single-gene changes (and fused pairs to one rule) whose model time stays below
// `budget`; each step evaluates them cheapest first and takes the cheapest that reaches `target`,
// else the one with the lowest error (when it lowers the error at all). The search's front often
// has a point just above a target error and the next one well above it in time (fire_bumps: 1% too
// much error at 10x less model time than MSAA-16, while the point at MSAA-16's error is at 6.6x).
// The start itself when no change lowers the error; the caller keeps the result only if it reaches
// the target.
Point reach(const SceneTuner& t, const Point& start, double target, double budget,
            const PolishOptions& opt = {});

// The cheapest point whose search error is <= limit (the first of equal times), -1 if none: the
// anchors finalize measures and polishes, and polish_from_uniform's start.
int cheapest_under(const std::vector<Point>& pts, double limit);

// Every uniform genome (one palette rule on every gene) with its objectives, in palette order.
std::vector<Point> uniform_points(const SceneTuner& t);

// The same descent from a uniform rule: the cheapest of `uniform` (uniform_points, evaluated once for
// all limits) whose sample error is <= limit, polished with that limit; nullopt when none reaches
// it. The genetic search's front can sit in another basin than the simple kernel mixes: at the
// stop-43 calibration bricks_ripples' front offered 123.66 ns/px at MSAA-16's error (a mix of
// gaussian rho=grad, rule3 and Gaussian steps, 1.96x plain), single-gene moves could not leave it,
// and the descent from all-box, all-tent or all-Gaussian each ends at 76.51 ns/px (box/tent/none,
// 1.21x plain) at the same error.
std::optional<Point> polish_from_uniform(const SceneTuner& t, const std::vector<Point>& uniform, double limit,
                                         const PolishOptions& opt = {});

// A move of the descents (polish, reach, the pair's polish_pair): gene a (and b, when a fused pair
// moves together; -1 otherwise) to palette rule `rule`.
struct GeneMove {
  int a = -1, b = -1;
  int rule = 0;
};

// Every single-gene change and every change of a fused pair (fused_gene_pairs) to one rule, in that
// order (genes, then rules); holds(gene, rule) says the current assignment already has it (a pair
// moves only when neither gene holds the rule: single-gene moves cover the rest).
template <class Holds>
std::vector<GeneMove> gene_moves(const Problem& prob, const std::vector<std::pair<int, int>>& fused,
                                 Holds holds) {
  const int rules = static_cast<int>(prob.palette.rules.size());
  std::vector<GeneMove> out;
  for (int k = 0; k < prob.space.size(); ++k)
    for (int r = 0; r < rules; ++r)
      if (!holds(k, r)) out.push_back({k, -1, r});
  for (const auto& [ga, gb] : fused)
    for (int r = 0; r < rules; ++r)
      if (!holds(ga, r) && !holds(gb, r)) out.push_back({ga, gb, r});
  return out;
}

// Gene pairs the compiler fuses only when both carry one kernel and width (a floor pair's pulse,
// floor(y + 1/2) - floor(y); a fract window's two steps, also as the second pair of a product chain):
// a single-gene move breaks the fusion, so it cannot move the pair to another kernel (checkerboard's
// pulses stayed Gaussian where box ones cost 8 ns less). polish also moves each pair to one rule.
std::vector<std::pair<int, int>> fused_gene_pairs(const Problem& prob);

}  // namespace bl::tuner
