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
};

SceneSummary summarize(const SceneTimes& s);
std::string report_markdown(const std::vector<SceneTimes>& scenes, const std::string& renderer, int tile);

}  // namespace bl::gpu_timing
