// The GPU timing report: per scene, what MSAA-n and the tuned front cost on a GPU's driver, and the
// speed-up at MSAA-16's error, next to the compiled-C++ speed-up bltune measured on the CPU.
// Pure data -> markdown (no GL), so it is tested without a GPU.
#pragma once

#include <string>
#include <vector>

namespace bl::gpu_timing {

struct ProgramTime {
  // kind: "baseline" (plain, msaaN, ssN, uniform rules), "front", "lod" (bltune's footprint-LOD pair of
  // two front programs chosen per fragment by its footprint, tuner/lod.hpp; at most one per scene) or
  // "adaptive" (its footprint-adaptive supersampler, tuner/adaptive_supersampling.hpp; at most one)
  std::string label, kind;
  int msaa = 0;             // samples per fragment (0: one evaluation)
  double error = 0;         // RMS vs truth as bltune measured it (CPU); may be +inf (infeasible)
  double compiled_ns = -1;  // bltune's compiled-C++ ns per pixel (< 0: not measured)
  double gpu_ms = -1;       // ms per frame of the tiled target (< 0: not timed)
  double compile_ms = -1;   // driver compile + link, ms
  std::string failure;      // compile or draw failure (then gpu_ms < 0)
  // Measured on the GPU (blgpu_time's merge): RMS against the GPU truth over every frame, as bltune
  // measures on the CPU (< 0: not measured), and the pixels no metric may hide (image/pixel_check).
  double gpu_error = -1;
  long nonfinite = 0, out_of_range = 0;
};

struct SceneTimes {
  std::string scene;
  int width = 0, height = 0;  // the tiled target
  std::vector<ProgramTime> programs;
};

// What the report concludes for one scene.
struct SceneSummary {
  double plain_ns = -1, msaa16_ns = -1, gaussian_ns = -1;  // GPU ns per pixel
  double msaa16_error = -1;
  std::string gpu_label;  // fastest front point on the GPU with error <= MSAA-16's ("" = none)
  double gpu_ns = -1, gpu_speedup = -1;
  std::string cpu_label;  // the same by bltune's compiled-C++ time
  double cpu_speedup = -1;
  // The footprint-LOD pair (kind "lod") when it reaches MSAA-16's error: its GPU ns per pixel and
  // MSAA-16's time over its time on each clock (< 0: no pair, not timed, or not at that error).
  double lod_ns = -1, lod_gpu_speedup = -1, lod_cpu_speedup = -1;
  // The footprint-adaptive supersampler (kind "adaptive") when it reaches MSAA-16's error: its GPU ns
  // per pixel and its time over ours (the faster of the fastest point and the pair there) on each
  // clock (< 0: none, not timed, or ours does not reach that error).
  double adaptive_ns = -1, adaptive_gpu_speedup = -1, adaptive_cpu_speedup = -1;
  double max_compile_ms = -1;
  int failures = 0;
  // By the errors measured on the GPU (< 0 / "": not measured). gpu_point_error: the GPU error of
  // gpu_label's point (chosen by bltune's errors). by_gpu_*: the fastest front point or LOD pair
  // whose GPU error is at most MSAA-16's GPU error, and MSAA-16's GPU time over its.
  double plain_error = -1, plain_gpu_error = -1, msaa16_gpu_error = -1;
  double gpu_point_cpu_error = -1, gpu_point_error = -1;
  std::string by_gpu_label;
  double by_gpu_ns = -1, by_gpu_speedup = -1;
  // The largest GPU error / bltune error over the scene's programs (not the truth), and which.
  double worst_error_ratio = -1;
  std::string worst_error_label;
  int nonfinite_programs = 0, out_of_range_programs = 0;  // programs with such pixels on the GPU
};

SceneSummary summarize(const SceneTimes& s);
// The section on errors measured on the GPU ("" where no program has one); report_markdown ends with it.
std::string errors_markdown(const std::vector<SceneTimes>& scenes);
std::string report_markdown(const std::vector<SceneTimes>& scenes, const std::string& renderer, int tile);

// Two tunings of the same scenes drawn on one GPU (blgpu_time --compare: the suite tuned with the CPU
// model against the same tuned with a fitted GPU model, tuner/gpu_fit.hpp): per scene both fastest
// programs (front point or LOD pair) at MSAA-16's error, their ratio, and each against its
// footprint-adaptive supersampler (kind "adaptive") at that error; one table by the GPU's own errors,
// one by bltune's. Scenes in only one of them are left out.
std::string comparison_markdown(const std::vector<SceneTimes>& a, const std::vector<SceneTimes>& b,
                                const std::string& name_a, const std::string& name_b);

}  // namespace bl::gpu_timing
