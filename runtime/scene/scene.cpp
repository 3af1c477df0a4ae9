#include "scene/scene.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include "glsl/shader.hpp"
#include "ir/hash.hpp"

namespace bl::scene {

using json = nlohmann::json;

namespace {

[[noreturn]] void fail(const std::string& origin, const std::string& field, const std::string& why) {
  throw std::invalid_argument("scene " + origin + (field.empty() ? "" : ", field '" + field + "'") + ": " +
                              why);
}

void only_fields(const json& j, const std::string& origin, const std::string& where,
                 const std::set<std::string>& allowed) {
  if (!j.is_object()) fail(origin, where, "must be an object");
  for (auto it = j.begin(); it != j.end(); ++it)
    if (!allowed.count(it.key())) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      fail(origin, where.empty() ? it.key() : where + "." + it.key(),
           "unknown field (allowed: " + list + ")");
    }
}

double number(const json& j, const std::string& origin, const std::string& field) {
  if (!j.is_number()) fail(origin, field, "must be a number, got " + j.dump());
  const double v = j.get<double>();
  if (!std::isfinite(v)) fail(origin, field, "must be finite");
  return v;
}

std::array<double, 3> vec3(const json& j, const std::string& origin, const std::string& field) {
  if (!j.is_array() || j.size() != 3) fail(origin, field, "must be an array of 3 numbers, got " + j.dump());
  return {number(j[0], origin, field), number(j[1], origin, field), number(j[2], origin, field)};
}

int positive_int(const json& j, const std::string& origin, const std::string& field, int max) {
  if (!j.is_number_integer() || j.get<long long>() < 1 || j.get<long long>() > max)
    fail(origin, field, "must be an integer in [1, " + std::to_string(max) + "], got " + j.dump());
  return j.get<int>();
}

std::string str(const json& j, const std::string& origin, const std::string& field) {
  if (!j.is_string()) fail(origin, field, "must be a string, got " + j.dump());
  return j.get<std::string>();
}

const char* parallax_name(shaders::Parallax p) {
  switch (p) {
    case shaders::Parallax::None:
      return "none";
    case shaders::Parallax::Bumps:
      return "bumps";
    case shaders::Parallax::Ripples:
      return "ripples";
  }
  return "?";
}

// "textures": {"<slot>": "<file>"}: every slot the shader declares, no other.
void load_textures(Scene& s, const json& j, const std::string& origin) {
  const shaders::ShaderDef& def = s.shader_def();
  std::string slots;
  for (const auto& t : def.textures) slots += (slots.empty() ? "" : ", ") + t.name;
  json bound = j.contains("textures") ? j["textures"] : json::object();
  if (!bound.is_object()) fail(origin, "textures", "must be an object {\"slot\": \"file\"}");
  for (auto it = bound.begin(); it != bound.end(); ++it) {
    bool known = false;
    for (const auto& t : def.textures) known = known || t.name == it.key();
    if (!known)
      fail(origin, "textures." + it.key(),
           "shader '" + s.shader + "' has no such texture slot (slots: " + (slots.empty() ? "none" : slots) +
               ")");
  }
  const std::filesystem::path base =
      origin == "<text>" ? std::filesystem::path() : std::filesystem::path(origin).parent_path();
  for (const auto& t : def.textures) {
    if (!bound.contains(t.name))
      fail(origin, "textures." + t.name,
           "shader '" + s.shader + "' reads this texture slot; bind a file to it");
    const std::string rel = str(bound[t.name], origin, "textures." + t.name);
    const std::string file = (base / rel).lexically_normal().string();
    try {
      s.textures.push_back(std::make_shared<const texture::Texture>(
          texture::load_texture(t.name, file, t.channels, t.encoding)));
    } catch (const texture::TextureError& e) {
      fail(origin, "textures." + t.name, e.what());
    }
    s.texture_files.push_back({t.name, file});
  }
}

}  // namespace

std::vector<const texture::Texture*> Scene::texture_slots(const std::vector<std::string>& names) const {
  std::vector<const texture::Texture*> out;
  for (const auto& n : names) {
    const texture::Texture* found = texture::find(textures, n);
    if (!found) throw std::invalid_argument("scene " + name + ": no texture bound to slot '" + n + "'");
    out.push_back(found);
  }
  return out;
}

const shaders::ShaderDef& Scene::shader_def() const {
  return glsl ? *glsl : shaders::find_shader(shader);
}

shaders::Effects Scene::effects() const {
  shaders::Effects fx;
  fx.parallax = parallax;
  fx.lighting = lighting;
  fx.animated = animated();
  return fx;
}

Scene parse_scene(const std::string& text, const std::string& origin) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    fail(origin, "", std::string("malformed JSON: ") + e.what());
  }
  only_fields(j, origin, "",
              {"name", "shader", "geometry", "camera", "times", "parallax", "lighting", "light", "image",
               "footprint", "ground_truth", "background", "textures"});
  Scene s;
  if (!j.contains("shader")) fail(origin, "shader", "is required");
  s.shader = str(j["shader"], origin, "shader");
  const bool glsl_file = s.shader.size() > 5 && s.shader.compare(s.shader.size() - 5, 5, ".glsl") == 0;
  if (glsl_file) {
    // A GLSL pattern: absolute, or relative to the scene file's folder; traced now.
    const std::filesystem::path base =
        origin == "<text>" ? std::filesystem::path() : std::filesystem::path(origin).parent_path();
    const std::filesystem::path file = std::filesystem::path(s.shader).is_absolute()
                                           ? std::filesystem::path(s.shader)
                                           : (base / s.shader).lexically_normal();
    s.shader_file = file.string();
    if (!std::filesystem::exists(file))
      fail(origin, "shader", "GLSL file " + s.shader_file + " does not exist");
    try {
      s.glsl = glsl::load_shader(s.shader_file);
    } catch (const std::exception& e) {
      fail(origin, "shader", e.what());
    }
  } else {
    try {
      shaders::find_shader(s.shader);
    } catch (const std::invalid_argument& e) {
      fail(origin, "shader", std::string(e.what()) + ", or a .glsl file");
    }
  }
  s.name = j.contains("name") ? str(j["name"], origin, "name")
                              : (glsl_file ? std::filesystem::path(s.shader).stem().string() : s.shader);
  if (j.contains("geometry")) {
    const json& g = j["geometry"];
    only_fields(g, origin, "geometry", {"type", "uv_scale"});
    if (g.contains("type") && str(g["type"], origin, "geometry.type") != "plane")
      fail(origin, "geometry.type", "unknown geometry '" + g["type"].get<std::string>() + "' (known: plane)");
    if (g.contains("uv_scale")) {
      s.uv_scale = number(g["uv_scale"], origin, "geometry.uv_scale");
      if (!(s.uv_scale > 0)) fail(origin, "geometry.uv_scale", "must be > 0");
    }
  }
  if (j.contains("camera")) {
    const json& c = j["camera"];
    only_fields(c, origin, "camera", {"position", "fov_deg", "views"});
    if (c.contains("position")) s.camera_position = vec3(c["position"], origin, "camera.position");
    if (s.camera_position[2] <= 0)
      fail(origin, "camera.position", "the camera must be above the plane (z > 0)");
    if (c.contains("fov_deg")) {
      s.fov_deg = number(c["fov_deg"], origin, "camera.fov_deg");
      if (!(s.fov_deg > 1 && s.fov_deg < 170)) fail(origin, "camera.fov_deg", "must lie in (1, 170)");
    }
    if (c.contains("views")) {
      if (!c["views"].is_array() || c["views"].empty())
        fail(origin, "camera.views", "must be a non-empty array");
      s.views.clear();
      for (std::size_t i = 0; i < c["views"].size(); ++i) {
        const std::string f = "camera.views[" + std::to_string(i) + "]";
        const json& v = c["views"][i];
        only_fields(v, origin, f, {"yaw", "pitch", "roll"});
        View view;
        if (v.contains("yaw")) view.yaw = number(v["yaw"], origin, f + ".yaw");
        if (v.contains("pitch")) view.pitch = number(v["pitch"], origin, f + ".pitch");
        if (v.contains("roll")) view.roll = number(v["roll"], origin, f + ".roll");
        if (!(view.pitch < 0 && view.pitch >= -90))
          fail(origin, f + ".pitch", "must lie in [-90, 0) (looking down)");
        s.views.push_back(view);
      }
    }
  }
  if (j.contains("times")) {
    if (!j["times"].is_array() || j["times"].empty())
      fail(origin, "times", "must be a non-empty array of numbers");
    s.times.clear();
    for (const auto& t : j["times"]) s.times.push_back(number(t, origin, "times"));
  }
  if (j.contains("parallax")) {
    const std::string p = str(j["parallax"], origin, "parallax");
    if (p == "none")
      s.parallax = shaders::Parallax::None;
    else if (p == "bumps")
      s.parallax = shaders::Parallax::Bumps;
    else if (p == "ripples")
      s.parallax = shaders::Parallax::Ripples;
    else
      fail(origin, "parallax", "unknown value '" + p + "' (known: none, bumps, ripples)");
  }
  if (j.contains("lighting")) {
    const std::string l = str(j["lighting"], origin, "lighting");
    if (l == "none")
      s.lighting = shaders::Lighting::None;
    else if (l == "phong")
      s.lighting = shaders::Lighting::Phong;
    else
      fail(origin, "lighting", "unknown value '" + l + "' (known: none, phong)");
  }
  if (j.contains("light")) s.light_dir = vec3(j["light"], origin, "light");
  const double ln = std::sqrt(s.light_dir[0] * s.light_dir[0] + s.light_dir[1] * s.light_dir[1] +
                              s.light_dir[2] * s.light_dir[2]);
  if (!(ln > 0)) fail(origin, "light", "must be a nonzero direction");
  for (double& x : s.light_dir) x /= ln;
  if (j.contains("image")) {
    only_fields(j["image"], origin, "image", {"width", "height"});
    if (j["image"].contains("width"))
      s.width = positive_int(j["image"]["width"], origin, "image.width", 16384);
    if (j["image"].contains("height"))
      s.height = positive_int(j["image"]["height"], origin, "image.height", 16384);
  }
  if (j.contains("footprint")) {
    only_fields(j["footprint"], origin, "footprint", {"sigma_px", "bound"});
    if (j["footprint"].contains("bound")) {
      const std::string b = str(j["footprint"]["bound"], origin, "footprint.bound");
      if (b == "dorn")
        s.footprint_bound = FootprintBound::Dorn;
      else if (b == "marginal")
        s.footprint_bound = FootprintBound::Marginal;
      else
        fail(origin, "footprint.bound", "unknown value '" + b + "' (known: dorn, marginal)");
    }
    if (j["footprint"].contains("sigma_px")) {
      s.sigma_px = number(j["footprint"]["sigma_px"], origin, "footprint.sigma_px");
      if (!(s.sigma_px > 0)) fail(origin, "footprint.sigma_px", "must be > 0");
    }
  }
  if (j.contains("ground_truth")) {
    only_fields(j["ground_truth"], origin, "ground_truth", {"samples"});
    if (j["ground_truth"].contains("samples"))
      s.truth_samples = positive_int(j["ground_truth"]["samples"], origin, "ground_truth.samples", 1 << 20);
  }
  if (j.contains("background")) s.background = vec3(j["background"], origin, "background");
  load_textures(s, j, origin);
  return s;
}

Scene load_scene(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument("scene " + path + ": cannot open the file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_scene(ss.str(), path);
}

std::string Scene::canonical_json() const {
  json j;
  j["name"] = name;
  j["shader"] = shader;
  j["geometry"] = {{"type", "plane"}, {"uv_scale", uv_scale}};
  json vs = json::array();
  for (const auto& v : views) vs.push_back({{"yaw", v.yaw}, {"pitch", v.pitch}, {"roll", v.roll}});
  j["camera"] = {{"position", camera_position}, {"fov_deg", fov_deg}, {"views", vs}};
  j["times"] = times;
  j["parallax"] = parallax_name(parallax);
  j["lighting"] = lighting == shaders::Lighting::Phong ? "phong" : "none";
  j["light"] = light_dir;
  j["image"] = {{"width", width}, {"height", height}};
  j["footprint"] = {{"sigma_px", sigma_px},
                    {"bound", footprint_bound == FootprintBound::Dorn ? "dorn" : "marginal"}};
  j["ground_truth"] = {{"samples", truth_samples}};
  j["background"] = background;
  if (!textures.empty()) {
    json t = json::object();
    for (std::size_t i = 0; i < textures.size(); ++i) {
      char hex[17];
      std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(textures[i]->content_hash));
      // The file's name and content, not its path: the hash must not depend on the working directory.
      t[texture_files[i].slot] = {{"file", std::filesystem::path(texture_files[i].file).filename().string()},
                                  {"content", hex}};
    }
    j["textures"] = t;
  }
  return j.dump();
}

std::uint64_t Scene::hash() const {
  return ir::fnv1a(canonical_json());
}

std::vector<Scene> suite_scenes() {
  std::vector<Scene> out;
  for (const auto& shader : shaders::base_shader_names())
    for (auto p : {shaders::Parallax::None, shaders::Parallax::Bumps, shaders::Parallax::Ripples}) {
      Scene s;
      s.shader = shader;
      s.parallax = p;
      s.name = shader + "_" + parallax_name(p);
      s.lighting = p == shaders::Parallax::None ? shaders::Lighting::None : shaders::Lighting::Phong;
      s.views = {View{0, -25, 0}, View{35, -40, 0}};
      const bool moves = shaders::find_shader(shader).uses_time || p == shaders::Parallax::Ripples;
      s.times = moves ? std::vector<double>{0.0, 0.7} : std::vector<double>{0.0};
      s.width = s.height = 192;
      out.push_back(s);
    }
  return out;
}

}  // namespace bl::scene
