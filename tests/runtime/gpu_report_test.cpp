// The GPU timing report's conclusions, on a hand-made table (numbers chosen so every answer is
// worked out by hand below).
#include "gpu_timing/gpu_report.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace bl::gpu_timing {
namespace {

SceneTimes table() {
  SceneTimes s;
  s.scene = "toy";
  s.width = 1000, s.height = 1000;  // 1e6 pixels: ms per frame x 1e6 / 1e6 = ns per pixel
  auto p = [](const char* label, const char* kind, int msaa, double error, double cpu_ns, double gpu_ms) {
    ProgramTime t;
    t.label = label, t.kind = kind, t.msaa = msaa, t.error = error, t.compiled_ns = cpu_ns, t.gpu_ms = gpu_ms;
    t.compile_ms = 10;
    return t;
  };
  s.programs = {p("plain", "baseline", 0, 0.10, 5, 0.5),     p("msaa16", "baseline", 16, 0.04, 80, 8.0),
                p("gaussian", "baseline", 0, 0.03, 60, 2.0), p("front00", "front", 0, 0.10, 5, 0.5),
                p("front01", "front", 0, 0.05, 10, 0.6),  // misses MSAA-16's error
                p("front02", "front", 0, 0.04, 20, 1.6),  // reaches it: GPU 8 / 1.6 = 5x, CPU 80 / 20 = 4x
                p("front03", "front", 0, 0.02, 16, 2.0),  // reaches it, faster on the CPU: 80 / 16 = 5x
                p("front04", "front", 0, INFINITY, 1, 0.1)};  // infeasible: never picked
  s.programs[6].compile_ms = 250;
  return s;
}

TEST(GpuReport, PicksTheFastestPointAtMsaa16sErrorByEachClock) {
  const SceneSummary r = summarize(table());
  EXPECT_DOUBLE_EQ(r.plain_ns, 0.5);
  EXPECT_DOUBLE_EQ(r.msaa16_ns, 8.0);
  EXPECT_DOUBLE_EQ(r.gaussian_ns, 2.0);
  EXPECT_EQ(r.gpu_label, "front02");
  EXPECT_DOUBLE_EQ(r.gpu_speedup, 5.0);
  EXPECT_EQ(r.cpu_label, "front03");
  EXPECT_DOUBLE_EQ(r.cpu_speedup, 5.0);
  EXPECT_DOUBLE_EQ(r.max_compile_ms, 250);
  EXPECT_EQ(r.failures, 0);
}

TEST(GpuReport, AFailedProgramIsCountedAndNeverPicked) {
  SceneTimes s = table();
  s.programs[5].gpu_ms = -1;
  s.programs[5].failure = "compile failed";
  const SceneSummary r = summarize(s);
  EXPECT_EQ(r.failures, 1);
  EXPECT_EQ(r.gpu_label, "front03");
  EXPECT_DOUBLE_EQ(r.gpu_speedup, 4.0);
  const std::string md = report_markdown({s}, "toy GPU", 10);
  EXPECT_NE(md.find("| toy | 0.500 | 8.000 (16.0x) | 2.000 (4.0x) | front03 | 2.000 | 4.0x | 5.0x | - | - / "
                    "- | - | - / - | 250 | 1 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("1 program(s) failed"), std::string::npos);
}

TEST(GpuReport, NotReachedWhenNoFrontPointIsAsAccurate) {
  SceneTimes s = table();
  for (ProgramTime& p : s.programs)
    if (p.kind == "front") p.error = 0.05;
  const SceneSummary r = summarize(s);
  EXPECT_TRUE(r.gpu_label.empty());
  EXPECT_LT(r.gpu_speedup, 0);
  EXPECT_NE(report_markdown({s}, "toy GPU", 10).find("not reached"), std::string::npos);
}

// A footprint-LOD pair (kind "lod") is reported beside the single points, never picked as one, and
// counted at >= 10x where it is faster than the best single point on that clock.
TEST(GpuReport, TheLodPairIsReportedBesideTheFrontAndCountedWhereFaster) {
  SceneTimes s = table();
  ProgramTime lod;
  lod.label = "lod", lod.kind = "lod", lod.error = 0.035, lod.compiled_ns = 7, lod.gpu_ms = 0.5;
  s.programs.push_back(lod);  // GPU 8 / 0.5 = 16x, CPU 80 / 7 = 11.4x
  const SceneSummary r = summarize(s);
  EXPECT_EQ(r.gpu_label, "front02");  // the single points' pick is unchanged
  EXPECT_DOUBLE_EQ(r.lod_ns, 0.5);
  EXPECT_DOUBLE_EQ(r.lod_gpu_speedup, 16.0);
  EXPECT_NEAR(r.lod_cpu_speedup, 80.0 / 7, 1e-12);
  const std::string md = report_markdown({s}, "toy GPU", 10);
  EXPECT_NE(md.find("| front02 | 1.600 | 5.0x | 5.0x | 0.500 | 16.0x / 11.4x | - | - / - | 250 | 0 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("speed-up at that error >= 10x on 0 (GPU) / 0 (CPU compiled)"), std::string::npos) << md;
  EXPECT_NE(md.find("(1 scene(s) have one at MSAA-16's error): >= 10x on 1 (GPU) / 1 (CPU compiled)"),
            std::string::npos)
      << md;
  // Less accurate than MSAA-16: no pair.
  s.programs.back().error = 0.05;
  const SceneSummary worse = summarize(s);
  EXPECT_LT(worse.lod_ns, 0);
  EXPECT_LT(worse.lod_gpu_speedup, 0);
  EXPECT_LT(worse.lod_cpu_speedup, 0);
  EXPECT_EQ(report_markdown({s}, "toy GPU", 10).find("With the footprint-LOD pair"), std::string::npos);
}

// The footprint-adaptive supersampler (kind "adaptive"): its time over ours at MSAA-16's error on each
// clock, ours being the fastest point there or the LOD pair where faster. By hand: it takes 3.2 ms on
// the GPU and 40 ns compiled; ours is front02 on the GPU (1.6 ms) and front03 on the CPU (16 ns):
// 2x / 2.5x; with a pair at 0.5 ms and 7 ns: 6.4x / 5.7x. Less accurate than MSAA-16: not compared.
TEST(GpuReport, TheAdaptiveSupersamplerIsComparedWithOurFastest) {
  SceneTimes s = table();
  ProgramTime ad;
  ad.label = "adaptive_ss", ad.kind = "adaptive", ad.error = 0.035, ad.compiled_ns = 40, ad.gpu_ms = 3.2;
  s.programs.push_back(ad);
  SceneSummary r = summarize(s);
  EXPECT_EQ(r.gpu_label, "front02");  // never picked as ours
  EXPECT_DOUBLE_EQ(r.adaptive_ns, 3.2);
  EXPECT_DOUBLE_EQ(r.adaptive_gpu_speedup, 2.0);
  EXPECT_DOUBLE_EQ(r.adaptive_cpu_speedup, 2.5);
  std::string md = report_markdown({s}, "toy GPU", 10);
  EXPECT_NE(md.find("| - | - / - | 3.200 | 2.0x / 2.5x | 250 | 0 |"), std::string::npos) << md;
  EXPECT_NE(md.find("Against footprint-adaptive supersampling at MSAA-16's error (1 scene(s)): ours takes "
                    "2.0x-2.0x, median 2.0x less time (GPU), 2.5x-2.5x, median 2.5x (CPU compiled)."),
            std::string::npos)
      << md;
  ProgramTime lod;
  lod.label = "lod", lod.kind = "lod", lod.error = 0.035, lod.compiled_ns = 7, lod.gpu_ms = 0.5;
  s.programs.push_back(lod);
  r = summarize(s);
  EXPECT_DOUBLE_EQ(r.adaptive_gpu_speedup, 6.4);
  EXPECT_NEAR(r.adaptive_cpu_speedup, 40.0 / 7, 1e-12);
  s.programs[s.programs.size() - 2].error = 0.05;
  r = summarize(s);
  EXPECT_LT(r.adaptive_ns, 0);
  EXPECT_LT(r.adaptive_gpu_speedup, 0);
  md = report_markdown({s}, "toy GPU", 10);
  EXPECT_EQ(md.find("Against footprint-adaptive"), std::string::npos) << md;
}

// Errors measured on the GPU (blgpu_time's merge): the fastest front point or pair whose GPU error is
// at most MSAA-16's GPU error, the largest GPU / CPU error ratio and the programs with NaN pixels.
// By hand: MSAA-16's GPU error is 0.041; front02 (0.0405, 1.6 ms) qualifies, front03 (0.05 on the
// GPU against 0.02 on the CPU: ratio 2.5, the worst) does not, the pair (0.039, 0.5 ms) is the
// fastest: 8 / 0.5 = 16x. front04 drew 3 NaN pixels; the truth is never compared.
TEST(GpuReport, ErrorsMeasuredOnTheGpu) {
  SceneTimes s = table();
  EXPECT_EQ(errors_markdown({s}), "");  // nothing measured: no section (a pack from before stop 41)
  const double gpu_error[] = {0.1002, 0.041, 0.03, 0.10, 0.06, 0.0405, 0.05, 0.2};
  for (std::size_t i = 0; i < s.programs.size(); ++i) s.programs[i].gpu_error = gpu_error[i];
  s.programs[7].nonfinite = 3;
  ProgramTime lod;
  lod.label = "lod", lod.kind = "lod", lod.error = 0.035, lod.compiled_ns = 7, lod.gpu_ms = 0.5,
  lod.gpu_error = 0.039;
  ProgramTime truth;
  truth.label = "truth", truth.kind = "truth", truth.msaa = 1024, truth.error = INFINITY, truth.gpu_error = 5;
  s.programs.push_back(lod);
  s.programs.push_back(truth);
  const SceneSummary r = summarize(s);
  EXPECT_DOUBLE_EQ(r.msaa16_gpu_error, 0.041);
  EXPECT_EQ(r.gpu_label, "front02");  // by bltune's errors, as before
  EXPECT_DOUBLE_EQ(r.gpu_point_cpu_error, 0.04);
  EXPECT_DOUBLE_EQ(r.gpu_point_error, 0.0405);
  EXPECT_EQ(r.by_gpu_label, "lod");
  EXPECT_DOUBLE_EQ(r.by_gpu_speedup, 16.0);
  EXPECT_DOUBLE_EQ(r.worst_error_ratio, 2.5);
  EXPECT_EQ(r.worst_error_label, "front03");
  EXPECT_EQ(r.nonfinite_programs, 1);
  const std::string md = report_markdown({s}, "toy GPU", 10);
  EXPECT_NE(
      md.find("| toy | 0.1000 / 0.1002 | 0.0400 / 0.0410 | front02: 0.0400 / 0.0405 | lod | 0.500 | 16.0x | "
              "2.500 (front03) | 1 / 0 |"),
      std::string::npos)
      << md;
  EXPECT_NE(
      md.find("MSAA-16's error reached on 1 of 1 scenes, at >= 10x less GPU time on 1; median speed-up "
              "16.0x; 1 program(s) with NaN or infinite pixels; the largest GPU / CPU error ratio 2.500 "
              "(toy/front03)."),
      std::string::npos)
      << md;
  // The pair's GPU error above MSAA-16's: front02 is the fastest that qualifies (8 / 1.6 = 5x).
  s.programs[8].gpu_error = 0.042;
  EXPECT_EQ(summarize(s).by_gpu_label, "front02");
  EXPECT_DOUBLE_EQ(summarize(s).by_gpu_speedup, 5.0);
}

// Two tunings of one scene side by side, by the GPU's errors and by bltune's: A as table() with GPU errors
// (front02 the fastest at MSAA-16's GPU error, 1.6 ns), B faster (a point at 0.8 ns); each against its
// adaptive supersampler at that error (A's 2.4 ns: 1.5x; B's error misses it: "-"). A scene only in
// one run is left out.
TEST(GpuReport, ComparesTwoTunings) {
  SceneTimes a = table();
  const double gpu_error[] = {0.1, 0.04, 0.03, 0.1, 0.05, 0.039, 0.02, 0.2};
  for (std::size_t i = 0; i < a.programs.size(); ++i) a.programs[i].gpu_error = gpu_error[i];
  ProgramTime ad;
  ad.label = "adaptive_ss", ad.kind = "adaptive", ad.error = 0.039, ad.gpu_ms = 2.4, ad.gpu_error = 0.0395;
  a.programs.push_back(ad);
  SceneTimes b = a;
  b.programs[5].gpu_ms = 0.8;            // front02: twice as fast
  b.programs.back().gpu_error = 0.0401;  // B's adaptive supersampler misses MSAA-16's GPU error
  SceneTimes other = a;
  other.scene = "only_in_a";
  const std::string md = comparison_markdown({a, other}, {b}, "cpu", "gpu");
  EXPECT_NE(md.find("| toy | 8.000 | front02 | 1.600 | front02 | 0.800 | 2.00x | 1.50x | - |"),
            std::string::npos)
      << md;
  EXPECT_EQ(md.find("only_in_a"), std::string::npos) << md;
  EXPECT_NE(
      md.find(
          "Both reach MSAA-16's error on 1 scene(s): gpu faster (by > 5%) on 1, slower on 0, median cpu / "
          "gpu 2.00x. Faster than the adaptive supersampler (by > 5%): cpu on 1 of 1, gpu on 0 of 0."),
      std::string::npos)
      << md;
  // By bltune's errors B's adaptive supersampler reaches MSAA-16's (0.039 <= 0.04): 2.4 / 0.8 = 3x.
  const std::size_t cpu_table = md.find("By bltune's errors");
  ASSERT_NE(cpu_table, std::string::npos) << md;
  EXPECT_NE(md.find("| toy | 8.000 | front02 | 1.600 | front02 | 0.800 | 2.00x | 1.50x | 3.00x |", cpu_table),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("cpu on 1 of 1, gpu on 1 of 1.", cpu_table), std::string::npos) << md;
}

}  // namespace
}  // namespace bl::gpu_timing
