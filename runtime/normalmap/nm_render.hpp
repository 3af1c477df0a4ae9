// Whole-frame renders of a normal-map scene, on all cores (render::parallel_rows):
//   render_technique   one shading per pixel at the centre, footprint from runtime/camera;
//   render_sampled     n Gaussian-jittered direct samples per pixel (sd sigma_px), seeded per pixel
//                      (reproducible, thread-count independent): MSAA n, and the ground truth;
//   render_truth       render_sampled with the scene's truth_samples, cached as EXR under cache_dir,
//                      keyed by the scene's canonical JSON, the texture's content and kShadingVersion.
#pragma once

#include <cstdint>
#include <string>

#include "image/image.hpp"
#include "normalmap/nm_scene.hpp"
#include "normalmap/normal_data.hpp"
#include "normalmap/techniques.hpp"

namespace bl::normalmap {

// Bump when brdf.hpp or the direct path changes (invalidates cached ground truth).
inline constexpr const char* kShadingVersion = "nm2";

// multi_fraction, when given, receives the share of hit pixels that took the multi-lobe path.
Image render_technique(const NmScene& s, const NormalMapData& d, Technique t,
                       double* multi_fraction = nullptr);
// samples = 0: direct shading at each pixel centre.
Image render_sampled(const NmScene& s, const NormalMapData& d, int samples, std::uint64_t seed = 1,
                     const std::string& progress_label = "");
std::string truth_cache_path(const NmScene& s, const NormalMapData& d, const std::string& cache_dir);
Image render_truth(const NmScene& s, const NormalMapData& d, const std::string& cache_dir);

}  // namespace bl::normalmap
