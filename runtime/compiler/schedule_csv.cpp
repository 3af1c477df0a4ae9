#include "compiler/schedule_csv.hpp"

#include <algorithm>
#include <fstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "compiler/schedule_text.hpp"

namespace bl::compiler {

namespace {

// One CSV line; fields may be double-quoted (bltune quotes rule_mix and schedule, which hold commas).
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '"') {
      if (quoted && i + 1 < line.size() && line[i + 1] == '"') {
        out.back() += '"';
        ++i;
      } else {
        quoted = !quoted;
      }
    } else if (c == ',' && !quoted) {
      out.emplace_back();
    } else if (c != '\r') {
      out.back() += c;
    }
  }
  return out;
}

int column(const std::vector<std::string>& header, const std::string& name, const std::string& file) {
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i] == name) return static_cast<int>(i);
  throw std::invalid_argument(file + ": no '" + name + "' column in the header" +
                              (name == "graph_hash" ? " (written by a bltune older than the graph check: "
                                                      "tune again to get a schedule that can be checked)"
                                                    : ""));
}

}  // namespace

LoadedSchedule load_schedule(const std::string& spec, const ir::Graph& g) {
  const auto colon = spec.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == spec.size())
    throw std::invalid_argument("schedule '" + spec +
                                "': expected FILE.csv:LABEL (e.g. out/front.csv:front02)");
  LoadedSchedule r;
  r.file = spec.substr(0, colon);
  r.label = spec.substr(colon + 1);
  std::ifstream in(r.file);
  if (!in) throw std::invalid_argument(r.file + ": cannot open the schedule file");
  std::string line;
  int line_no = 0;
  while (std::getline(in, line) && (++line_no, line.empty() || line[0] == '#')) {
  }
  if (line.empty()) throw std::invalid_argument(r.file + ": empty file, expected bltune's front.csv");
  const std::vector<std::string> header = csv_fields(line);
  const int c_label = column(header, "label", r.file), c_sched = column(header, "schedule", r.file),
            c_hash = column(header, "graph_hash", r.file), c_kind = column(header, "kind", r.file);
  // Sample counts of the MSAA-N and ssN baselines (files from stop 35 on; older ones say "plain x N"
  // in the schedule column instead).
  auto optional = [&](const char* name) {
    const auto it = std::find(header.begin(), header.end(), name);
    return it == header.end() ? -1 : static_cast<int>(it - header.begin());
  };
  const int c_msaa = optional("msaa"), c_ss = optional("supersample");
  std::string known;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> f = csv_fields(line);
    const std::string where = r.file + ":" + std::to_string(line_no);
    if (static_cast<int>(f.size()) != static_cast<int>(header.size()))
      throw std::invalid_argument(where + ": " + std::to_string(f.size()) + " fields, the header has " +
                                  std::to_string(header.size()));
    if (f[c_label] != r.label) {
      known += (known.empty() ? "" : ", ") + f[c_label];
      continue;
    }
    const std::string want = graph_hash_text(g);
    if (f[c_hash] != want)
      throw std::invalid_argument(where + " (" + r.label + "): tuned for graph " + f[c_hash] +
                                  ", the scene's shader traces to graph " + want +
                                  ": the schedule belongs to another shader or an older version of it");
    r.text = f[c_sched];
    if (r.text.rfind("all ", 0) == 0) {  // a uniform baseline ("all dorn")
      r.schedule = uniform_schedule(g, rules::parse_rule(r.text.substr(4)));
    } else if (f[c_kind] == "baseline" && (c_msaa >= 0 && c_ss >= 0 ? f[c_msaa] != "0" || f[c_ss] != "0"
                                                                    : r.text.rfind("plain x ", 0) == 0)) {
      throw std::invalid_argument(
          where + " (" + r.label +
          "): an MSAA baseline (or a stratified ssN one) is not a schedule (render it "
          "with blrender --msaa N, or --supersample N)");
    } else {
      r.schedule = parse_schedule(g, r.text, where + " (" + r.label + ")");
    }
    return r;
  }
  throw std::invalid_argument(r.file + ": no row labelled '" + r.label +
                              "' (known labels: " + (known.empty() ? "none" : known) + ")");
}

ChosenSchedule choose_schedule(const ir::Graph& g, const std::string& rules_text, const std::string& spec) {
  if (spec.empty()) return {uniform_schedule(g, rules::parse_rule(rules_text)), rules_text, rules_text};
  LoadedSchedule l = load_schedule(spec, g);
  return {std::move(l.schedule), l.label, l.file + ":" + l.label + ": " + l.text};
}

}  // namespace bl::compiler
