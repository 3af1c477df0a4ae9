// Lowering: traced DAG + one rule per node -> straight-line program (lir.hpp). Each node becomes a
// (mean, variance) pair, plus a screen-space gradient of the mean where a "gaussian:rho=grad" node
// needs the correlation of its inputs. Lowering is naive; optimize() then removes what the outputs do
// not need. Rules that do not apply to a node (e.g. box on a product, or a Gaussian rule for log,
// which has no Gaussian closed form) are replaced by the nearest rule that does, and the substitution
// is recorded in Program::notes.
#pragma once

#include <vector>

#include "compiler/lir.hpp"
#include "ir/graph.hpp"
#include "rules/rule.hpp"

namespace bl::compiler {

using Schedule = std::vector<rules::Rule>;  // one rule per graph node (indexed like Graph::nodes())

// Throws std::invalid_argument when the schedule's size differs from the graph's.
Program lower(const ir::Graph& g, const Schedule& schedule);

// The lowering before optimize(): what tests compare the optimized program's values against.
Program lower_naive(const ir::Graph& g, const Schedule& schedule);

// Convenience: the same rule on every node.
Schedule uniform_schedule(const ir::Graph& g, const rules::Rule& r);

// The fixed standard-normal samples node `node` uses for Monte Carlo with n samples and `dims`
// random inputs: antithetic pairs (z, -z) of a seeded stream, so linear nodes are exact, scaled per
// dimension to unit mean square (moment matching).
std::vector<float> mc_normals(int node, int n, int dims);

}  // namespace bl::compiler
