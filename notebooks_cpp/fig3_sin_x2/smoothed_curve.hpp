// A 1D smoothed program through the real pipeline: trace a shader of one input u, lower it under a
// uniform rule, run the batch Evaluator with (mean x, sd sigma, screen gradient (1, 0)) per point.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "compiler/lir.hpp"
#include "dsl/trace.hpp"
#include "ir/graph.hpp"

namespace nb::sin_x2 {

// The graph of r = f(u), u the one varying input.
bl::ir::Graph trace_1d(const std::function<bl::dsl::Var(bl::dsl::Var)>& f);

// The program for `rule` ("dorn", "gaussian", "mc8", ...) on every node.
bl::compiler::Program compile(const bl::ir::Graph& g, const std::string& rule);

// The output mean at each x, the input u ~ (x, sigma^2).
std::vector<float> evaluate(const bl::compiler::Program& p, const std::vector<float>& xs, float sigma);

// Evaluator time per point (ns) over the batch xs: the best of `rounds` rounds, each repeating the
// batch for at least round_seconds (the best, because the cores are shared and noise only adds).
double ns_per_eval(const bl::compiler::Program& p, const std::vector<float>& xs, float sigma, int rounds = 7,
                   double round_seconds = 0.03);

}  // namespace nb::sin_x2
