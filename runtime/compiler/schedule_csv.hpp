// Loading a tuned schedule by name: "FILE.csv:LABEL" names a row of a bltune front.csv (a front
// point "front03", or the uniform baselines "plain", "dorn", "gaussian"). The CSV records the hash
// of the graph it was tuned for (column graph_hash); a schedule for another graph is refused.
#pragma once

#include <string>

#include "compiler/lower.hpp"
#include "ir/graph.hpp"

namespace bl::compiler {

struct LoadedSchedule {
  Schedule schedule;
  std::string file, label;
  std::string text;  // the schedule column as written
};

// `spec` is FILE:LABEL (split at the last ':'). Throws std::invalid_argument naming the file and,
// as the case may be: a missing ':', an unreadable file, a missing column, an unknown label (listing
// the known ones), an MSAA baseline (not a schedule), a graph hash that differs from g's, or (via
// parse_schedule) a bad entry.
LoadedSchedule load_schedule(const std::string& spec, const ir::Graph& g);

// What a tool was asked to compile: the tuned schedule `spec` (FILE:LABEL) when it is not empty,
// else the rule `rules_text` on every node. label: the front point's label or the rule text (names
// the method in reports and files); what: "FILE:LABEL: <schedule text>" or the rule text (banners).
struct ChosenSchedule {
  Schedule schedule;
  std::string label, what;
};
ChosenSchedule choose_schedule(const ir::Graph& g, const std::string& rules_text, const std::string& spec);

}  // namespace bl::compiler
