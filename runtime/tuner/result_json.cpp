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
              {"compiled_note", r.compiled_note},
              {"anchor_breakdown", r.anchor_breakdown},
              {"lod", r.lod ? json{{"near", r.lod->near},
                                   {"far", r.lod->far},
                                   {"near_schedule", r.lod->near_schedule},
                                   {"far_schedule", r.lod->far_schedule},
                                   {"near_samples", r.lod->near_samples},
                                   {"far_samples", r.lod->far_samples},
                                   {"limit", r.lod->limit},
                                   {"near_share", r.lod->near_share},
                                   {"model_ns", r.lod->model_ns},
                                   {"error", r.lod->error},
                                   {"compiled_ns", r.lod->compiled_ns}}
                            : json()},
              {"adaptive_ss", r.adaptive_ss ? json{{"near_samples", r.adaptive_ss->near_samples},
                                                   {"far_samples", r.adaptive_ss->far_samples},
                                                   {"limit", r.adaptive_ss->limit},
                                                   {"near_share", r.adaptive_ss->near_share},
                                                   {"model_ns", r.adaptive_ss->model_ns},
                                                   {"error", r.adaptive_ss->error},
                                                   {"compiled_ns", r.adaptive_ss->compiled_ns}}
                                            : json()},
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
  r.compiled_note = j.value("compiled_note", std::string());
  r.anchor_breakdown = j.value("anchor_breakdown", std::string());
  if (j.contains("lod") && !j.at("lod").is_null()) {
    const json& l = j.at("lod");
    LodResult lod;
    lod.near = l.at("near");
    lod.far = l.at("far");
    lod.near_schedule = l.value("near_schedule", std::string());
    lod.far_schedule = l.value("far_schedule", std::string());
    lod.near_samples = l.value("near_samples", 1);  // results from stop 36 on
    lod.far_samples = l.value("far_samples", 1);
    lod.limit = l.at("limit");
    lod.near_share = l.at("near_share");
    lod.model_ns = l.at("model_ns");
    lod.error = l.at("error");
    lod.compiled_ns = l.at("compiled_ns");
    r.lod = lod;
  }
  if (j.contains("adaptive_ss") && !j.at("adaptive_ss").is_null()) {  // results from stop 35 on
    const json& l = j.at("adaptive_ss");
    AdaptiveSupersampling a;
    a.near_samples = l.at("near_samples");
    a.far_samples = l.at("far_samples");
    a.limit = l.at("limit");
    a.near_share = l.at("near_share");
    a.model_ns = l.at("model_ns");
    a.error = l.at("error");
    a.compiled_ns = l.at("compiled_ns");
    r.adaptive_ss = a;
  }
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
