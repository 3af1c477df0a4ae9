// A schedule as text, the form bltune writes in front.csv's `schedule` column and blrender/blsmooth
// read back: space-separated `node:rule` entries, e.g. "3:none 5:mc2 6:rule2@0.54 9:gaussian:rho=grad".
// `node` is an index into Graph::nodes(), `rule` is rules::to_string's text. Nodes not listed get
// "none" (the tuner lists every gene, i.e. every reachable non-constant node, and leaves constants
// out). The text is only meaningful for the graph it was made for: keep Graph::hash() beside it
// (schedule_csv.hpp checks it).
#pragma once

#include <string>

#include "compiler/lower.hpp"
#include "ir/graph.hpp"

namespace bl::compiler {

// Every reachable non-constant node in depth-first order (the tuner's genes), then any other node
// whose rule is not "none", so parse_schedule(g, schedule_to_text(g, s)) == s for every s.
std::string schedule_to_text(const ir::Graph& g, const Schedule& s);

// Throws std::invalid_argument naming `where` (e.g. "front.csv label front02"), the entry's position
// and text, and what is wrong: an empty text, no ':', a node that is not an index of g, a node listed twice,
// or a rule parse_rule rejects.
Schedule parse_schedule(const ir::Graph& g, const std::string& text, const std::string& where = "schedule");

// Graph::hash as the 16 hex digits the tuner's outputs record.
std::string graph_hash_text(const ir::Graph& g);

}  // namespace bl::compiler
