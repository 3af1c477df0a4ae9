// The search's error measure: RMS in display space against the cached ground truth over every frame
// of a scene, on a fixed random subsample of pixels (evaluating only those pixels), or on all
// pixels. The per-pixel program inputs are the camera footprint's, mapped by input name exactly as
// render::render_smoothed maps them (a test checks that the all-pixel error equals rms_display of
// render_smoothed).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "camera/plane_batch.hpp"
#include "compiler/lir.hpp"
#include "image/pixel_check.hpp"
#include "scene/scene.hpp"

namespace bl::tuner {

class PixelSample {
 public:
  // `pixels` in total over all frames (split evenly), <= 0 or more than the image: every pixel.
  // Ground truth comes from render_truth with `cache_dir` (rendered and cached when missing).
  PixelSample(const scene::Scene& s, const std::string& cache_dir, int pixels, std::uint64_t seed);
  PixelSample(const scene::Scene& s, const ir::Graph& g, const std::string& cache_dir, int pixels,
              std::uint64_t seed);  // the same, with the scene's traced graph (not traced again)

  struct Score {
    double rms = 0;      // display_error (image/display.hpp): unclamped, a NaN/inf channel counts 1
    PixelCounts counts;  // sampled pixels with a NaN/inf channel, or one outside range()
  };
  // p over the sampled pixels of all frames; thread-safe.
  Score score(const compiler::Program& p) const;
  // The search's objective: score(p).rms, or +infinity when any sampled pixel has a NaN or infinite
  // channel (such a schedule is infeasible, however few pixels it breaks).
  double error(const compiler::Program& p) const;
  int count() const { return total_; }
  // Per sampled pixel hit by the camera (frame order, as outputs()): its squared display errors summed
  // over the three channels, as score() sums them (a NaN/inf channel counts 1). score(p).rms =
  // sqrt((miss_sq() + their sum) / (3 count())).
  std::vector<double> pixel_sq(const compiler::Program& p) const;
  double miss_sq() const;  // the sampled pixels the camera misses (sky), summed the same way
  // The same pixels' footprints: the larger of sigma_u and sigma_v, the surface coordinates' sds
  // (what a footprint-LOD program switches on; tuner/lod.hpp).
  std::vector<float> footprints() const;
  // The hit pixels whose footprint is below `limit` (below) or at or above it (!below), as a sample
  // of their own: count() is their number, no missed pixels. For pricing a program on part of the
  // image (SceneTuner::cost_model_over).
  PixelSample subset(float limit, bool below) const;
  // p's outputs (any number) over the sampled hit pixels of all frames, concatenated in frame
  // order: out[k][i]. For inspecting values (magnitude_profile), not errors.
  std::vector<std::vector<float>> outputs(const compiler::Program& p) const;
  // render::valid_range of the scene (the declared range of the shader's outputs, else [0, 1]
  // widened to the ground truth's and the plain render's values).
  const ValueRange& range() const { return range_; }

 private:
  PixelSample() = default;
  struct FrameData {
    double time = 0;
    int n = 0;                 // sampled pixels hit by the camera
    camera::PlaneBatch hits;   // those pixels' traces, in sample order
    std::vector<float> truth;  // display space, 3 per hit pixel
    double miss_sq = 0;        // squared error summed over missed sampled pixels
  };
  scene::Scene scene_;
  std::vector<FrameData> frames_;
  int total_ = 0;  // sampled pixels over all frames (hit or not)
  ValueRange range_;
  // Per hit pixel (frame order) the summed squared error of p's shown colour; counts its checks.
  std::vector<double> hit_sq(const compiler::Program& p, PixelCounts* counts) const;
};

}  // namespace bl::tuner
