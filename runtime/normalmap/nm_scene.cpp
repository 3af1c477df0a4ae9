#include "normalmap/nm_scene.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include "ir/hash.hpp"

namespace bl::normalmap {

using json = nlohmann::json;

namespace {

struct Ctx {
  std::string origin;
  [[noreturn]] void fail(const std::string& field, const std::string& why) const {
    throw std::invalid_argument("normal-map scene " + origin +
                                (field.empty() ? "" : ", field '" + field + "'") + ": " + why);
  }
  void only(const json& j, const std::string& where, const std::set<std::string>& allowed) const {
    if (!j.is_object()) fail(where, "must be an object, got " + j.dump());
    for (auto it = j.begin(); it != j.end(); ++it)
      if (!allowed.count(it.key())) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        fail(where.empty() ? it.key() : where + "." + it.key(), "unknown field (allowed: " + list + ")");
      }
  }
  double num(const json& j, const std::string& field) const {
    if (!j.is_number()) fail(field, "must be a number, got " + j.dump());
    const double v = j.get<double>();
    if (!std::isfinite(v)) fail(field, "must be finite");
    return v;
  }
  double num_in(const json& j, const std::string& field, double lo, double hi) const {
    const double v = num(j, field);
    if (v < lo || v > hi) fail(field, "must be in [" + fmt(lo) + ", " + fmt(hi) + "], got " + j.dump());
    return v;
  }
  int integer(const json& j, const std::string& field, int lo, int hi) const {
    if (!j.is_number_integer() || j.get<long long>() < lo || j.get<long long>() > hi)
      fail(field,
           "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + j.dump());
    return j.get<int>();
  }
  std::array<double, 3> vec3(const json& j, const std::string& field) const {
    if (!j.is_array() || j.size() != 3) fail(field, "must be an array of 3 numbers, got " + j.dump());
    return {num(j[0], field), num(j[1], field), num(j[2], field)};
  }
  std::string str(const json& j, const std::string& field) const {
    if (!j.is_string()) fail(field, "must be a string, got " + j.dump());
    return j.get<std::string>();
  }
  static std::string fmt(double v) {
    std::ostringstream o;
    o << v;
    return o.str();
  }
};

}  // namespace

camera::FootprintOptions NmScene::footprint() const {
  camera::FootprintOptions o;
  o.texture_scale = uv_scale;
  o.pixel_sigma = sigma_px;
  o.bound = bound;
  return o;
}

std::string NmScene::canonical_json() const {
  json j;
  j["name"] = name;
  j["texture"] = texture_text;
  j["uv_scale"] = uv_scale;
  j["camera"] = {{"position", {camera.position.x, camera.position.y, camera.position.z}},
                 {"fov_deg", camera.vfov_deg},
                 {"yaw", camera.yaw_deg},
                 {"pitch", camera.pitch_deg},
                 {"roll", camera.roll_deg}};
  j["image"] = {{"width", camera.width}, {"height", camera.height}};
  j["footprint"] = {{"sigma_px", sigma_px},
                    {"bound", bound == camera::FootprintBound::kDornAxisAligned ? "dorn" : "marginal"}};
  j["light"] = {{"direction", {light.dir.x, light.dir.y, light.dir.z}}, {"color", light.color}};
  json m = {{"albedo", material.albedo}, {"ambient", material.ambient}};
  if (material.model == Model::BlinnPhong) {
    m["model"] = "blinn_phong";
    m["ks"] = material.ks;
    m["exponent"] = material.exponent;
  } else {
    m["model"] = "ggx";
    m["alpha"] = material.alpha;
    m["f0"] = material.f0;
  }
  j["material"] = m;
  j["multi_lobe"] = {
      {"longitude", grid.longitude}, {"latitude", grid.latitude}, {"threshold", lobe_threshold}};
  j["msaa"] = msaa;
  j["ground_truth"] = {{"samples", truth_samples}};
  j["background"] = background;
  return j.dump();
}

std::uint64_t NmScene::hash() const {
  return ir::fnv1a(canonical_json());
}

NmScene parse_nm_scene(const std::string& text, const std::string& origin, const std::string& base_dir) {
  const Ctx cx{origin};
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    cx.fail("", std::string("malformed JSON: ") + e.what());
  }
  cx.only(j, "",
          {"name", "texture", "uv_scale", "camera", "image", "footprint", "light", "material", "multi_lobe",
           "msaa", "ground_truth", "background"});
  NmScene s;
  s.origin = origin;
  s.camera.position = {0, 0, 1};
  s.camera.pitch_deg = -20;
  if (j.contains("name")) s.name = cx.str(j["name"], "name");
  if (!j.contains("texture")) cx.fail("texture", "missing (the normal map's file)");
  s.texture_text = cx.str(j["texture"], "texture");
  if (s.texture_text.empty()) cx.fail("texture", "must name a file");
  const std::filesystem::path tp(s.texture_text);
  s.texture =
      tp.is_absolute() ? tp.string() : (std::filesystem::path(base_dir) / tp).lexically_normal().string();
  if (j.contains("uv_scale")) s.uv_scale = cx.num_in(j["uv_scale"], "uv_scale", 1e-6, 1e6);
  if (j.contains("camera")) {
    const json& c = j["camera"];
    cx.only(c, "camera", {"position", "fov_deg", "yaw", "pitch", "roll"});
    if (c.contains("position")) {
      const auto p = cx.vec3(c["position"], "camera.position");
      if (p[2] <= 0) cx.fail("camera.position", "the camera must be above the plane (z > 0)");
      s.camera.position = {p[0], p[1], p[2]};
    }
    if (c.contains("fov_deg")) s.camera.vfov_deg = cx.num_in(c["fov_deg"], "camera.fov_deg", 1, 170);
    if (c.contains("yaw")) s.camera.yaw_deg = cx.num(c["yaw"], "camera.yaw");
    if (c.contains("pitch")) s.camera.pitch_deg = cx.num_in(c["pitch"], "camera.pitch", -90, 90);
    if (c.contains("roll")) s.camera.roll_deg = cx.num(c["roll"], "camera.roll");
  }
  if (j.contains("image")) {
    cx.only(j["image"], "image", {"width", "height"});
    if (j["image"].contains("width"))
      s.camera.width = cx.integer(j["image"]["width"], "image.width", 1, 8192);
    if (j["image"].contains("height"))
      s.camera.height = cx.integer(j["image"]["height"], "image.height", 1, 8192);
  }
  if (j.contains("footprint")) {
    cx.only(j["footprint"], "footprint", {"sigma_px", "bound"});
    if (j["footprint"].contains("sigma_px"))
      s.sigma_px = cx.num_in(j["footprint"]["sigma_px"], "footprint.sigma_px", 1e-3, 100);
    if (j["footprint"].contains("bound")) {
      const std::string b = cx.str(j["footprint"]["bound"], "footprint.bound");
      if (b == "dorn")
        s.bound = camera::FootprintBound::kDornAxisAligned;
      else if (b == "marginal")
        s.bound = camera::FootprintBound::kGaussianMarginal;
      else
        cx.fail("footprint.bound", "unknown bound '" + b + "' (dorn, marginal)");
    }
  }
  if (j.contains("light")) {
    cx.only(j["light"], "light", {"direction", "color"});
    if (j["light"].contains("direction")) {
      const auto d = cx.vec3(j["light"]["direction"], "light.direction");
      const V3 v{d[0], d[1], d[2]};
      if (length(v) == 0 || d[2] <= 0) cx.fail("light.direction", "must point up from the plane (z > 0)");
      s.light.dir = normalize(v);
    }
    if (j["light"].contains("color")) s.light.color = cx.vec3(j["light"]["color"], "light.color");
  }
  if (!j.contains("material")) cx.fail("material", "missing (model blinn_phong or ggx)");
  {
    const json& m = j["material"];
    cx.only(m, "material", {"model", "albedo", "ambient", "ks", "exponent", "alpha", "f0"});
    if (!m.contains("model")) cx.fail("material.model", "missing (blinn_phong or ggx)");
    const std::string model = cx.str(m["model"], "material.model");
    if (model == "blinn_phong")
      s.material.model = Model::BlinnPhong;
    else if (model == "ggx")
      s.material.model = Model::GGX;
    else
      cx.fail("material.model", "unknown model '" + model + "' (blinn_phong, ggx)");
    const bool bp = s.material.model == Model::BlinnPhong;
    for (const char* k : {"ks", "exponent"})
      if (!bp && m.contains(k)) cx.fail(std::string("material.") + k, "only for model blinn_phong");
    for (const char* k : {"alpha", "f0"})
      if (bp && m.contains(k)) cx.fail(std::string("material.") + k, "only for model ggx");
    if (m.contains("albedo")) s.material.albedo = cx.vec3(m["albedo"], "material.albedo");
    if (m.contains("ambient")) s.material.ambient = cx.num_in(m["ambient"], "material.ambient", 0, 10);
    if (m.contains("ks")) s.material.ks = cx.num_in(m["ks"], "material.ks", 0, 100);
    if (m.contains("exponent")) s.material.exponent = cx.integer(m["exponent"], "material.exponent", 1, 4096);
    if (m.contains("alpha")) s.material.alpha = cx.num_in(m["alpha"], "material.alpha", 1e-3, 1);
    if (m.contains("f0")) s.material.f0 = cx.num_in(m["f0"], "material.f0", 0, 1);
  }
  if (j.contains("multi_lobe")) {
    const json& m = j["multi_lobe"];
    cx.only(m, "multi_lobe", {"longitude", "latitude", "threshold"});
    if (m.contains("longitude")) s.grid.longitude = cx.integer(m["longitude"], "multi_lobe.longitude", 1, 16);
    if (m.contains("latitude")) s.grid.latitude = cx.integer(m["latitude"], "multi_lobe.latitude", 1, 16);
    if (m.contains("threshold")) s.lobe_threshold = cx.num_in(m["threshold"], "multi_lobe.threshold", 0, 2);
  }
  if (j.contains("msaa")) {
    if (!j["msaa"].is_array()) cx.fail("msaa", "must be an array of sample counts, got " + j["msaa"].dump());
    s.msaa.clear();
    for (const json& n : j["msaa"]) s.msaa.push_back(cx.integer(n, "msaa", 1, 4096));
  }
  if (j.contains("ground_truth")) {
    cx.only(j["ground_truth"], "ground_truth", {"samples"});
    if (j["ground_truth"].contains("samples"))
      s.truth_samples = cx.integer(j["ground_truth"]["samples"], "ground_truth.samples", 1, 1 << 20);
  }
  if (j.contains("background")) s.background = cx.vec3(j["background"], "background");
  try {
    camera::validate(s.camera);
  } catch (const std::invalid_argument& e) {
    cx.fail("camera", e.what());
  }
  return s;
}

NmScene load_nm_scene(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument("normal-map scene " + path + ": cannot open the file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_nm_scene(ss.str(), path, std::filesystem::path(path).parent_path().string());
}

}  // namespace bl::normalmap
