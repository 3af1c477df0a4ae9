// The renderer: a scene frame (view, time) rendered plain (1 sample at the pixel centre), with MSAA
// (n Gaussian-jittered samples), smoothed by a compiled program (1 evaluation per pixel, through the
// batch evaluator), or as ground truth (many jittered samples, cached on disk as EXR).
#pragma once

#include <cstdint>
#include <string>

#include "camera/plane_batch.hpp"
#include "compiler/evaluator.hpp"
#include "compiler/lir.hpp"
#include "image/image.hpp"
#include "scene/scene.hpp"

namespace bl::render {

struct Frame {
  int view = 0;
  double time = 0;
};

// samples = 0: one sample at each pixel centre (plain). Otherwise `samples` samples per pixel,
// offsets ~ N(0, sigma_px^2) per axis (the same kernel the smoothing targets), counter-based
// (render/jitter.hpp: a hash of seed, frame, pixel and sample), so renders are reproducible,
// independent of the thread count and the same with every standard library.
Image render_native(const scene::Scene& s, const Frame& f, int samples, std::uint64_t seed = 1,
                    const std::string& progress_label = "");

// One evaluation of `program` per pixel at the pixel centre, inputs from the camera footprint.
// The program's inputs are matched by name (u, v, time, view_*, light_*); an unknown input name
// throws naming it.
Image render_smoothed(const scene::Scene& s, const Frame& f, const compiler::Program& program);

// Ground truth with scene.truth_samples samples per pixel, cached as
// <cache_dir>/truth_cb_<scene hash>_<shader graph hash>_v<view>_t<time>.exr (the shader's traced
// graph is part of the key, so editing a shader invalidates its cache). An empty cache_dir disables
// the cache.
Image render_truth(const scene::Scene& s, const Frame& f, const std::string& cache_dir);
std::string truth_cache_path(const scene::Scene& s, const Frame& f, const std::string& cache_dir);

// Value of a per-frame uniform input (time, light_x/y/z); throws naming an unknown input.
double uniform_input(const scene::Scene& s, const Frame& f, const std::string& name);

// Storage bind_inputs points into for inputs the plane batch does not hold (zero sds and
// gradients, per-frame uniforms); it must outlive the Batch.
struct InputStorage {
  std::vector<float> zeros;
  std::vector<std::vector<float>> constants;
};

// The program's inputs for every pixel of `b`, matched by name: u and v (mean, footprint sd, screen
// gradient), view_x/y/z (mean), time and light_* (the frame's uniforms). Throws naming an unknown
// input. The one mapping the renderer and the tuner's pixel sample share.
compiler::Batch bind_inputs(const compiler::Program& p, const camera::PlaneBatch& b, const scene::Scene& s,
                            const Frame& f, InputStorage& storage);

// All frames of a scene: every view, and every time (one when static).
std::vector<Frame> frames(const scene::Scene& s);

}  // namespace bl::render
