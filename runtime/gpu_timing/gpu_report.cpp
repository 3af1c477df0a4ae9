#include "gpu_timing/gpu_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace bl::gpu_timing {

namespace {

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string err(double v) {
  return v >= 0 ? fmt("%.4f", v) : std::string("-");
}

}  // namespace

std::string errors_markdown(const std::vector<SceneTimes>& scenes) {
  bool any = false;
  for (const SceneTimes& s : scenes)
    for (const ProgramTime& p : s.programs) any = any || p.gpu_error >= 0;
  if (!any) return "";
  std::ostringstream os;
  os << "\n## Errors on this GPU\n\nEvery program drawn at the scene's size at each frame and measured "
        "against the GPU truth (the plain program at the scene's truth sample count in one fragment) in "
        "display space, as bltune measures against the CPU truth. CPU = bltune's error; \"by GPU errors\": "
        "the fastest front point or LOD pair whose GPU error is at most MSAA-16's GPU error.\n\n"
        "| scene | plain error CPU / GPU | MSAA-16 error CPU / GPU | fastest point at MSAA-16's error (CPU "
        "errors): error CPU / GPU | by GPU errors: fastest | its ns/px | its GPU speed-up | largest GPU / "
        "CPU "
        "error | programs with NaN / out-of-range pixels |\n|---|---|---|---|---|---|---|---|---|\n";
  int reached = 0, ten = 0, nonfinite = 0;
  std::vector<double> ups;
  double worst = -1;
  std::string worst_at;
  for (const SceneTimes& s : scenes) {
    const SceneSummary r = summarize(s);
    os << "| " << s.scene << " | " << err(r.plain_error) << " / " << err(r.plain_gpu_error) << " | "
       << err(r.msaa16_error) << " / " << err(r.msaa16_gpu_error) << " | "
       << (r.gpu_label.empty()
               ? std::string("-")
               : r.gpu_label + ": " + err(r.gpu_point_cpu_error) + " / " + err(r.gpu_point_error))
       << " | " << (r.by_gpu_label.empty() ? "not reached" : r.by_gpu_label) << " | "
       << (r.by_gpu_ns >= 0 ? fmt("%.3f", r.by_gpu_ns) : "-") << " | "
       << (r.by_gpu_speedup > 0 ? fmt("%.1fx", r.by_gpu_speedup) : "-") << " | "
       << (r.worst_error_ratio >= 0 ? fmt("%.3f", r.worst_error_ratio) + " (" + r.worst_error_label + ")"
                                    : "-")
       << " | " << r.nonfinite_programs << " / " << r.out_of_range_programs << " |\n";
    nonfinite += r.nonfinite_programs;
    if (r.by_gpu_speedup > 0) {
      ++reached;
      ten += r.by_gpu_speedup >= 10;
      ups.push_back(r.by_gpu_speedup);
    }
    if (r.worst_error_ratio > worst)
      worst = r.worst_error_ratio, worst_at = s.scene + "/" + r.worst_error_label;
  }
  os << "\nBy the errors measured on this GPU: MSAA-16's error reached on " << reached << " of "
     << scenes.size() << " scenes, at >= 10x less GPU time on " << ten << "; median speed-up "
     << (ups.empty() ? "-" : fmt("%.1fx", median(ups))) << "; " << nonfinite
     << " program(s) with NaN or infinite pixels; the largest GPU / CPU error ratio "
     << (worst >= 0 ? fmt("%.3f", worst) + " (" + worst_at + ")" : std::string("-")) << ".\n";
  return os.str();
}

SceneSummary summarize(const SceneTimes& s) {
  SceneSummary r;
  const double px = static_cast<double>(s.width) * s.height;
  auto ns = [&](const ProgramTime& p) { return p.gpu_ms * 1e6 / px; };
  const ProgramTime* msaa16 = nullptr;
  for (const ProgramTime& p : s.programs) {
    if (!p.failure.empty()) ++r.failures;
    r.max_compile_ms = std::max(r.max_compile_ms, p.compile_ms);
    if (p.kind == "truth") continue;
    r.nonfinite_programs += p.nonfinite > 0;
    r.out_of_range_programs += p.out_of_range > 0;
    if (p.gpu_error >= 0 && p.error > 0 && std::isfinite(p.error) &&
        p.gpu_error / p.error > r.worst_error_ratio) {
      r.worst_error_ratio = p.gpu_error / p.error;
      r.worst_error_label = p.label;
    }
    if (p.kind != "baseline") continue;
    if (p.label == "plain") r.plain_error = p.error, r.plain_gpu_error = p.gpu_error;
    if (p.label == "plain" && p.gpu_ms >= 0) r.plain_ns = ns(p);
    if (p.label == "gaussian" && p.gpu_ms >= 0) r.gaussian_ns = ns(p);
    if (p.msaa == 16) msaa16 = &p;
  }
  if (msaa16 == nullptr) return r;
  r.msaa16_error = msaa16->error;
  r.msaa16_gpu_error = msaa16->gpu_error;
  if (msaa16->gpu_ms >= 0) r.msaa16_ns = ns(*msaa16);
  // By the GPU's own errors: the fastest front point or pair at MSAA-16's GPU error.
  if (msaa16->gpu_error >= 0 && msaa16->gpu_ms >= 0) {
    const ProgramTime* best = nullptr;
    for (const ProgramTime& p : s.programs)
      if ((p.kind == "front" || p.kind == "lod") && p.gpu_ms > 0 && p.gpu_error >= 0 &&
          p.gpu_error <= msaa16->gpu_error && (best == nullptr || p.gpu_ms < best->gpu_ms))
        best = &p;
    if (best != nullptr) {
      r.by_gpu_label = best->label;
      r.by_gpu_ns = ns(*best);
      r.by_gpu_speedup = msaa16->gpu_ms / best->gpu_ms;
    }
  }
  // The fastest front point that reaches MSAA-16's error, by each clock.
  const ProgramTime *gpu = nullptr, *cpu = nullptr;
  for (const ProgramTime& p : s.programs) {
    if (p.kind != "front" || !(p.error <= msaa16->error)) continue;
    if (p.gpu_ms >= 0 && (gpu == nullptr || p.gpu_ms < gpu->gpu_ms)) gpu = &p;
    if (p.compiled_ns >= 0 && (cpu == nullptr || p.compiled_ns < cpu->compiled_ns)) cpu = &p;
  }
  if (gpu != nullptr && msaa16->gpu_ms >= 0) {
    r.gpu_label = gpu->label;
    r.gpu_ns = ns(*gpu);
    r.gpu_speedup = msaa16->gpu_ms / gpu->gpu_ms;
    r.gpu_point_cpu_error = gpu->error;
    r.gpu_point_error = gpu->gpu_error;
  }
  if (cpu != nullptr && msaa16->compiled_ns >= 0) {
    r.cpu_label = cpu->label;
    r.cpu_speedup = msaa16->compiled_ns / cpu->compiled_ns;
  }
  // Ours on each clock: the fastest point at MSAA-16's error, or the pair where it is faster.
  double ours_gpu = gpu != nullptr ? gpu->gpu_ms : -1, ours_cpu = cpu != nullptr ? cpu->compiled_ns : -1;
  for (const ProgramTime& p : s.programs) {
    if (p.kind != "lod" || !(p.error <= msaa16->error)) continue;
    if (p.gpu_ms > 0 && msaa16->gpu_ms >= 0) {
      r.lod_ns = ns(p);
      r.lod_gpu_speedup = msaa16->gpu_ms / p.gpu_ms;
    }
    if (p.compiled_ns > 0 && msaa16->compiled_ns >= 0)
      r.lod_cpu_speedup = msaa16->compiled_ns / p.compiled_ns;
    if (p.gpu_ms > 0 && (ours_gpu < 0 || p.gpu_ms < ours_gpu)) ours_gpu = p.gpu_ms;
    if (p.compiled_ns > 0 && (ours_cpu < 0 || p.compiled_ns < ours_cpu)) ours_cpu = p.compiled_ns;
  }
  for (const ProgramTime& p : s.programs) {
    if (p.kind != "adaptive" || !(p.error <= msaa16->error)) continue;
    if (p.gpu_ms > 0) r.adaptive_ns = ns(p);
    if (p.gpu_ms > 0 && ours_gpu > 0) r.adaptive_gpu_speedup = p.gpu_ms / ours_gpu;
    if (p.compiled_ns > 0 && ours_cpu > 0) r.adaptive_cpu_speedup = p.compiled_ns / ours_cpu;
  }
  return r;
}

namespace {

// The adaptive supersampler's GPU ns per pixel when its GPU error reaches MSAA-16's GPU error (-1: not).
double adaptive_at_msaa16(const SceneTimes& s, const SceneSummary& r) {
  const double px = static_cast<double>(s.width) * s.height;
  for (const ProgramTime& p : s.programs)
    if (p.kind == "adaptive" && p.gpu_ms > 0 && p.gpu_error >= 0 && r.msaa16_gpu_error >= 0 &&
        p.gpu_error <= r.msaa16_gpu_error)
      return p.gpu_ms * 1e6 / px;
  return -1;
}

// One tuning's answer for a scene under one reading of "at MSAA-16's error".
struct Pick {
  std::string label;     // fastest front point or LOD pair there ("" = none)
  double ns = -1;        // its GPU ns per pixel
  double adaptive = -1;  // the adaptive supersampler's GPU ns per pixel when it reaches that error too
};

// by_gpu: the GPU's own errors against MSAA-16's GPU error; else bltune's errors against MSAA-16's.
Pick pick(const SceneTimes& s, const SceneSummary& r, bool by_gpu) {
  Pick p;
  if (by_gpu) {
    p.label = r.by_gpu_label, p.ns = r.by_gpu_ns, p.adaptive = adaptive_at_msaa16(s, r);
    return p;
  }
  p.label = r.gpu_label, p.ns = r.gpu_ns;
  if (r.lod_ns > 0 && (p.ns < 0 || r.lod_ns < p.ns)) p.label = "lod", p.ns = r.lod_ns;
  p.adaptive = r.adaptive_ns;
  return p;
}

}  // namespace

std::string comparison_markdown(const std::vector<SceneTimes>& a, const std::vector<SceneTimes>& b,
                                const std::string& name_a, const std::string& name_b) {
  std::ostringstream os;
  auto label = [](const Pick& p) { return p.label.empty() ? std::string("not reached") : p.label; };
  auto ns = [](double v) { return v > 0 ? fmt("%.3f", v) : std::string("-"); };
  auto x = [](double v) { return v > 0 ? fmt("%.2fx", v) : std::string("-"); };
  for (const bool by_gpu : {true, false}) {
    os << (by_gpu ? "By the errors measured on the GPU (each program's GPU error at most MSAA-16's GPU error)"
                  : "\nBy bltune's errors (at most MSAA-16's; the GPU's own differ by up to ~1%, which moves "
                    "picks whose error is that close to MSAA-16's)")
       << ": each tuning's fastest front point or LOD pair there (GPU ns per pixel), " << name_a << " / "
       << name_b << " (> 1: " << name_b
       << " is faster), and each against its footprint-adaptive supersampler at that error (its time / ours; "
          "> 1: ours is faster).\n\n| scene | MSAA-16 ns/px | "
       << name_a << ": fastest | ns/px | " << name_b << ": fastest | ns/px | " << name_a << " / " << name_b
       << " | " << name_a << " vs adaptive | " << name_b
       << " vs adaptive |\n|---|---|---|---|---|---|---|---|---|\n";
    int both = 0, faster = 0, slower = 0, win_a = 0, win_b = 0, vs_a = 0, vs_b = 0;
    std::vector<double> ratios;
    for (const SceneTimes& sa : a) {
      const auto it =
          std::find_if(b.begin(), b.end(), [&](const SceneTimes& s) { return s.scene == sa.scene; });
      if (it == b.end()) continue;
      const SceneSummary ra = summarize(sa), rb = summarize(*it);
      const Pick pa = pick(sa, ra, by_gpu), pb = pick(*it, rb, by_gpu);
      const double ratio = pa.ns > 0 && pb.ns > 0 ? pa.ns / pb.ns : -1;
      const double va = pa.adaptive > 0 && pa.ns > 0 ? pa.adaptive / pa.ns : -1;
      const double vb = pb.adaptive > 0 && pb.ns > 0 ? pb.adaptive / pb.ns : -1;
      os << "| " << sa.scene << " | " << ns(ra.msaa16_ns) << " | " << label(pa) << " | " << ns(pa.ns) << " | "
         << label(pb) << " | " << ns(pb.ns) << " | " << x(ratio) << " | " << x(va) << " | " << x(vb)
         << " |\n";
      if (ratio > 0) {
        ++both;
        ratios.push_back(ratio);
        faster += ratio > 1.05;
        slower += ratio < 1 / 1.05;
      }
      if (va > 0) ++vs_a, win_a += va > 1.05;
      if (vb > 0) ++vs_b, win_b += vb > 1.05;
    }
    os << "\nBoth reach MSAA-16's error on " << both << " scene(s): " << name_b << " faster (by > 5%) on "
       << faster << ", slower on " << slower << ", median " << name_a << " / " << name_b << " "
       << (ratios.empty() ? "-" : fmt("%.2fx", median(ratios)))
       << ". Faster than the adaptive supersampler (by > 5%): " << name_a << " on " << win_a << " of " << vs_a
       << ", " << name_b << " on " << win_b << " of " << vs_b << ".\n";
  }
  return os.str();
}

std::string report_markdown(const std::vector<SceneTimes>& scenes, const std::string& renderer, int tile) {
  std::ostringstream os;
  os << "GPU: " << renderer << "; each scene's image tiled " << tile << " x " << tile
     << " (one draw shades every pixel of the scene " << tile * tile
     << " times); ns per pixel of the target, best of 3 runs of glFinish-bracketed draws. Errors are "
        "bltune's (CPU) RMS against the truth; \"CPU\" = bltune's compiled-C++ speed-up on its own "
        "fastest point at MSAA-16's error.\n\n";
  os << "| scene | plain ns/px | MSAA-16 ns/px (x plain) | all-Gaussian ns/px (x plain) | fastest point at "
        "MSAA-16's "
        "error | its ns/px | GPU speed-up at MSAA-16's error | CPU speed-up | footprint-LOD pair ns/px | its "
        "speed-up (GPU / CPU) | adaptive supersampling ns/px | ours vs it (GPU / CPU) | slowest compile ms | "
        "failures |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  std::vector<double> gpu_up, cpu_up;
  int reached = 0, ten_gpu = 0, ten_cpu = 0, failures = 0, ten_gpu_lod = 0, ten_cpu_lod = 0, pairs = 0;
  std::vector<double> ad_gpu, ad_cpu;  // ours vs the adaptive supersampler
  auto up = [](double v) { return v > 0 ? fmt("%.1fx", v) : std::string("-"); };
  for (const SceneTimes& s : scenes) {
    const SceneSummary r = summarize(s);
    failures += r.failures;
    auto ratio = [&](double v) { return v >= 0 && r.plain_ns > 0 ? fmt("%.1fx", v / r.plain_ns) : "-"; };
    os << "| " << s.scene << " | " << (r.plain_ns >= 0 ? fmt("%.3f", r.plain_ns) : "-") << " | "
       << (r.msaa16_ns >= 0 ? fmt("%.3f", r.msaa16_ns) : "-") << " (" << ratio(r.msaa16_ns) << ") | "
       << (r.gaussian_ns >= 0 ? fmt("%.3f", r.gaussian_ns) : "-") << " (" << ratio(r.gaussian_ns) << ") | "
       << (r.gpu_label.empty() ? "not reached" : r.gpu_label) << " | "
       << (r.gpu_ns >= 0 ? fmt("%.3f", r.gpu_ns) : "-") << " | " << up(r.gpu_speedup) << " | "
       << up(r.cpu_speedup) << " | " << (r.lod_ns >= 0 ? fmt("%.3f", r.lod_ns) : "-") << " | "
       << up(r.lod_gpu_speedup) << " / " << up(r.lod_cpu_speedup) << " | "
       << (r.adaptive_ns >= 0 ? fmt("%.3f", r.adaptive_ns) : "-") << " | " << up(r.adaptive_gpu_speedup)
       << " / " << up(r.adaptive_cpu_speedup) << " | "
       << (r.max_compile_ms >= 0 ? fmt("%.0f", r.max_compile_ms) : "-") << " | " << r.failures << " |\n";
    pairs += r.lod_gpu_speedup > 0 || r.lod_cpu_speedup > 0;
    if (r.adaptive_gpu_speedup > 0) ad_gpu.push_back(r.adaptive_gpu_speedup);
    if (r.adaptive_cpu_speedup > 0) ad_cpu.push_back(r.adaptive_cpu_speedup);
    ten_gpu_lod += std::max(r.gpu_speedup, r.lod_gpu_speedup) >= 10;
    ten_cpu_lod += std::max(r.cpu_speedup, r.lod_cpu_speedup) >= 10;
    if (r.gpu_speedup > 0) {
      ++reached;
      gpu_up.push_back(r.gpu_speedup);
      if (r.gpu_speedup >= 10) ++ten_gpu;
    }
    if (r.cpu_speedup > 0) {
      cpu_up.push_back(r.cpu_speedup);
      if (r.cpu_speedup >= 10) ++ten_cpu;
    }
  }
  os << "\nMSAA-16's error reached on " << reached << " of " << scenes.size()
     << " scenes; speed-up at that error >= 10x on " << ten_gpu << " (GPU) / " << ten_cpu
     << " (CPU compiled); median speed-up " << (gpu_up.empty() ? "-" : fmt("%.1fx", median(gpu_up)))
     << " (GPU) / " << (cpu_up.empty() ? "-" : fmt("%.1fx", median(cpu_up))) << " (CPU compiled); "
     << failures << " program(s) failed to compile or draw.\n";
  if (pairs > 0)
    os << "With the footprint-LOD pair where it is faster (" << pairs
       << " scene(s) have one at MSAA-16's error): >= 10x on " << ten_gpu_lod << " (GPU) / " << ten_cpu_lod
       << " (CPU compiled).\n";
  if (!ad_gpu.empty() || !ad_cpu.empty()) {
    auto range = [](const std::vector<double>& v) {
      if (v.empty()) return std::string("-");
      return fmt("%.1fx", *std::min_element(v.begin(), v.end())) + "-" +
             fmt("%.1fx", *std::max_element(v.begin(), v.end())) + ", median " + fmt("%.1fx", median(v));
    };
    os << "Against footprint-adaptive supersampling at MSAA-16's error ("
       << std::max(ad_gpu.size(), ad_cpu.size()) << " scene(s)): ours takes " << range(ad_gpu)
       << " less time (GPU), " << range(ad_cpu) << " (CPU compiled).\n";
  }
  os << errors_markdown(scenes);
  return os.str();
}

}  // namespace bl::gpu_timing
