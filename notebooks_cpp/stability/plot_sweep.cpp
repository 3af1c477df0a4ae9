// See plot_sweep.hpp.
#include "plot_sweep.hpp"

#include <cmath>
#include <sstream>

#include "plot.hpp"

namespace nbs {
namespace {

// Log axes: exact zeros at 1e-18, NaN/inf (and anything above) at the top, 10.
double clip(double e) {
  if (std::isnan(e)) return NAN;
  if (!(e < 10)) return 10;
  return e > 1e-18 ? e : 1e-18;
}

const char* const kSeries[] = {"w l lw 2 lc rgb '#d62728' t 'naive, double'",
                               "w l lw 2 lc rgb '#1f77b4' t 'emitted, double'",
                               "w l lw 1.5 dt 2 lc rgb '#ff9896' t 'naive, float'",
                               "w l lw 1.5 dt 2 lc rgb '#9ecae1' t 'emitted, float'"};

}  // namespace

void plot_sweep(const std::string& png, const std::vector<Entry>& entries,
                const std::vector<std::vector<Point>>& results) {
  std::ostringstream s;
  for (size_t i = 0; i < entries.size(); ++i) {
    std::vector<std::vector<double>> rows;
    for (const Point& p : results[i])
      rows.push_back({p.sigma, clip(p.naive_d), clip(p.emitted_d), clip(p.naive_f), clip(p.emitted_f)});
    s << nb::datablock("d" + std::to_string(i), rows);
  }
  const int cols = 4, nrows = static_cast<int>((entries.size() + cols - 1) / cols);
  const double h = 0.94 / nrows;
  s << "set terminal pngcairo size 1800," << 360 * nrows + 80 << " font 'Sans,10'\n"
    << "set output '" << png << "'\n"
    << "set multiplot title 'worst |error| / max(1, |ref|) against sigma: naive textbook form vs emitted "
       "table entry (NaN/inf drawn at 10, exact 0 at 1e-18; grey: bounds 1e-9 double, 2e-5 float)' font "
       "',13'\n"
    << "set logscale xy\nset grid\nset format x '10^{%L}'\nset format y '10^{%L}'\n"
    << "set xrange [1e-12:1e6]\nset yrange [1e-18:20]\nset xtics 1e-12, 1e3, 1e6\nset ytics 1e-18, 1e3, 10\n"
    << "set size " << 1.0 / cols << "," << h << "\nunset key\n";
  for (size_t i = 0; i < entries.size(); ++i) {
    const int r = static_cast<int>(i) / cols, c = static_cast<int>(i) % cols;
    s << "set origin " << c * (1.0 / cols) << "," << 0.94 - (r + 1) * h << "\n"
      << "set title '" << entries[i].name << "' font ',12' noenhanced\n"
      << "plot 1e-9 w l lc rgb '#aaaaaa' notitle, 2e-5 w l dt 3 lw 1.5 lc rgb '#888888' notitle";
    for (int k = 0; k < 4; ++k) s << ", $d" << i << " u 1:" << k + 2 << " " << kSeries[k];
    s << "\n";
  }
  // The legend in the free panel (or below the last row).
  const size_t slot = entries.size();
  s << "set origin " << (slot % cols) * (1.0 / cols) << "," << 0.94 - (slot / cols + 1) * h << "\n"
    << "unset title\nunset border\nunset tics\nunset grid\nunset logscale\nset xrange [0:1]\nset yrange "
       "[0:1]\n"
    << "set key center center vertical font ',12'\nplot ";
  for (int k = 0; k < 4; ++k) s << (k ? ", " : "") << "2 " << kSeries[k];
  s << "\nunset multiplot\n";
  nb::run_gnuplot(s.str());
}

}  // namespace nbs
