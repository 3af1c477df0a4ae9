#include "tuner/result_json.hpp"

#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

namespace bl::tuner {

using nlohmann::json;

namespace {

json num(double v) {
  return std::isfinite(v) ? json(v) : json(nullptr);
}  // NaN/inf -> null
double num(const json& j) {
  return j.is_null() ? std::numeric_limits<double>::quiet_NaN() : j.get<double>();
}

// A footprint pair (SceneResult::lod and ::adaptive_ss).
json to(const LodResult& p) {
  return {{"near", p.near},
          {"far", p.far},
          {"near_schedule", p.near_schedule},
          {"far_schedule", p.far_schedule},
          {"near_samples", p.near_samples},
          {"far_samples", p.far_samples},
          {"limit", p.limit},
          {"near_share", p.near_share},
          {"model_ns", p.model_ns},
          {"error", p.error},
          {"compiled_ns", p.compiled_ns}};
}
// Older files: a LOD pair without sample counts (before stop 36: each side its schedule); an
// adaptive supersampler with sample counts only (stop 35: labelled here plain or ssN, schedules "").
LodResult pair_from(const json& l) {
  LodResult p;
  p.near_samples = l.value("near_samples", 1);
  p.far_samples = l.value("far_samples", 1);
  auto label = [](int samples) {
    return samples > 1 ? "ss" + std::to_string(samples) : std::string("plain");
  };
  p.near = l.contains("near") ? l.at("near").get<std::string>() : label(p.near_samples);
  p.far = l.contains("far") ? l.at("far").get<std::string>() : label(p.far_samples);
  p.near_schedule = l.value("near_schedule", std::string());
  p.far_schedule = l.value("far_schedule", std::string());
  p.limit = l.at("limit");
  p.near_share = l.at("near_share");
  p.model_ns = l.at("model_ns");
  p.error = l.at("error");
  p.compiled_ns = l.at("compiled_ns");
  return p;
}

json to(const Measured& m) {
  return {{"label", m.label},
          {"schedule", m.schedule},
          {"msaa", m.msaa},
          {"supersample", m.supersample},
          {"model_ns", num(m.model_ns)},
          {"search_error", num(m.search_error)},
          {"error", num(m.error)},
          {"psnr", num(m.psnr)},
          {"nonfinite_pixels", m.nonfinite},
          {"out_of_range_pixels", m.out_of_range},
          {"eval_ms", num(m.eval_ms)},
          {"compiled_ns", num(m.compiled_ns)},
          {"compiled_ms", num(m.compiled_ms)},
          {"glsl_ms", num(m.glsl_ms)},
          {"refined", m.refined},
          {"mix", m.mix}};
}

Measured from(const json& j) {
  Measured m;
  m.label = j.at("label");
  m.schedule = j.at("schedule");
  m.msaa = j.at("msaa");
  m.supersample = j.value("supersample", 0);  // files before stop 34 have none
  m.model_ns = num(j.at("model_ns"));
  m.search_error = num(j.at("search_error"));
  m.error = num(j.at("error"));
  m.psnr = num(j.at("psnr"));
  m.nonfinite = j.value("nonfinite_pixels", std::size_t{0});
  m.out_of_range = j.value("out_of_range_pixels", std::size_t{0});
  m.eval_ms = num(j.at("eval_ms"));
  m.compiled_ns = j.contains("compiled_ns") ? num(j.at("compiled_ns")) : -1;
  m.compiled_ms = j.contains("compiled_ms") ? num(j.at("compiled_ms")) : -1;
  m.glsl_ms = num(j.at("glsl_ms"));
  m.refined = j.at("refined");
  m.mix = j.at("mix").get<std::map<std::string, double>>();
  return m;
}

}  // namespace

std::string result_to_json(const SceneResult& r) {
  json f = json::array(), b = json::array();
  for (const Measured& m : r.front) f.push_back(to(m));
  for (const Measured& m : r.baselines) b.push_back(to(m));
  return json{{"scene", r.scene},
              {"graph_hash", r.graph_hash},
              {"nodes", r.nodes},
              {"genes", r.genes},
              {"pixels", r.pixels},
              {"frames", r.frames},
              {"search_seconds", r.search_seconds},
              {"finalize_seconds", r.finalize_seconds},
              {"evaluations", r.evaluations},
              {"rejected_nonfinite", r.rejected_nonfinite},
              {"gl_renderer", r.gl_renderer},
              {"cost_machine", r.cost_machine},
              {"compiled_note", r.compiled_note},
              {"anchor_breakdown", r.anchor_breakdown},
              {"lod", r.lod ? to(*r.lod) : json()},
              {"adaptive_ss", r.adaptive_ss ? to(*r.adaptive_ss) : json()},
              {"front", f},
              {"baselines", b}}
      .dump(1);
}

SceneResult result_from_json(const std::string& text) {
  const json j = json::parse(text);
  SceneResult r;
  r.scene = j.at("scene");
  r.graph_hash = j.value("graph_hash", "");
  r.nodes = j.at("nodes");
  r.genes = j.at("genes");
  r.pixels = j.at("pixels");
  r.frames = j.at("frames");
  r.search_seconds = j.at("search_seconds");
  r.finalize_seconds = j.at("finalize_seconds");
  r.evaluations = j.at("evaluations");
  r.rejected_nonfinite = j.value("rejected_nonfinite", -1L);
  r.gl_renderer = j.at("gl_renderer");
  r.cost_machine = j.value("cost_machine", std::string());
  r.compiled_note = j.value("compiled_note", std::string());
  r.anchor_breakdown = j.value("anchor_breakdown", std::string());
  if (j.contains("lod") && !j.at("lod").is_null()) r.lod = pair_from(j.at("lod"));
  if (j.contains("adaptive_ss") && !j.at("adaptive_ss").is_null())
    r.adaptive_ss = pair_from(j.at("adaptive_ss"));
  for (const json& m : j.at("front")) r.front.push_back(from(m));
  for (const json& m : j.at("baselines")) r.baselines.push_back(from(m));
  return r;
}

SceneResult load_result(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::ostringstream text;
  text << in.rdbuf();
  try {
    return result_from_json(text.str());
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

}  // namespace bl::tuner
