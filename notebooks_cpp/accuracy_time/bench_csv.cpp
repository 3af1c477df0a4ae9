// See bench_csv.hpp. The columns are looked up by name in the header, so a reordered file still reads.
#include "bench_csv.hpp"

#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace nb::acc {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) out.push_back(cell);
  return out;
}

}  // namespace

std::vector<EntryRow> read_accuracy_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in)
    throw std::runtime_error(path + " not found: run `build/bin/bench_table --summary docs/accuracy_cost`");
  std::string line;
  std::getline(in, line);
  std::map<std::string, std::size_t> col;
  const std::vector<std::string> header = split(line);
  for (std::size_t i = 0; i < header.size(); ++i) col[header[i]] = i;
  auto at = [&](const std::vector<std::string>& c, const std::string& name) -> const std::string& {
    const auto it = col.find(name);
    if (it == col.end() || it->second >= c.size()) throw std::runtime_error(path + ": no column " + name);
    return c[it->second];
  };
  auto num = [&](const std::vector<std::string>& c, const std::string& name) {
    return std::stod(at(c, name));
  };
  std::vector<EntryRow> rows;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::vector<std::string> c = split(line);
    EntryRow r;
    r.entry = at(c, "entry");
    r.kernel = at(c, "kernel");
    r.family = at(c, "family");
    r.plain_ns = num(c, "plain_ns");
    r.smoothed_ns = num(c, "smoothed_ns");
    r.err_plain = num(c, "err_plain");
    for (int k = 0; k < 3; ++k) {
      const std::string n = std::to_string(kMcSamples[k]);
      r.mc_ns[k] = num(c, "mc" + n + "_ns");
      r.err_mc[k] = num(c, "err_mc" + n);
    }
    r.ref_rms = num(c, "ref_rms");
    r.f32_smoothed_ns = num(c, "f32_smoothed_ns");
    r.f32_smoothed_err = num(c, "f32_smoothed_err");
    rows.push_back(r);
  }
  return rows;
}

}  // namespace nb::acc
