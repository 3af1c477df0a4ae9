// See smoothed_curve.hpp.
#include "smoothed_curve.hpp"

#include <algorithm>
#include <chrono>

#include "compiler/evaluator.hpp"
#include "compiler/lower.hpp"
#include "rules/rule.hpp"

namespace nb::sin_x2 {
namespace {

// Inputs for one point each: mean x, sd sigma, gradient (1, 0) (u moves with screen x).
struct Inputs {
  std::vector<float> sd, gx, gy;
  bl::compiler::Batch batch;
  Inputs(const std::vector<float>& xs, float sigma)
      : sd(xs.size(), sigma), gx(xs.size(), 1.0f), gy(xs.size(), 0.0f) {
    batch.count = static_cast<int>(xs.size());
    batch.mean = {xs.data()};
    batch.sd = {sd.data()};
    batch.grad_x = {gx.data()};
    batch.grad_y = {gy.data()};
  }
};

}  // namespace

bl::ir::Graph trace_1d(const std::function<bl::dsl::Var(bl::dsl::Var)>& f) {
  bl::ir::Graph g;
  bl::dsl::Tracer t(g);
  const bl::dsl::Var u = bl::dsl::Var::input("u", true);
  g.add_output("r", f(u).id());
  return g;
}

bl::compiler::Program compile(const bl::ir::Graph& g, const std::string& rule) {
  return bl::compiler::lower(g, bl::compiler::uniform_schedule(g, bl::rules::parse_rule(rule)));
}

std::vector<float> evaluate(const bl::compiler::Program& p, const std::vector<float>& xs, float sigma) {
  Inputs in(xs, sigma);
  std::vector<float> out(xs.size());
  bl::compiler::Evaluator(p).run(in.batch, {out.data()});
  return out;
}

double ns_per_eval(const bl::compiler::Program& p, const std::vector<float>& xs, float sigma, int rounds,
                   double round_seconds) {
  using clock = std::chrono::steady_clock;
  Inputs in(xs, sigma);
  std::vector<float> out(xs.size());
  bl::compiler::Evaluator ev(p);
  ev.run(in.batch, {out.data()});  // warm-up (allocations, caches)
  double best = 1e300;
  for (int r = 0; r < rounds; ++r) {
    long points = 0;
    double elapsed = 0;
    const auto t0 = clock::now();
    do {
      ev.run(in.batch, {out.data()});
      points += static_cast<long>(xs.size());
      elapsed = std::chrono::duration<double>(clock::now() - t0).count();
    } while (elapsed < round_seconds);
    best = std::min(best, 1e9 * elapsed / static_cast<double>(points));
  }
  return best;
}

}  // namespace nb::sin_x2
