#include "tuner/report.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

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

}  // namespace

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
        s.measured = b.eval_ms / r.front[i].eval_ms;
        break;
      }
    out.push_back(s);
  }
  return out;
}

void write_scene_report(const SceneResult& r, const std::string& dir) {
  std::filesystem::create_directories(dir);
  const double px = r.pixels;
  {
    std::ofstream csv(dir + "/front.csv");
    csv << "kind,label,model_ns_per_pixel,model_ms_per_frame,eval_ms_per_frame,glsl_ms_per_frame,search_"
           "error,"
           "rms_display,psnr_db,nonfinite_pixels,out_of_range_pixels,refined,rule_mix,schedule,graph_hash\n";
    auto row = [&](const char* kind, const Measured& m) {
      csv << kind << "," << m.label << "," << m.model_ns << "," << m.model_ns * px * 1e-6 << "," << m.eval_ms
          << "," << m.glsl_ms << "," << m.search_error << "," << m.error << "," << m.psnr << ","
          << m.nonfinite << "," << m.out_of_range << "," << (m.refined ? 1 : 0) << ",\"" << mix_text(m)
          << "\",\"" << m.schedule << "\"," << r.graph_hash << "\n";
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
    << "msaa(c) = strcol(2)[1:4] eq 'msaa' ? column(c) : NaN\n"
    << "set multiplot layout 1,2 title '" << r.scene
    << ": Pareto front vs MSAA, plain, all-Dorn, all-Gaussian'\n";
  for (int panel = 0; panel < 2; ++panel) {
    const int c = panel == 0 ? 3 : 5;
    g << "set xlabel '" << (panel == 0 ? "cost model (ns per pixel)" : "measured evaluator (ms per frame)")
      << "'\n"
      << "plot f every ::1 u (front(" << c << ")):(front(8)) w lp pt 7 lc rgb '#d62728' t 'tuned front', \\\n"
      << "  '' every ::1 u (msaa(" << c << ")):(msaa(8)) w lp pt 5 lc rgb '#1f77b4' t 'MSAA 2..32', \\\n"
      << "  '' every ::1 u (msaa(" << c << ")):(msaa(8)):2 w labels offset 0,1 notitle, \\\n"
      << "  '' every ::1 u (lab('plain'," << c
      << ")):(lab('plain',8)) w p pt 9 ps 1.5 lc rgb '#000000' t 'plain', \\\n"
      << "  '' every ::1 u (lab('dorn'," << c
      << ")):(lab('dorn',8)) w p pt 11 ps 1.5 lc rgb '#2ca02c' t 'all Dorn', \\\n"
      << "  '' every ::1 u (lab('gaussian'," << c
      << ")):(lab('gaussian',8)) w p pt 13 ps 1.5 lc rgb '#ff7f0e' t "
         "'all adaptive Gaussian'\n";
  }
  g << "unset multiplot\n";
  const bool plotted = run_gnuplot(g.str());

  std::ofstream md(dir + "/report.md");
  md << "# Tuning " << r.scene << "\n\n"
     << "DAG nodes " << r.nodes << ", genes " << r.genes << ", " << r.frames << " frame(s) of " << r.pixels
     << " pixels. Search " << fmt("%.1f", r.search_seconds) << " s (" << r.evaluations
     << " distinct candidates), finalize " << fmt("%.1f", r.finalize_seconds) << " s.\n\n"
     << (plotted ? "![Pareto front](pareto.png)\n\n" : "(gnuplot not found: no plot)\n\n")
     << "Times: *model* = cost model (ns per pixel, and ms per frame = ns x pixels); *eval* = batch "
        "evaluator "
        "(render_smoothed, all threads) ms per frame; *GLSL* = emitted GLSL on "
     << (r.gl_renderer.empty() ? "(no GL driver: not measured)" : r.gl_renderer)
     << " ms per frame. MSAA n is n evaluations of the plain program (model and measured times are n x "
        "plain's). "
        "Errors: RMS in display space over every pixel of every frame, on the unclamped display curve "
        "(a value outside [0, 1] counts with its distance, a NaN/inf channel as 1; docs/runtime.md); "
        "*NaN px* / *range px*: pixels (all frames) with a NaN/inf channel / a channel outside [0, 1] "
        "widened to the ground truth's range. "
     << (r.rejected_nonfinite >= 0
             ? "Search: " + std::to_string(r.rejected_nonfinite) +
                   " evaluation(s) infeasible for NaN/inf on the sampled pixels (error +inf)."
             : std::string())
     << "\n\n"
     << "| point | model ns/px | model ms/frame | eval ms/frame | GLSL ms/frame | search error | RMS | PSNR "
        "dB | NaN px | range px | NM "
        "| rule mix |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  auto row = [&](const Measured& m) {
    md << "| " << m.label << " | " << fmt("%.1f", m.model_ns) << " | "
       << fmt("%.3f", m.model_ns * r.pixels * 1e-6) << " | " << fmt("%.3f", m.eval_ms) << " | "
       << glsl_text(m.glsl_ms) << " | "
       << (std::isnan(m.search_error) ? std::string("-") : fmt("%.5f", m.search_error)) << " | "
       << fmt("%.5f", m.error) << " | " << fmt("%.2f", m.psnr) << " | " << m.nonfinite << " | "
       << m.out_of_range << " | " << (m.refined ? "yes" : "") << " | " << mix_text(m) << " |\n";
  };
  for (const Measured& m : r.front) row(m);
  md << "| **baselines** | | | | | | | | | | | |\n";
  for (const Measured& m : r.baselines) row(m);
  md << "\n## Speed-up against MSAA at equal error\n\n| MSAA | its RMS | fastest front point at <= that "
        "error | "
        "speed-up (model) | speed-up (evaluator) |\n|---|---|---|---|---|\n";
  for (const Speedup& s : speedups(r)) {
    md << "| " << s.msaa << " | " << fmt("%.5f", s.msaa_error) << " | ";
    if (s.front_index < 0)
      md << "none reaches it | - | - |\n";
    else
      md << r.front[s.front_index].label << " | " << fmt("%.1fx", s.model) << " | "
         << fmt("%.1fx", s.measured) << " |\n";
  }
  md << "\nImages: `front*_vs_truth_msaa.png` (frame 0: ground truth | variant | MSAA of the nearest model "
        "time). Full schedules (node:rule) are in front.csv.\n";
}

void write_suite_summary(const std::vector<SceneResult>& rs, const std::string& dir) {
  std::filesystem::create_directories(dir);
  std::ofstream md(dir + "/summary.md"), csv(dir + "/summary.csv");
  csv << "scene,nodes,search_s,finalize_s,front_size,msaa16_error,best_error,speedup16_model,speedup16_eval,"
         "reaches_10x\n";
  md << "# Tuning summary\n\n| scene | nodes | search s | front | MSAA-16 RMS | best RMS | time at MSAA-16 "
        "error "
        "(model / eval speed-up) | >= 10x |\n|---|---|---|---|---|---|---|---|\n";
  for (const SceneResult& r : rs) {
    double best = INFINITY;
    for (const Measured& m : r.front) best = std::min(best, m.error);
    Speedup s16;
    for (const Speedup& s : speedups(r))
      if (s.msaa == 16) s16 = s;
    const bool ten = s16.front_index >= 0 && s16.model >= 10;
    md << "| " << r.scene << " | " << r.nodes << " | " << fmt("%.1f", r.search_seconds) << " | "
       << r.front.size() << " | " << fmt("%.5f", s16.msaa_error) << " | " << fmt("%.5f", best) << " | "
       << (s16.front_index < 0 ? std::string("not reached")
                               : fmt("%.1fx", s16.model) + " / " + fmt("%.1fx", s16.measured))
       << " | " << (ten ? "yes" : "no") << " |\n";
    csv << r.scene << "," << r.nodes << "," << r.search_seconds << "," << r.finalize_seconds << ","
        << r.front.size() << "," << s16.msaa_error << "," << best << "," << s16.model << "," << s16.measured
        << "," << (ten ? 1 : 0) << "\n";
  }
}

}  // namespace bl::tuner
