// See plots.hpp.
#include "plots.hpp"

#include <cmath>

#include "notebook.hpp"
#include "plot.hpp"

namespace nb::acc {
namespace {

const char* kFamilyColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2"};
const int kPointType[kWays] = {2, 6, 6, 6, 7, 7};  // plain x, MC open circles, smoothed filled
const double kPointSize[kWays] = {0.7, 0.5, 0.8, 1.1, 0.7, 0.7};

double rel(double e, double scale) {
  return scale > 0 ? std::max(1e-10, e / scale) : NAN;
}

// A name inside a single-quoted gnuplot string, '_' escaped for enhanced text.
std::string esc(const std::string& name) {
  std::string out;
  for (const char c : name) out += c == '_' ? std::string("\\_") : std::string(1, c);
  return out;
}

}  // namespace

std::string entries_script(const std::string& png, const std::vector<EntryRow>& rows,
                           const std::vector<FamilyStats>& fams) {
  std::string s;
  for (std::size_t f = 0; f < fams.size(); ++f) {
    std::vector<std::vector<double>> d;
    for (const EntryRow& r : rows) {
      if (r.family != fams[f].family) continue;
      d.push_back({r.plain_ns, rel(r.err_plain, r.ref_rms), r.mc_ns[0], rel(r.err_mc[0], r.ref_rms),
                   r.mc_ns[1], rel(r.err_mc[1], r.ref_rms), r.mc_ns[2], rel(r.err_mc[2], r.ref_rms),
                   r.f32_smoothed_ns, rel(r.f32_smoothed_err, r.ref_rms)});
    }
    s += nb::datablock("E" + std::to_string(f), d);
    std::vector<std::vector<double>> m;
    for (int w = 0; w < kSmoothed; ++w) m.push_back({fams[f].ns[w], std::max(1e-10, fams[f].err[w])});
    s += nb::datablock("M" + std::to_string(f), m);
  }
  s += "set terminal pngcairo size 1500,640 font 'sans,10'\nset output '" + png + "'\n";
  s += "set multiplot layout 1,2 title 'Every table entry: time per call against relative RMS error "
       "(bench\\_table, "
       "double; float for the smoothed points)'\n";
  s +=
      "set logscale xy\nset format y '10^{%L}'\nset xlabel 'ns per call'\nset ylabel 'RMS error / RMS of the "
      "smoothed value'\nset yrange [1e-10:10]\nset key outside right font 'sans,9'\nset grid\n";
  s += "set title 'entries (x plain, o MC-4/16/64 growing, * smoothed float; errors of 0 drawn at "
       "10^{-10})'\nplot ";
  for (std::size_t f = 0; f < fams.size(); ++f) {
    const std::string c = kFamilyColours[f % 7], e = "$E" + std::to_string(f);
    for (int w = 0; w < kSmoothed; ++w) {
      const int x = 1 + 2 * w;
      s += std::string(f || w ? ", " : "") + e + " u " + std::to_string(x) + ":" + std::to_string(x + 1) +
           " w p pt " + std::to_string(kPointType[w]) + " ps " + nb::num(kPointSize[w]) + " lc rgb '" + c +
           "' " + (w == 0 ? "t '" + fams[f].family + "'" : "notitle");
    }
  }
  s += "\nset title 'family medians: plain -> MC-4 -> MC-16 -> MC-64, and the smoothed entry (float)'\nplot ";
  for (std::size_t f = 0; f < fams.size(); ++f) {
    const std::string c = kFamilyColours[f % 7], m = "$M" + std::to_string(f);
    s += std::string(f ? ", " : "") + m + " every ::1::3 u 1:2 w lp pt 6 lw 1.5 lc rgb '" + c + "' t '" +
         fams[f].family + "', " + m + " every ::0::0 u 1:2 w p pt 2 ps 1.5 lc rgb '" + c + "' notitle, " + m +
         " every ::4::4 u 1:2 w p pt 7 ps 1.5 lc rgb '" + c + "' notitle";
  }
  s += "\nunset multiplot\n";
  return s;
}

std::string speedup_script(const std::string& png, const Suite& su) {
  std::vector<std::vector<double>> d;
  std::string xtics, labels;
  for (std::size_t i = 0; i < su.scenes.size(); ++i) {
    const auto& r = su.scenes[i];
    const bl::tuner::Speedup s16 = speedup_at(r, 16);
    double model = NAN, eval = NAN, lmodel = NAN, leval = NAN;
    if (s16.front_index >= 0) {
      model = s16.model;
      eval = s16.measured;
    } else {
      int level = 0;
      for (const bl::tuner::Speedup& s : bl::tuner::speedups(r))
        if (s.front_index >= 0 && s.msaa < 16 && s.msaa > level) {
          level = s.msaa;
          lmodel = s.model;
          leval = s.measured;
        }
      if (level)
        labels += "set label 'MSAA-" + std::to_string(level) + "' at " + std::to_string(i) + "," +
                  nb::num(lmodel) + " offset 1,0 font 'sans,8'\n";
    }
    d.push_back({double(i), model, eval, lmodel, leval});
    xtics += std::string(i ? ", " : "") + "'" + esc(r.scene) + "' " + std::to_string(i);
  }
  std::string s = nb::datablock("S", d);
  s += "set terminal pngcairo size 1300,620 font 'sans,10'\nset output '" + png + "'\n";
  s += "set title 'Speed-up of the tuned front against MSAA at equal error (filled: at MSAA-16''s error; "
       "open: "
       "scene does not reach it, speed-up at the highest MSAA level it reaches, labelled)'\n";
  s += "set logscale y\nset ylabel 'MSAA time / front point time'\nset xtics (" + xtics +
       ") rotate by 45 right font 'sans,8'\nset xrange [-0.5:" +
       std::to_string(double(su.scenes.size()) - 0.5) + "]\nset grid y\nset key top left\n" + labels;
  s += "plot $S u 1:2 w p pt 7 ps 1.3 lc rgb '#d62728' t 'cost model', $S u 1:3 w p pt 5 ps 1.1 lc rgb "
       "'#1f77b4' t 'evaluator (measured)', $S u 1:4 w p pt 6 ps 1.3 lc rgb '#d62728' notitle, $S u 1:5 w p "
       "pt 4 "
       "ps 1.1 lc rgb '#1f77b4' notitle, 1 w l dt 2 lc rgb '#000000' t '1x', 10 w l dt 3 lc rgb '#2ca02c' t "
       "'10x (issue target)'\n";
  return s;
}

std::string fronts_script(const std::string& png, const Suite& su) {
  std::string s, plot;
  for (std::size_t i = 0; i < su.scenes.size(); ++i) {
    const auto& r = su.scenes[i];
    const bl::tuner::Measured* m16 = msaa(r, 16);
    if (!m16) continue;
    std::vector<std::vector<double>> f, l;
    for (const auto& p : r.front) f.push_back({p.model_ns / m16->model_ns, p.error / m16->error});
    for (const auto& b : r.baselines)
      if (b.msaa > 0) l.push_back({b.model_ns / m16->model_ns, b.error / m16->error});
    s += nb::datablock("F" + std::to_string(i), f) + nb::datablock("L" + std::to_string(i), l);
    plot += std::string(plot.empty() ? "" : ", ") + "$L" + std::to_string(i) +
            " u 1:2 w l lw 0.6 lc rgb '#bbbbbb' notitle, $F" + std::to_string(i) +
            " u 1:2 w lp pt 7 ps 0.5 lt " + std::to_string(i + 1) + " t '" + esc(r.scene) + "'";
  }
  s += "set terminal pngcairo size 1300,760 font 'sans,10'\nset output '" + png + "'\n";
  s += "set title 'Tuned fronts of every scene, normalized by the scene''s MSAA-16 (grey: its MSAA 2..32 "
       "ladder; "
       "cost-model time)'\n";
  s += "set logscale xy\nset xlabel 'time / MSAA-16 time'\nset ylabel 'RMS error / MSAA-16 RMS error'\n";
  s += "set key outside right font 'sans,8'\nset grid\nset object circle at 1,1 size char 0.6 fc rgb "
       "'#000000' "
       "fs solid\nset arrow from 1,graph 0 to 1,graph 1 nohead dt 3\nset arrow from graph 0,first 1 to graph "
       "1,first 1 nohead dt 3\n";
  s += "plot " + plot + "\n";
  return s;
}

}  // namespace nb::acc
