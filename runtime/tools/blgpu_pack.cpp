// blgpu_pack: the GLSL a renderer would run for a tuned suite, packed for timing on a GPU machine
// by blgpu_time (which needs nothing but an EGL/OpenGL driver, so the pack travels; see
// docs/gpu_timing.md). For each scene directory of a `bltune --suite` output: every front point's
// smoothed shader, the plain shader, MSAA-n of it (n samples per fragment) and the uniform rules,
// each as a complete fragment shader; the image is tiled so one draw fills a GPU with exactly the
// scene's per-pixel work; the footprint-LOD pair (result.json "lod") as one more shader, lod.frag;
// the GPU truth (the plain program at the scene's truth sample count) as truth.frag, drawn but not
// timed. manifest.json holds each frame's uniforms and, per program, the error and compiled-C++
// time bltune measured (the timing tool adds GPU times and errors on the GPU).
//
//   blgpu_pack --suite docs/tuning/suite --scenes scenes/suite --out build/gpu_pack [--tile 10]
//   blgpu_pack --suite out/tune/mine --scene my/pattern.json --out build/gpu_pack   (one scene)
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "compiler/emit.hpp"
#include "compiler/lower.hpp"
#include "compiler/schedule_csv.hpp"
#include "compiler/schedule_text.hpp"
#include "compiler/supersample.hpp"
#include "render/glsl_frame.hpp"
#include "render/render.hpp"
#include "render/value_range.hpp"
#include "scene/scene.hpp"
#include "shaders/shader.hpp"

using namespace bl;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json uniform_json(const gl::Uniform& u) {
  json j{{"name", u.name}};
  std::visit(
      [&](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, float>)
          j["float"] = v;
        else if constexpr (std::is_same_v<T, int>)
          j["int"] = v;
        else if constexpr (std::is_same_v<T, gl::Vec2> || std::is_same_v<T, gl::Vec3> ||
                           std::is_same_v<T, gl::Vec4>)
          j["vec"] = std::vector<float>(v.begin(), v.end());
        else
          throw std::invalid_argument("uniform " + u.name + ": matrices and samplers are not packed");
      },
      u.value);
  return j;
}

json read_json(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path.string() + ": cannot read");
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    throw std::runtime_error(path.string() + ": " + e.what());
  }
}

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw std::runtime_error(path.string() + ": write failed");
}

// One scene: its programs as fragment shaders under out/<scene>/, its manifest entry returned.
// Which programs to pack: every baseline and front point, or (a short GPU session) the named
// baselines and the `fronts` fastest front points (by compiled C++) at MSAA-16's error.
struct Selection {
  std::vector<std::string> baselines;  // empty: all
  int fronts = -1;                     // < 0: all
  int truth_samples = 0;               // the GPU truth's samples per pixel (0: the scene's)
};

json pack_scene(const fs::path& result_dir, const fs::path& scenes_dir, const std::string& scene_override,
                const fs::path& out, int tile, const Selection& sel) {
  const json result = read_json(result_dir / "result.json");
  const std::string name = result.at("scene").get<std::string>();
  // The scene file: --scene, else <scenes>/<scene name>.json, else <scenes>/<result dir>.json
  // (docs/tuning/glsl/hex_tiles tuned scenes/glsl/hex_tiles.json, whose scene is hex_tiles_glsl).
  fs::path scene_file = scene_override.empty() ? scenes_dir / (name + ".json") : fs::path(scene_override);
  if (scene_override.empty() && !fs::exists(scene_file) &&
      fs::exists(scenes_dir / (result_dir.filename().string() + ".json")))
    scene_file = scenes_dir / (result_dir.filename().string() + ".json");
  const scene::Scene s = scene::load_scene(scene_file.string());
  if (!s.texture_files.empty())
    throw std::invalid_argument(scene_file.string() +
                                ": textured scenes are not packed (no sampler uniforms)");
  const ir::Graph g = shaders::trace(s.shader_def(), s.effects());
  if (compiler::graph_hash_text(g) != result.at("graph_hash").get<std::string>())
    throw std::invalid_argument((result_dir / "result.json").string() + ": tuned for graph " +
                                result.at("graph_hash").get<std::string>() + ", but " + scene_file.string() +
                                " traces to " + compiler::graph_hash_text(g) + " (rerun bltune)");
  const std::string csv = (result_dir / "front.csv").string();
  fs::create_directories(out / name);
  json programs = json::array();
  auto add = [&](const json& row, const std::string& kind) {
    const std::string label = row.at("label").get<std::string>();
    const int msaa = row.at("msaa").get<int>(), ss = row.value("supersample", 0);
    // MSAA rows are the plain schedule run with n samples per fragment; ssN rows the plain program
    // supersampled in the shader (compiler/supersample.hpp).
    const compiler::Schedule sched =
        compiler::load_schedule(csv + ":" + (msaa > 0 || ss > 0 ? "plain" : label), g).schedule;
    const compiler::Program p = ss > 0
                                    ? compiler::stratified_samples(compiler::lower(g, sched), ss, s.sigma_px)
                                    : compiler::lower(g, sched);
    render::FragmentOptions fo;
    fo.samples = msaa;
    fo.tiled = true;
    const std::string frag = name + "/" + label + ".frag";
    write_file(out / frag, render::glsl_fragment_source(s, p, "450", fo));
    programs.push_back({{"label", label},
                        {"kind", kind},
                        {"msaa", msaa},
                        {"error", row.at("error")},
                        {"compiled_ns", row.value("compiled_ns", -1.0)},
                        {"model_ns", row.value("model_ns", -1.0)},
                        {"mix", row.value("mix", json::object())},
                        {"frag", frag}});
  };
  double msaa16_error = -1;
  for (const json& b : result.at("baselines")) {
    if (b.at("msaa").get<int>() == 16) msaa16_error = b.at("error").get<double>();
    const std::string label = b.at("label");
    if (sel.baselines.empty() ||
        std::find(sel.baselines.begin(), sel.baselines.end(), label) != sel.baselines.end())
      add(b, "baseline");
  }
  std::vector<json> fronts;
  for (const json& f : result.at("front"))
    if (sel.fronts < 0 || (f.at("error").is_number() && f.at("error").get<double>() <= msaa16_error))
      fronts.push_back(f);
  if (sel.fronts >= 0) {
    std::sort(fronts.begin(), fronts.end(), [](const json& a, const json& b) {
      return a.value("compiled_ns", 1e30) < b.value("compiled_ns", 1e30);
    });
    if (static_cast<int>(fronts.size()) > sel.fronts) fronts.resize(sel.fronts);
  }
  for (const json& f : fronts) add(f, "front");
  // A footprint pair as the fragment a renderer would run: both functions and the dispatcher of
  // compiler::emit_glsl_lod, `label`.frag, with the result's error and times.
  auto add_pair = [&](const std::string& label, const std::string& kind, const compiler::Program& near,
                      const compiler::Program& far, const json& r, const std::string& what, json entry) {
    const float limit = r.at("limit").get<float>();
    render::FragmentOptions fo;
    fo.tiled = true;
    const std::string frag = name + "/" + label + ".frag";
    write_file(out / frag,
               render::glsl_version_line("450") +
                   compiler::emit_glsl_lod(near, far, limit, "bl_shade", "scene " + name + ": " + what) +
                   "\n" + render::glsl_fragment_main(near, "bl_shade", fo));
    entry.update({{"label", label},
                  {"kind", kind},
                  {"msaa", 0},
                  {"error", r.at("error")},
                  {"compiled_ns", r.value("compiled_ns", -1.0)},
                  {"model_ns", r.value("model_ns", -1.0)},
                  {"mix", json::object()},
                  {"limit", limit},
                  {"frag", frag}});
    programs.push_back(entry);
  };
  // A footprint pair of result.json: each side its schedule at its stratified samples (the plain
  // program where the schedule is absent: stop 35's adaptive_ss).
  auto pair_side = [&](const json& l, const std::string& where, const std::string& key) {
    const std::string text = l.value(key + "_schedule", std::string());
    const compiler::Schedule sched = text.empty()
                                         ? compiler::load_schedule(csv + ":plain", g).schedule
                                         : compiler::parse_schedule(g, text, where + key + "_schedule");
    const compiler::Program p = compiler::lower(g, sched);
    return compiler::stratified_samples(p, l.value(key + "_samples", 1), s.sigma_px);
  };
  auto pair_what = [](const json& l) {  // sides without labels (stop 35): plain or ssN by their samples
    auto side = [&](const std::string& key) {
      const int n = l.value(key + "_samples", 1);
      return l.value(key, n > 1 ? "ss" + std::to_string(n) : std::string("plain"));
    };
    return side("near") + " + " + side("far");
  };
  // The footprint-LOD pair (bltune's result.json "lod": two front points or ssN and the limit).
  if (const auto it = result.find("lod"); it != result.end() && !it->is_null()) {
    const json& l = *it;
    const std::string where = (result_dir / "result.json").string() + ": lod.";
    add_pair("lod", "lod", pair_side(l, where, "near"), pair_side(l, where, "far"), l,
             "footprint LOD " + pair_what(l), {{"near", l.at("near")}, {"far", l.at("far")}});
  }
  // The footprint-adaptive supersampler (result.json "adaptive_ss": plain or ssN on each side).
  if (const auto it = result.find("adaptive_ss"); it != result.end() && !it->is_null()) {
    const json& a = *it;
    const std::string where = (result_dir / "result.json").string() + ": adaptive_ss.";
    add_pair("adaptive_ss", "adaptive", pair_side(a, where, "near"), pair_side(a, where, "far"), a,
             "adaptive supersampling " + pair_what(a), json::object());
  }
  // The GPU's own ground truth: the plain program at the scene's truth sample count in one fragment
  // (the CPU truth's kernel and count), its samples past every MSAA-n's so the two are independent.
  // blgpu_time renders it and every program at each frame and measures errors as bltune does; it
  // is never timed. (The CPU truth would not do for a hash pattern: fract(sin(x) * 43758.5) is
  // another pattern on another GPU's sin.)
  {
    render::FragmentOptions fo;
    fo.samples = sel.truth_samples > 0 ? sel.truth_samples : s.truth_samples;
    fo.tiled = true;
    fo.first_sample = 1u << 24;
    const std::string frag = name + "/truth.frag";
    write_file(out / frag,
               render::glsl_fragment_source(
                   s, compiler::lower(g, compiler::load_schedule(csv + ":plain", g).schedule), "450", fo));
    programs.push_back(
        {{"label", "truth"}, {"kind", "truth"}, {"msaa", fo.samples}, {"error", nullptr}, {"frag", frag}});
  }
  // Every frame's uniforms (views and times): errors are over all of them, as bltune's are; the
  // timings draw the first.
  json frames = json::array();
  for (const render::Frame& f : render::frames(s)) {
    json uniforms = json::array();
    for (const gl::Uniform& u : render::glsl_frame_uniforms(s, f)) uniforms.push_back(uniform_json(u));
    frames.push_back({{"view", f.view}, {"time", f.time}, {"uniforms", uniforms}});
  }
  // The valid range's declared part (render/value_range.hpp); blgpu_time widens [0, 1] on the
  // undeclared sides by its own truth and plain images, as bltune does with the CPU's.
  const DeclaredBounds d = render::declared_bounds(s, g);
  auto bound = [](float v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json declared = json::array();
  for (int c = 0; c < Image::kChannels; ++c) declared.push_back({bound(d.lo[c]), bound(d.hi[c])});
  return {{"scene", name},
          {"scene_width", s.width},
          {"scene_height", s.height},
          {"declared_range", declared},
          {"width", s.width * tile},
          {"height", s.height * tile},
          {"uniforms", frames.front().at("uniforms")},
          {"frames", frames},
          {"programs", programs}};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "blgpu_pack: a tuned suite's GLSL (fronts, plain, MSAA-n, uniform rules) packed for blgpu_time"};
  std::string suite = "docs/tuning/suite", scenes = "scenes/suite", scene_file, out, only;
  int tile = 10;
  Selection sel;
  app.add_option("--suite", suite,
                 "a bltune --suite output (one directory per scene with result.json), or one bltune --out "
                 "directory (result.json in it)");
  auto* scenes_opt = app.add_option("--scenes", scenes, "the directory of the scene files it was tuned on");
  app.add_option("--scene", scene_file, "the scene file of a single bltune --out directory (your own scene)")
      ->excludes(scenes_opt);
  app.add_option("--out", out, "the pack's directory (created; manifest.json and <scene>/<label>.frag)")
      ->required();
  app.add_option("--tile", tile, "the target is the scene's image repeated tile x tile times")
      ->check(CLI::Range(1, 64));
  app.add_option("--only", only, "pack only scenes whose name contains this");
  app.add_option("--baselines", sel.baselines, "pack only these baselines (plain, msaa16, gaussian, ...)")
      ->delimiter(',');
  app.add_option(
      "--fronts", sel.fronts,
      "pack only the N fastest front points (compiled C++) at MSAA-16's error (default: every point)");
  app.add_option("--truth-samples", sel.truth_samples,
                 "samples per pixel of the GPU truth the errors are measured against (default: the scene's "
                 "ground_truth.samples; fewer for a quick check on a CPU driver)")
      ->check(CLI::Range(1, 1 << 20));
  CLI11_PARSE(app, argc, argv);
  try {
    std::vector<fs::path> dirs;
    if (!fs::is_directory(suite)) throw std::invalid_argument(suite + ": not a directory");
    if (fs::exists(fs::path(suite) / "result.json")) {
      dirs.push_back(suite);  // one scene's bltune output
    } else {
      if (!scene_file.empty())
        throw std::invalid_argument("--scene names one scene, but " + suite + " has no result.json");
      for (const auto& e : fs::directory_iterator(suite))
        if (fs::exists(e.path() / "result.json") &&
            e.path().filename().string().find(only) != std::string::npos)
          dirs.push_back(e.path());
    }
    if (dirs.empty())
      throw std::invalid_argument(suite + ": no <scene>/result.json" +
                                  (only.empty() ? "" : " matching " + only));
    std::sort(dirs.begin(), dirs.end());
    fs::create_directories(out);
    json manifest{{"suite", suite}, {"tile", tile}, {"scenes", json::array()}};
    std::size_t count = 0;
    for (const fs::path& d : dirs) {
      manifest["scenes"].push_back(pack_scene(d, scenes, scene_file, out, tile, sel));
      count += manifest["scenes"].back()["programs"].size();
      std::fprintf(stderr, "packed %s (%zu programs)\n", d.filename().c_str(),
                   manifest["scenes"].back()["programs"].size());
    }
    write_file(fs::path(out) / "manifest.json", manifest.dump(1));
    std::printf("%s: %zu scenes, %zu fragment shaders\n", out.c_str(), dirs.size(), count);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "blgpu_pack: %s\n", e.what());
    return 1;
  }
  return 0;
}
