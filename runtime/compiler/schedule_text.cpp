#include "compiler/schedule_text.hpp"

#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace bl::compiler {

std::string schedule_to_text(const ir::Graph& g, const Schedule& s) {
  if (static_cast<int>(s.size()) != g.size())
    throw std::invalid_argument("schedule_to_text: a schedule of " + std::to_string(s.size()) +
                                " rules for a graph of " + std::to_string(g.size()) + " nodes");
  std::vector<char> listed(g.size(), 0);
  std::string out;
  auto put = [&](int n) {
    out += (out.empty() ? "" : " ") + std::to_string(n) + ":" + rules::to_string(s[n]);
    listed[n] = 1;
  };
  for (int n : g.depth_first_order())
    if (g.node(n).op != ir::Op::Const) put(n);
  for (int n = 0; n < g.size(); ++n)
    if (!listed[n] && !(s[n] == rules::Rule{})) put(n);
  return out;
}

Schedule parse_schedule(const ir::Graph& g, const std::string& text, const std::string& where) {
  Schedule s(g.size());
  std::vector<char> seen(g.size(), 0);
  std::istringstream in(text);
  int k = 0;
  for (std::string entry; in >> entry; ++k) {
    auto bad = [&](const std::string& why) {
      throw std::invalid_argument(where + ": entry " + std::to_string(k + 1) + " '" + entry + "': " + why);
    };
    const auto colon = entry.find(':');
    if (colon == std::string::npos || colon == 0) bad("expected node:rule");
    const std::string node = entry.substr(0, colon);
    if (node.find_first_not_of("0123456789") != std::string::npos || node.size() > 9)
      bad("node '" + node + "' is not a node index");
    const int n = std::stoi(node);
    if (n >= g.size())
      bad("node " + node + " is not in the graph (" + std::to_string(g.size()) +
          " nodes): was the schedule made for another shader?");
    if (seen[n]) bad("node " + node + " is listed twice");
    seen[n] = 1;
    try {
      s[n] = rules::parse_rule(entry.substr(colon + 1));
    } catch (const std::invalid_argument& e) {
      bad(e.what());
    }
  }
  if (k == 0)
    throw std::invalid_argument(where + ": the schedule text is empty (expected node:rule entries)");
  return s;
}

std::string graph_hash_text(const ir::Graph& g) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(g.hash()));
  return buf;
}

}  // namespace bl::compiler
