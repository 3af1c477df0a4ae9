// Normal-map scene files (JSON): a normal-mapped plane z = 0 seen by one camera, lit by one
// directional light, shaded with Blinn-Phong or GGX (brdf.hpp). Fields (all optional but
// "texture" and "material"):
//   name, texture (path, relative to the scene file), uv_scale (u = uv_scale x; the map repeats
//   every unit of u), camera {position, fov_deg, yaw, pitch, roll}, image {width, height},
//   footprint {sigma_px, bound dorn|marginal}, light {direction, color}, material {model
//   blinn_phong|ggx, albedo, ambient, ks, exponent (blinn_phong), alpha, f0 (ggx)},
//   multi_lobe {longitude, latitude, threshold (radians of sigma_theta)}, msaa [n...],
//   ground_truth {samples}, background [r, g, b].
// An unknown field, a bad value or a wrong type is rejected naming the file and the field.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "camera/camera.hpp"
#include "camera/plane_hit.hpp"
#include "normalmap/brdf.hpp"
#include "normalmap/normal_data.hpp"

namespace bl::normalmap {

struct NmScene {
  std::string name = "normalmap";
  std::string origin;        // the scene file ("<text>" when parsed from a string)
  std::string texture;       // resolved path
  std::string texture_text;  // as written in the file
  double uv_scale = 1;
  camera::Camera camera;
  double sigma_px = 0.5;
  camera::FootprintBound bound = camera::FootprintBound::kDornAxisAligned;
  Light light;
  Material material;
  LobeGrid grid;
  double lobe_threshold = 0.1;
  std::vector<int> msaa{2, 4, 8, 16, 32};
  int truth_samples = 1024;
  std::array<double, 3> background{0, 0, 0};

  camera::FootprintOptions footprint() const;
  std::string canonical_json() const;  // every field, fixed order (cache keys, reports)
  std::uint64_t hash() const;
};

// Throws std::invalid_argument naming `origin` and the field.
NmScene parse_nm_scene(const std::string& json_text, const std::string& origin = "<text>",
                       const std::string& base_dir = ".");
NmScene load_nm_scene(const std::string& path);

}  // namespace bl::normalmap
