// See suite.hpp.
#include "suite.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tuner/result_json.hpp"

namespace nb::acc {

Suite read_suite(const std::string& dir, const std::string& scenes_dir) {
  namespace fs = std::filesystem;
  Suite s;
  s.dir = dir;
  s.found = fs::is_directory(dir);
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(scenes_dir))
    if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  for (const std::string& n : names) {
    const fs::path p = fs::path(dir) / n / "result.json";
    std::ifstream in(p);
    if (!s.found || !in) {
      s.missing.push_back(n);
      continue;
    }
    std::stringstream text;
    text << in.rdbuf();
    s.scenes.push_back(bl::tuner::result_from_json(text.str()));
  }
  return s;
}

const bl::tuner::Measured* msaa(const bl::tuner::SceneResult& r, int n) {
  for (const auto& b : r.baselines)
    if (b.msaa == n) return &b;
  return nullptr;
}

bl::tuner::Speedup speedup_at(const bl::tuner::SceneResult& r, int n) {
  for (const auto& s : bl::tuner::speedups(r))
    if (s.msaa == n) return s;
  return {};
}

}  // namespace nb::acc
