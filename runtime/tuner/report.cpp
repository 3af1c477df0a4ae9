#include "tuner/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "jit/jit.hpp"

namespace bl::tuner {

namespace {

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string mix_text(const Measured& m) {
  std::string out;
  for (const auto& [k, v] : m.mix)
    if (v > 0) out += (out.empty() ? "" : ", ") + k + " " + fmt("%.0f%%", 100 * v);
  return out;
}

std::string glsl_text(double ms) {
  return ms >= 0 ? fmt("%.3f", ms) : "-";
}

bool run_gnuplot(const std::string& script) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) return false;
  FILE* p = popen("gnuplot", "w");
  if (!p) return false;
  std::fwrite(script.data(), 1, script.size(), p);
  return pclose(p) == 0;
}

std::string join_labels(const std::vector<std::string>& v) {
  std::string out;
  for (const std::string& x : v) out += (out.empty() ? "" : ", ") + x;
  return out;
}

}  // namespace

double measured_ms(const Measured& m) {
  return m.compiled_ms > 0 ? m.compiled_ms : m.eval_ms;
}

ModelAccuracy model_accuracy(const SceneResult& r) {
  std::vector<double> e;
  ModelAccuracy a;
  for (const auto* list : {&r.front, &r.baselines})
    for (const Measured& m : *list)
      if (m.compiled_ns > 0 && m.model_ns > 0) {
        const double ratio = m.model_ns / m.compiled_ns;
        e.push_back(std::fabs(ratio - 1));
        if (e.back() > kModelTolerance) a.outside.push_back(m.label + " (" + fmt("%.2f", ratio) + ")");
      }
  a.points = static_cast<int>(e.size());
  if (e.empty()) return a;
  std::sort(e.begin(), e.end());
  a.median = e.size() % 2 ? e[e.size() / 2] : 0.5 * (e[e.size() / 2 - 1] + e[e.size() / 2]);
  a.worst = e.back();
  return a;
}

std::vector<Speedup> speedups(const SceneResult& r) {
  std::vector<Speedup> out;
  for (const Measured& b : r.baselines) {
    if (b.msaa == 0) continue;
    Speedup s;
    s.msaa = b.msaa;
    s.msaa_error = b.error;
    for (std::size_t i = 0; i < r.front.size(); ++i)  // sorted by model time: first hit is fastest
      if (r.front[i].error <= b.error) {
        s.front_index = static_cast<int>(i);
        s.model = b.model_ns / r.front[i].model_ns;
        s.compiled = b.compiled_ms > 0 && r.front[i].compiled_ms > 0;
        s.measured = s.compiled ? b.compiled_ms / r.front[i].compiled_ms : b.eval_ms / r.front[i].eval_ms;
        break;
      }
    out.push_back(s);
  }
  return out;
}

Speedup speedup16(const SceneResult& r) {
  for (const Speedup& s : speedups(r))
    if (s.msaa == 16) return s;
  return {};
}

namespace {

// The footprint-LOD pair is at MSAA-16's error (s16: speedup16(r)); it may be where no single point
// is (a side supersampled, from stop 36).
bool lod_at16(const SceneResult& r, const Speedup& s16) {
  return s16.msaa == 16 && r.lod && r.lod->error <= s16.msaa_error;
}

// A footprint-LOD side for the report: its schedule, or "plain at N stratified samples" (an ssN side:
// the plain schedule, every node none, is not worth a line).
std::string side_text(const std::string& schedule, int samples) {
  return samples > 1 ? "plain at " + std::to_string(samples) + " stratified samples" : "`" + schedule + "`";
}

TenfoldGap tenfold_gap(const SceneResult& r, const Speedup& s16, double factor) {
  TenfoldGap g;
  const Measured* m16 = nullptr;
  for (const Measured& b : r.baselines)
    if (b.msaa == 16) m16 = &b;
  if (!m16 || !(m16->model_ns > 0)) return g;
  g.msaa16_error = m16->error;
  // The fastest point at its error is the one the speed-up is read from: it must reach `factor`.
  g.at_error = s16.front_index;
  if (g.at_error >= 0) g.time_cut = 1 - s16.model / factor;
  const double budget = m16->model_ns / factor;
  for (std::size_t i = 0; i < r.front.size(); ++i) {
    const Measured& m = r.front[i];
    if (m.model_ns <= budget && (g.at_time < 0 || m.error < r.front[g.at_time].error)) {
      g.at_time = static_cast<int>(i);
      g.error_cut = 1 - m16->error / m.error;
    }
  }
  return g;
}

}  // namespace

LodSpeedup lod_speedup16(const SceneResult& r) {
  LodSpeedup s;
  if (!r.lod) return s;
  for (const Measured& b : r.baselines)
    if (b.msaa == 16) {
      if (r.lod->model_ns > 0) s.model = b.model_ns / r.lod->model_ns;
      if (r.lod->compiled_ns > 0 && b.compiled_ns > 0) s.measured = b.compiled_ns / r.lod->compiled_ns;
    }
  return s;
}

Ours16 ours16(const SceneResult& r) {
  Ours16 o;
  const Speedup s16 = speedup16(r);
  if (s16.msaa != 16) return o;
  const bool lod = lod_at16(r, s16);
  if (s16.front_index >= 0) {
    const Measured& point = r.front[s16.front_index];
    o.compiled_ns = point.compiled_ns > 0 ? point.compiled_ns : 0;
    o.model_ns = point.model_ns;
  }
  if (lod && r.lod->compiled_ns > 0 && (o.compiled_ns <= 0 || r.lod->compiled_ns < o.compiled_ns))
    o.compiled_ns = r.lod->compiled_ns;
  if (lod && r.lod->model_ns > 0 && (o.model_ns <= 0 || r.lod->model_ns < o.model_ns))
    o.model_ns = r.lod->model_ns;
  return o;
}

StratifiedSpeedup stratified_speedup16(const SceneResult& r) {
  StratifiedSpeedup out;
  const Speedup s16 = speedup16(r);
  if (s16.msaa != 16) return out;
  const Measured* ss = nullptr;  // the fewest samples at MSAA-16's error
  for (const Measured& b : r.baselines)
    if (b.supersample > 0 && b.error <= s16.msaa_error && (ss == nullptr || b.supersample < ss->supersample))
      ss = &b;
  if (ss == nullptr) return out;
  out.label = ss->label;
  out.ss_ns = ss->compiled_ns > 0 ? ss->compiled_ns : 0;
  out.ss_model_ns = ss->model_ns;
  const Ours16 o = ours16(r);
  if (ss->compiled_ns > 0 && o.compiled_ns > 0) {
    out.ours_ns = o.compiled_ns;
    out.measured = ss->compiled_ns / o.compiled_ns;
  }
  if (ss->model_ns > 0 && o.model_ns > 0) {
    out.ours_model_ns = o.model_ns;
    out.model = ss->model_ns / o.model_ns;
  }
  return out;
}

AdaptiveSpeedup adaptive_speedup16(const SceneResult& r) {
  AdaptiveSpeedup out;
  const Ours16 o = ours16(r);
  if (!r.adaptive_ss) return out;
  if (o.model_ns > 0) out.model = r.adaptive_ss->model_ns / o.model_ns;
  if (o.compiled_ns > 0 && r.adaptive_ss->compiled_ns > 0)
    out.measured = r.adaptive_ss->compiled_ns / o.compiled_ns;
  return out;
}

TenfoldGap tenfold_gap(const SceneResult& r, double factor) {
  return tenfold_gap(r, speedup16(r), factor);
}

void write_scene_report(const SceneResult& r, const std::string& dir) {
  std::filesystem::create_directories(dir);
  const double px = r.pixels;
  {
    std::ofstream csv(dir + "/front.csv");
    csv << "kind,label,model_ns_per_pixel,model_ms_per_frame,eval_ms_per_frame,glsl_ms_per_frame,search_"
           "error,"
           "rms_display,psnr_db,refined,compiled_ns_per_pixel,compiled_ms_per_frame,rule_mix,schedule,"
           "nonfinite_pixels,out_of_range_pixels,graph_hash,msaa,supersample\n";
    auto row = [&](const char* kind, const Measured& m) {
      csv << kind << "," << m.label << "," << m.model_ns << "," << m.model_ns * px * 1e-6 << "," << m.eval_ms
          << "," << m.glsl_ms << "," << m.search_error << "," << m.error << "," << m.psnr << ","
          << (m.refined ? 1 : 0) << "," << m.compiled_ns << "," << m.compiled_ms << ",\"" << mix_text(m)
          << "\",\"" << m.schedule << "\"," << m.nonfinite << "," << m.out_of_range << "," << r.graph_hash
          << "," << m.msaa << "," << m.supersample << "\n";
    };
    for (const Measured& m : r.front) row("front", m);
    for (const Measured& m : r.baselines) row("baseline", m);
  }
  const std::string csv = std::filesystem::absolute(dir + "/front.csv").string();
  const std::string png = std::filesystem::absolute(dir + "/pareto.png").string();
  std::ostringstream g;
  g << "set terminal pngcairo size 1400,560 font 'Sans,10' noenhanced\nset output '" << png << "'\n"
    << "set datafile separator ','\nset logscale xy\nset grid\nset key outside right top\n"
    << "set ylabel 'RMS error (display space)'\nf = '" << csv << "'\n"
    << "front(c) = strcol(1) eq 'front' ? column(c) : NaN\n"
    << "lab(name, c) = strcol(2) eq name ? column(c) : NaN\n"
    // front.csv's last two columns: MSAA's and ssN's sample counts (0 on other rows)
    << "msaa(c) = column(18) > 0 ? column(c) : NaN\n"
    << "ss(c) = column(19) > 0 ? column(c) : NaN\n"
    << "set multiplot layout 1,2 title '" << r.scene
    << ": Pareto front vs MSAA, plain, all-Dorn, all-Gaussian'\n";
  for (int panel = 0; panel < 2; ++panel) {
    const bool compiled = !r.front.empty() && r.front.front().compiled_ms > 0;
    const int c = panel == 0 ? 3 : compiled ? 12 : 5;
    g << "set xlabel '"
      << (panel == 0 ? "cost model (ns per pixel)"
          : compiled ? "measured compiled C++ -O3 (ms per frame, 1 thread)"
                     : "measured evaluator (ms per frame)")
      << "'\n"
      << "plot f every ::1 u (front(" << c << ")):(front(8)) w lp pt 7 lc rgb '#d62728' t 'tuned front', \\\n"
      << "  '' every ::1 u (msaa(" << c << ")):(msaa(8)) w lp pt 5 lc rgb '#1f77b4' t 'MSAA 2..32', \\\n"
      << "  '' every ::1 u (msaa(" << c << ")):(msaa(8)):2 w labels offset 0,1 notitle, \\\n"
      << "  '' every ::1 u (ss(" << c << ")):(ss(8)) w lp pt 4 lc rgb '#17becf' t 'stratified ss4..16', \\\n"
      << "  '' every ::1 u (ss(" << c << ")):(ss(8)):2 w labels offset 0,-1 notitle, \\\n"
      << "  '' every ::1 u (lab('plain'," << c
      << ")):(lab('plain',8)) w p pt 9 ps 1.5 lc rgb '#000000' t 'plain', \\\n"
      << "  '' every ::1 u (lab('dorn'," << c
      << ")):(lab('dorn',8)) w p pt 11 ps 1.5 lc rgb '#2ca02c' t 'all Dorn', \\\n"
      << "  '' every ::1 u (lab('gaussian'," << c
      << ")):(lab('gaussian',8)) w p pt 13 ps 1.5 lc rgb '#ff7f0e' t "
         "'all adaptive Gaussian'";
    // The footprint-LOD pair (not a row of front.csv): inline data, on the compiled panel when timed.
    const double lod_x = !r.lod       ? -1
                         : panel == 0 ? r.lod->model_ns
                         : compiled   ? r.lod->compiled_ns * px * 1e-6
                                      : -1;
    // The footprint-adaptive supersampler likewise.
    const double ad_x = !r.adaptive_ss ? -1
                        : panel == 0   ? r.adaptive_ss->model_ns
                        : compiled     ? r.adaptive_ss->compiled_ns * px * 1e-6
                                       : -1;
    std::string data;  // the inline points' data blocks, after the plot command
    if (lod_x > 0) {
      g << ", \\\n  '-' u 1:2 w p pt 15 ps 2 lc rgb '#9467bd' t 'footprint LOD (" << r.lod->near << " + "
        << r.lod->far << ")'";
      data += fmt("%g", lod_x) + "," + fmt("%g", r.lod->error) + "\ne\n";  // the script reads commas
    }
    if (ad_x > 0) {
      g << ", \\\n  '-' u 1:2 w p pt 6 ps 2 lc rgb '#17becf' t 'adaptive supersampling ("
        << r.adaptive_ss->near_samples << " / " << r.adaptive_ss->far_samples << " samples)'";
      data += fmt("%g", ad_x) + "," + fmt("%g", r.adaptive_ss->error) + "\ne\n";
    }
    g << "\n" << data;
  }
  g << "unset multiplot\n";
  const bool plotted = run_gnuplot(g.str());

  std::ofstream md(dir + "/report.md");
  md << "# Tuning " << r.scene << "\n\n"
     << "DAG nodes " << r.nodes << ", genes " << r.genes << ", " << r.frames << " frame(s) of " << r.pixels
     << " pixels. Search " << fmt("%.1f", r.search_seconds) << " s (" << r.evaluations
     << " distinct candidates), finalize " << fmt("%.1f", r.finalize_seconds) << " s.\n\n"
     << (plotted ? "![Pareto front](pareto.png)\n\n" : "(gnuplot not found: no plot)\n\n")
     << "Times: *model* = cost model ("
     << (r.cost_machine.empty()
             ? std::string("ns per pixel, calibrated on compiled code")
             : "ns per pixel on **" + r.cost_machine +
                   "**, fitted on its draws (bench/gpu_cost_fit); the compiled and eval columns "
                   "time this CPU")
     << "); *compiled* = the emitted "
        "C++ compiled at run time (`"
     << jit::flags_text()
     << "`), one thread, over frame 0's pixel inputs (ns per pixel; ms per "
        "frame), the time the speed-ups quote"
     << (r.compiled_note.empty()
             ? ""
             : " (**not measured**: " + r.compiled_note + "; the evaluator's time is quoted)")
     << "; *eval* = the batch evaluator on the same inputs (ms per frame); *GLSL* = emitted GLSL on "
     << (r.gl_renderer.empty() ? "(not measured: `bltune --glsl` times it)" : r.gl_renderer)
     << " ms per frame. MSAA n: the plain program n times per pixel at counter-based jittered positions "
        "(compiled: measured; model and eval: n x plain's). Errors: RMS in display space over every pixel "
        "of every frame, on the unclamped display curve (a value outside [0, 1] counts with its distance, a "
        "NaN/inf channel as 1; docs/runtime.md); *NaN px* / *range px*: pixels (all frames) with a NaN/inf "
        "channel / a channel outside [0, 1] widened to the ground truth's range. "
     << (r.rejected_nonfinite >= 0
             ? "Search: " + std::to_string(r.rejected_nonfinite) +
                   " evaluation(s) infeasible for NaN/inf on the sampled pixels (error +inf)."
             : std::string())
     << "\n\n"
     << "| point | model ns/px | compiled ns/px | model / compiled | compiled ms/frame | eval ms/frame | "
        "GLSL "
        "ms/frame | search error | RMS | PSNR dB | NaN px | range px | NM | rule mix "
        "|\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  auto row = [&](const Measured& m) {
    const bool c = m.compiled_ns > 0;
    // Three digits under 10 ns (a GPU model prices a pixel at 0.3-5 ns); model / compiled only when
    // both time this CPU.
    md << "| " << m.label << " | " << fmt(m.model_ns < 10 ? "%.3g" : "%.1f", m.model_ns) << " | "
       << (c ? fmt("%.1f", m.compiled_ns) : "-") << " | "
       << (c && r.cost_machine.empty() ? fmt("%.2f", m.model_ns / m.compiled_ns) : "-") << " | "
       << (c ? fmt("%.3f", m.compiled_ms) : "-") << " | " << fmt("%.3f", m.eval_ms) << " | "
       << glsl_text(m.glsl_ms) << " | "
       << (std::isnan(m.search_error) ? std::string("-") : fmt("%.5f", m.search_error)) << " | "
       << fmt("%.5f", m.error) << " | " << fmt("%.2f", m.psnr) << " | " << m.nonfinite << " | "
       << m.out_of_range << " | " << (m.refined ? "yes" : "") << " | " << mix_text(m) << " |\n";
  };
  for (const Measured& m : r.front) row(m);
  md << "| **baselines** | | | | | | | | | | | | | |\n";
  for (const Measured& m : r.baselines) row(m);
  md << "\n## Speed-up against MSAA at equal error\n\n| MSAA | its RMS | fastest front point at <= that "
        "error | "
        "speed-up (model) | speed-up (measured) |\n|---|---|---|---|---|\n";
  for (const Speedup& s : speedups(r)) {
    md << "| " << s.msaa << " | " << fmt("%.5f", s.msaa_error) << " | ";
    if (s.front_index < 0)
      md << "none reaches it | - | - |\n";
    else
      md << r.front[s.front_index].label << " | " << fmt("%.1fx", s.model) << " | "
         << fmt("%.1fx", s.measured) << (s.compiled ? " compiled" : " evaluator") << " |\n";
  }
  {
    const StratifiedSpeedup st = stratified_speedup16(r);
    md << "\nStratified supersampling in the shader (ssN: the plain program at N fixed offsets, "
          "compiler/supersample.hpp; the model prices its samples one after another): ";
    auto ns = [](double v) { return v > 0 ? fmt("%.2f", v) : std::string("-"); };
    auto ratio = [](double v) { return v > 0 ? fmt("%.1fx", v) : std::string("-"); };
    if (st.label.empty())
      md << "no ssN baseline reaches MSAA-16's error.\n";
    else if (!(st.ours_model_ns > 0 || st.ours_ns > 0))
      md << "the cheapest at MSAA-16's error is " << st.label << " (" << ns(st.ss_model_ns)
         << " ns/px model, " << ns(st.ss_ns)
         << " compiled); no front point or LOD pair reaches that error.\n";
    else
      md << "the cheapest at MSAA-16's error is " << st.label << " (" << ns(st.ss_model_ns)
         << " ns/px model, " << ns(st.ss_ns)
         << " compiled); the fastest front point or LOD pair at that error takes " << ns(st.ours_model_ns)
         << " model, " << ns(st.ours_ns) << " compiled: **" << ratio(st.model) << "** / **"
         << ratio(st.measured) << "** less time.\n";
    md << "\nFootprint-adaptive stratified supersampling (tuner/adaptive_supersampling.hpp: two sample "
          "counts "
          "chosen per pixel by its footprint, as the LOD pair chooses two programs): ";
    if (!r.adaptive_ss) {
      md << "no pair of sample counts reaches MSAA-16's error.\n";
    } else {
      const LodResult& a = *r.adaptive_ss;
      const AdaptiveSpeedup as = adaptive_speedup16(r);
      md << a.near_samples << " sample(s) below a footprint of " << fmt("%.3g", a.limit) << ", "
         << a.far_samples << " above (" << fmt("%.0f%%", 100 * a.near_share)
         << " of pixels near): " << ns(a.model_ns) << " ns/px model, " << ns(a.compiled_ns)
         << " compiled, error " << fmt("%.5f", a.error) << "; "
         << (as.model > 0 || as.measured > 0
                 ? "the fastest front point or LOD pair at MSAA-16's error takes **" + ratio(as.model) +
                       "** / **" + ratio(as.measured) + "** less time.\n"
                 : std::string("no front point or LOD pair reaches that error.\n"));
    }
  }
  md << "\n## Footprint LOD at MSAA-16's error\n\n"
        "Two programs chosen per pixel by its footprint (the larger of sigma_u and sigma_v): the near "
        "one below the limit, the far one above, compiled into one loop (tuner/lod_pair.hpp). Each is a "
        "front "
        "point, a search front point (searchNN: row NN of front_search.csv, not measured on its own), "
        "such a point descended as one side of the pair (frontNN-near, frontNN-far: "
        "tuner/lod_polish.hpp) or "
        "the plain program at N stratified samples (ssN, near only); the far one is smoothed. The fastest "
        "pair at "
        "MSAA-16's error is kept when it beats every single point there.\n\n";
  if (r.lod) {
    const LodSpeedup ls = lod_speedup16(r);
    md << "| near | far | footprint limit | pixels near | model ns/px | compiled ns/px | RMS | speed-up "
          "(model / measured) |\n|---|---|---|---|---|---|---|---|\n"
       << "| " << r.lod->near << " | " << r.lod->far << " | " << fmt("%.4g", r.lod->limit) << " | "
       << fmt("%.0f%%", 100 * r.lod->near_share) << " | " << fmt("%.2f", r.lod->model_ns) << " | "
       << (r.lod->compiled_ns > 0 ? fmt("%.2f", r.lod->compiled_ns) : "-") << " | "
       << fmt("%.5f", r.lod->error) << " | " << fmt("%.1fx", ls.model) << " / "
       << (ls.measured > 0 ? fmt("%.1fx", ls.measured) : "-") << " |\n\n"
       << "Code: `front/lod.glsl`, `front/lod.hpp`. Schedules: near "
       << side_text(r.lod->near_schedule, r.lod->near_samples) << "; far "
       << side_text(r.lod->far_schedule, r.lod->far_samples) << ".\n";
  } else {
    md << "None: no pair reaches MSAA-16's error faster than the fastest single point there.\n";
  }
  const ModelAccuracy acc = model_accuracy(r);
  if (!r.cost_machine.empty())
    md << "\nThe model prices " << r.cost_machine
       << ", the compiled column times this CPU: their ratio says nothing (bench/gpu_cost_fit judges the "
          "model "
          "against the GPU's own draws).\n";
  else if (acc.points > 0)
    md << "\nCost model vs compiled code over " << acc.points
       << " measured points: median |model/compiled - 1| " << fmt("%.0f%%", 100 * acc.median) << ", worst "
       << fmt("%.0f%%", 100 * acc.worst) << "; model / compiled outside 1 +- "
       << fmt("%.0f%%", 100 * kModelTolerance) << ": "
       << (acc.outside.empty() ? std::string("none") : join_labels(acc.outside)) << ".\n";
  if (!r.anchor_breakdown.empty()) md << "\n" << r.anchor_breakdown;
  md << "\nImages: `front*_vs_truth_msaa.png` (frame 0: ground truth | variant | MSAA of the nearest model "
        "time). Full schedules (node:rule) are in front.csv.\n";
}

namespace {

// "The critical path: 111 instructions, bl::plain::sin x6 67.03 ns (31%), ...": what a
// latency-bound program would have to shorten, largest first.
std::string critical_path_line(const CostModel::Breakdown& b) {
  std::vector<std::pair<double, std::string>> parts;
  int n = 0;
  for (const auto& [name, c] : b.path) {
    parts.emplace_back(c.ns, name + " x" + std::to_string(c.count));
    n += c.count;
  }
  std::stable_sort(parts.begin(), parts.end(),
                   [](const auto& x, const auto& y) { return x.first > y.first; });
  std::string line = "The critical path: " + std::to_string(n) + " instructions with a latency";
  constexpr std::size_t kShown = 8;
  double rest = 0;
  for (std::size_t k = 0; k < parts.size(); ++k)
    if (k < kShown)
      line += ", " + parts[k].second + " " + fmt("%.2f", parts[k].first) + " ns (" +
              fmt("%.0f%%", 100 * parts[k].first / b.path_ns) + ")";
    else
      rest += parts[k].first;
  if (parts.size() > kShown)
    line += ", " + std::to_string(parts.size() - kShown) + " other kinds " + fmt("%.2f", rest) + " ns";
  return line + ".\n\n";
}

}  // namespace

std::string time_breakdown_markdown(const CostModel& m, const compiler::Program& p,
                                    const compiler::Program& plain) {
  const CostModel::Breakdown b = m.breakdown(p);
  std::vector<std::pair<double, std::string>> rows;
  for (const auto& [name, calls] : b.functions)
    rows.emplace_back(calls.ns, "| " + name + " | " + std::to_string(calls.count) + " | ");
  rows.emplace_back(b.ops_ns, "| inline arithmetic | " + std::to_string(b.ops) + " | ");
  rows.emplace_back(b.spill_ns, "| values kept across calls (spill) | | ");
  rows.emplace_back(b.loop_ns,
                    "| pixel loop and " + std::to_string(p.outputs.size()) + " output stores | | ");
  std::stable_sort(rows.begin(), rows.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  std::ostringstream md;
  md << "| part | calls | ns/px | share of T |\n|---|---|---|---|\n";
  for (const auto& [ns, row] : rows)
    md << row << fmt("%.2f", ns) << " | "
       << fmt("%.0f%%", b.throughput_ns > 0 ? 100 * ns / b.throughput_ns : 0.0) << " |\n";
  md << "| **throughput T** | | " << fmt("%.2f", b.throughput_ns) << " | 100% |\n\n";
  if (m.window_ns > 0 && b.path_ns > 0)
    md << "Latency: critical path L " << fmt("%.2f", b.path_ns) << " ns; with a " << fmt("%.1f", m.window_ns)
       << " ns out-of-order window the chain costs L' = L min(1, T / window) = " << fmt("%.2f", b.chain_ns)
       << " ns per pixel; cost (T^" << fmt("%g", CostModel::kLatencyNorm) << " + L'^"
       << fmt("%g", CostModel::kLatencyNorm) << ")^(1/" << fmt("%g", CostModel::kLatencyNorm) << ") = **"
       << fmt("%.2f", b.cost_ns) << " ns/px**.\n\n"
       << critical_path_line(b);
  else
    md << "No latencies in this cost model (" << m.method << "): cost = "
       << (m.floor_ns > 0 ? "T against the floor of " + fmt("%.3f", m.floor_ns) + " ns" : std::string("T"))
       << " = **" << fmt("%.2f", b.cost_ns) << " ns/px**.\n\n";
  const double plain_ns = m.cost(plain), msaa16_ns = m.msaa_cost(plain, 16);  // as finalize quotes it
  const double vs16 = msaa16_ns / b.cost_ns;
  md << "Plain program " << fmt("%.2f", plain_ns) << " ns/px: this schedule costs "
     << fmt("%.2f", b.cost_ns / plain_ns) << "x plain, " << fmt("%.1f", vs16 >= 1 ? vs16 : 1 / vs16) << "x "
     << (vs16 >= 1 ? "less" : "more") << " time than MSAA-16 ("
     << (m.floor_ns > 0 ? "16 samples of plain in one fragment, " : "16 plain programs, ")
     << fmt("%.1f", msaa16_ns) << " ns/px). 10x less time than MSAA-16 at its error asks for at most "
     << fmt("%.2f", msaa16_ns / 10) << " ns/px (" << fmt("%.2f", msaa16_ns / 10 / plain_ns) << "x plain).\n";
  return md.str();
}

void write_suite_summary(const std::vector<SceneResult>& rs, const std::string& dir) {
  std::filesystem::create_directories(dir);
  std::ofstream md(dir + "/summary.md"), csv(dir + "/summary.csv");
  csv << "scene,nodes,search_s,finalize_s,front_size,msaa16_error,best_error,speedup16_model,speedup16_"
         "measured,"
         "reaches_10x,model_vs_compiled_median,model_vs_compiled_worst,lod_speedup16_model,lod_speedup16_"
         "measured,reaches_10x_with_lod,stratified16,speedup16_vs_stratified_model,speedup16_vs_stratified_"
         "measured,adaptive_ss,speedup16_vs_adaptive_model,speedup16_vs_adaptive_measured\n";
  md << "# Tuning summary\n\n";
  // A suite priced for another machine (bltune --cost-machine) says so first: "model" is its time.
  if (!rs.empty() && !rs.front().cost_machine.empty())
    md << "Model times: **" << rs.front().cost_machine
       << "** (a cost model fitted on its draws, bench/gpu_cost_fit); measured: compiled C++ on this "
          "CPU.\n\n";
  md << "| scene | nodes | search s | front | MSAA-16 RMS | best RMS | time at MSAA-16 "
        "error "
        "(model / measured speed-up) | >= 10x | model vs compiled (median / worst) | footprint LOD at "
        "MSAA-16's error (model / measured) | >= 10x with LOD | vs stratified supersampling at MSAA-16's "
        "error (model / measured) | vs footprint-adaptive supersampling (model / measured) "
        "|\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  int reach_single = 0, reach_lod = 0;
  int count_single = 0, count_lod = 0, count_ss = 0, count_ss_model = 0, with_ss = 0;
  int count_ad = 0, count_ad_model = 0, with_ad = 0;
  // Beside it, where each scene stands against >= 10x by the model: what to cut, time or error.
  std::ostringstream gaps;
  auto pct = [](double cut) { return cut <= 0 ? std::string("none") : fmt("%.0f%%", 100 * cut); };
  for (const SceneResult& r : rs) {
    double best = INFINITY;
    for (const Measured& m : r.front) best = std::min(best, m.error);
    const Speedup s16 = speedup16(r);
    const bool ten = s16.front_index >= 0 && s16.model >= 10;
    const LodSpeedup ls = lod_speedup16(r);
    const bool ten_lod = ten || ls.model >= 10;
    count_single += ten;
    count_lod += ten_lod;
    reach_single += s16.front_index >= 0;
    reach_lod += s16.front_index >= 0 || lod_at16(r, s16);
    const ModelAccuracy acc = model_accuracy(r);
    md << "| " << r.scene << " | " << r.nodes << " | " << fmt("%.1f", r.search_seconds) << " | "
       << r.front.size() << " | " << fmt("%.5f", s16.msaa_error) << " | " << fmt("%.5f", best) << " | "
       << (s16.front_index < 0 ? std::string("not reached")
                               : fmt("%.1fx", s16.model) + " / " + fmt("%.1fx", s16.measured))
       << " | " << (ten ? "yes" : "no") << " | "
       << (acc.points && r.cost_machine.empty()  // a GPU model against CPU times says nothing
               ? fmt("%.0f%%", 100 * acc.median) + " / " + fmt("%.0f%%", 100 * acc.worst)
               : std::string("-"))
       << " | "
       << (r.lod ? r.lod->near + " + " + r.lod->far + ": " + fmt("%.1fx", ls.model) + " / " +
                       (ls.measured > 0 ? fmt("%.1fx", ls.measured) : std::string("-"))
                 : std::string("-"))
       << " | " << (ten_lod ? "yes" : "no") << " | ";
    const StratifiedSpeedup st = stratified_speedup16(r);
    auto ratio = [](double x) { return x > 0 ? fmt("%.1fx", x) : std::string("-"); };
    const bool compared = st.ours_model_ns > 0 || st.ours_ns > 0;
    md << (st.label.empty() ? std::string("-")
           : compared       ? st.label + ": " + ratio(st.model) + " / " + ratio(st.measured)
                            : st.label + ": not reached")
       << " | ";
    const AdaptiveSpeedup as = adaptive_speedup16(r);
    const std::string ad_label = r.adaptive_ss ? std::to_string(r.adaptive_ss->near_samples) + "/" +
                                                     std::to_string(r.adaptive_ss->far_samples)
                                               : std::string();
    const bool ad_compared = as.model > 0 || as.measured > 0;
    md << (!r.adaptive_ss ? std::string("-")
           : ad_compared  ? ad_label + ": " + ratio(as.model) + " / " + ratio(as.measured)
                          : ad_label + ": not reached")
       << " |\n";
    with_ad += ad_compared;
    count_ad += as.measured >= 10;
    count_ad_model += as.model >= 10;
    with_ss += compared;
    count_ss += st.measured >= 10;
    count_ss_model += st.model >= 10;
    csv << r.scene << "," << r.nodes << "," << r.search_seconds << "," << r.finalize_seconds << ","
        << r.front.size() << "," << s16.msaa_error << "," << best << "," << s16.model << "," << s16.measured
        << "," << (ten ? 1 : 0) << "," << acc.median << "," << acc.worst << "," << ls.model << ","
        << ls.measured << "," << (ten_lod ? 1 : 0) << "," << st.label << "," << st.model << "," << st.measured
        << "," << ad_label << "," << as.model << "," << as.measured << "\n";
    const TenfoldGap g = tenfold_gap(r, s16, 10);
    gaps << "| " << r.scene << " | "
         << (g.at_error < 0 ? std::string("none") : r.front[g.at_error].label + fmt(" (%.1fx)", s16.model))
         << " | " << (g.at_error < 0 ? std::string("-") : pct(g.time_cut)) << " | "
         << (lod_at16(r, s16) && ls.model > 0
                 ? r.lod->near + " + " + r.lod->far + fmt(" (%.1fx): ", ls.model) + pct(1 - ls.model / 10)
                 : std::string("-"))
         << " | ";
    if (g.at_time < 0) {
      gaps << "none | - | - |\n";
      continue;
    }
    const Measured& m = r.front[g.at_time];
    double measured = NAN;
    for (const Measured& b : r.baselines)
      if (b.msaa == 16 && b.compiled_ms > 0 && m.compiled_ms > 0) measured = b.compiled_ms / m.compiled_ms;
    gaps << m.label << (std::isfinite(measured) ? fmt(" (%.1fx measured)", measured) : std::string()) << " | "
         << fmt("%.2f", m.error / g.msaa16_error) << " | " << pct(g.error_cut) << " |\n";
  }
  md << "\n"
     << reach_single << " of " << rs.size() << " scenes reach MSAA-16's error with one program; " << reach_lod
     << " with a footprint-LOD pair or one program.\n\n"
     << count_single << " of " << rs.size()
     << " scenes reach MSAA-16's error at >= 10x less model time with one program; " << count_lod
     << " with a footprint-LOD pair (tuner/lod_pair.hpp) or one program.\n";
  if (with_ss > 0)
    md << "\nAgainst the cheapest stratified supersampling in the shader at MSAA-16's error (ssN, a fixed "
          "pattern as GPU MSAA uses): "
       << count_ss_model << " (model) / " << count_ss << " (measured) of the " << with_ss
       << " scenes compared at >= 10x less time (one program or the LOD pair).\n";
  if (with_ad > 0)
    md << "\nAgainst footprint-adaptive stratified supersampling at MSAA-16's error (two sample counts "
          "chosen "
          "per pixel by the footprint, near/far samples in the column; tuner/adaptive_supersampling.hpp): "
       << count_ad_model << " (model) / " << count_ad << " (measured) of the " << with_ad
       << " scenes compared at >= 10x less time.\n";
  md << "\n## What >= 10x (model) at MSAA-16's error still needs\n\n"
        "Either side closes the gap: the model time of the fastest point (or of the footprint-LOD pair) at "
        "MSAA-16's error, or the error of the most accurate point already at >= 10x less model time (its "
        "measured speed-up in brackets).\n\n"
        "| scene | fastest point at MSAA-16's error | model time to cut | footprint-LOD pair: model time to "
        "cut | most accurate point at >= 10x | its error / MSAA-16's | error to cut |\n"
        "|---|---|---|---|---|---|---|\n"
     << gaps.str();
}

}  // namespace bl::tuner
