#include "gl/shader_log.hpp"

#include <algorithm>
#include <regex>
#include <sstream>

namespace bl::gl {

std::vector<int> shader_log_lines(const std::string& log) {
  // Mesa: "<string>:<line>(<column>)"; NVIDIA/AMD: "<string>(<line>)" or "ERROR: <string>:<line>:".
  static const std::regex kPatterns[] = {std::regex(R"(^\s*\d+:(\d+)\(\d+\))"),
                                         std::regex(R"(^\s*\d+\((\d+)\))"),
                                         std::regex(R"(^\s*(?:ERROR|WARNING):\s*\d+:(\d+):)")};
  std::vector<int> lines;
  std::istringstream in(log);
  std::string row;
  while (std::getline(in, row)) {
    for (const auto& pattern : kPatterns) {
      std::smatch m;
      if (std::regex_search(row, m, pattern)) {
        int line = std::stoi(m[1].str());
        if (std::find(lines.begin(), lines.end(), line) == lines.end()) lines.push_back(line);
        break;
      }
    }
  }
  return lines;
}

std::string annotate_shader_log(const std::string& log, const std::string& source) {
  std::vector<std::string> src;
  std::istringstream in(source);
  for (std::string row; std::getline(in, row);) src.push_back(row);

  std::ostringstream out;
  out << log;
  if (!log.empty() && log.back() != '\n') out << '\n';
  const std::vector<int> lines = shader_log_lines(log);
  if (!lines.empty()) out << "offending source lines:\n";
  for (int line : lines) {
    out << "  " << line << " | ";
    if (line >= 1 && line <= static_cast<int>(src.size())) {
      out << src[line - 1];
    } else {
      out << "(no such line: the source has " << src.size() << ")";
    }
    out << '\n';
  }
  return out.str();
}

}  // namespace bl::gl
