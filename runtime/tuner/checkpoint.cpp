#include "tuner/checkpoint.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

namespace bl::tuner {

using nlohmann::json;

namespace {

// JSON has no infinity: infeasible objectives are written as null.
json num(double v) {
  return std::isfinite(v) ? json(v) : json(nullptr);
}
double num(const json& j) {
  return j.is_null() ? std::numeric_limits<double>::infinity() : j.get<double>();
}

json points_json(const std::vector<Point>& pts) {
  json a = json::array();
  for (const Point& p : pts)
    a.push_back({{"genome", genome_key(p.genome)}, {"time", num(p.obj.time)}, {"error", num(p.obj.error)}});
  return a;
}

std::vector<Point> points_of(const json& a, int palette_size) {
  std::vector<Point> out;
  for (const json& p : a)
    out.push_back({genome_from_key(p.at("genome").get<std::string>(), palette_size),
                   {num(p.at("time")), num(p.at("error"))}});
  return out;
}

}  // namespace

void save_checkpoint(const std::string& path, const Checkpoint& c, const Palette& pal) {
  std::ostringstream rng;
  rng << c.rng;
  json pop = json::array();
  for (std::size_t i = 0; i < c.population.size(); ++i)
    pop.push_back({{"genome", genome_key(c.population[i])},
                   {"time", num(c.objectives[i].time)},
                   {"error", num(c.objectives[i].error)}});
  const json j = {{"problem", c.problem_key},     {"options", c.options_key},   {"seed", c.seed},
                  {"restart", c.restart},         {"generation", c.generation}, {"complete", c.complete},
                  {"palette", pal.names},         {"rng", rng.str()},           {"population", pop},
                  {"front", points_json(c.front)}};
  const std::filesystem::path p(path);
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << j.dump(1) << "\n";
    if (!out) throw std::runtime_error("checkpoint: cannot write " + tmp);
  }
  std::filesystem::rename(tmp, path);
}

bool load_checkpoint(const std::string& path, const Checkpoint& expect, const Palette& pal, Checkpoint* out) {
  std::ifstream in(path);
  if (!in) return false;
  json j;
  try {
    in >> j;
    if (j.at("problem") != expect.problem_key || j.at("options") != expect.options_key ||
        j.at("seed").get<std::uint64_t>() != expect.seed || j.at("restart").get<int>() != expect.restart ||
        j.at("palette").get<std::vector<std::string>>() != pal.names)
      return false;
    Checkpoint c = expect;
    c.generation = j.at("generation").get<int>();
    c.complete = j.at("complete").get<bool>();
    std::istringstream rng(j.at("rng").get<std::string>());
    rng >> c.rng;
    if (!rng) throw std::runtime_error("bad RNG state");
    const int n = static_cast<int>(pal.rules.size());
    for (const Point& p : points_of(j.at("population"), n)) {
      c.population.push_back(p.genome);
      c.objectives.push_back(p.obj);
    }
    c.front = points_of(j.at("front"), n);
    *out = std::move(c);
    return true;
  } catch (const std::exception& e) {
    throw std::runtime_error("checkpoint " + path + " is corrupt: " + e.what() +
                             " (delete it to start over)");
  }
}

std::string points_to_json(const std::vector<Point>& pts) {
  return points_json(pts).dump();
}

std::vector<Point> points_from_json(const std::string& text, int palette_size) {
  return points_of(json::parse(text), palette_size);
}

}  // namespace bl::tuner
