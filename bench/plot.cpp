// gnuplot script for the accuracy-cost plot; see plot.hpp. Columns refer to report.cpp's CSV.
#include "plot.hpp"

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace blb {
namespace {

// Point style and legend title per series: plain, MC-4, MC-16, MC-64, float smoothed, smoothed.
const char* const kStyles[] = {
    "w p pt 2 ps 1.0 lc rgb '#000000' t 'plain f (no smoothing)'",
    "w p pt 8 ps 1.0 lc rgb '#74a9cf' t 'MC-4'",
    "w p pt 10 ps 1.0 lc rgb '#2b8cbe' t 'MC-16'",
    "w p pt 12 ps 1.0 lc rgb '#034e7b' t 'MC-64'",
    "w p pt 5 ps 0.8 lc rgb '#ff7f0e' t 'smoothed, float (measured error)'",
    "w p pt 7 ps 0.9 lc rgb '#d62728' t 'smoothed, double (error 0 by construction, drawn at "
    "1e-17)'"};

std::string script(const std::string& csv, const std::string& png,
                   const std::vector<std::string>& panels) {
  std::ostringstream s;
  std::string fams;
  for (const std::string& f : panels) fams += (fams.empty() ? "" : " ") + f;
  s << "set terminal pngcairo size 1800,1150 font 'Sans,11'\n"
    << "set output '" << png << "'\n"
    << "set datafile separator ','\n"
    << "set logscale xy\n"
    << "set format y '10^{%L}'\n"
    << "set yrange [1e-18:*]\n"
    << "set grid\n"
    << "set xlabel 'time per call (ns, log scale)'\n"
    << "set ylabel 'RMS error vs exact smoothed value'\n"
    << "floor = 1e-17\n"
    // Exact zeros go to the floor; NaN stays undefined (not drawn).
    << "e(c) = column(c) > 0 ? column(c) : (column(c) == 0 ? floor : NaN)\n"
    << "in(fam, c) = strcol(3) eq fam ? column(c) : NaN\n"
    << "f = '" << csv << "'\n"
    << "set multiplot title 'bandlimit: RMS error vs time per call, every registry entry "
       "(double; float smoothed in orange)' font ',14'\n"
    << "set size 0.333,0.43\n"
    << "unset key\n"
    << "i = 0\n"
    << "do for [fam in '" << fams << "'] {\n"
    << "  set origin (i % 3) * 0.333, (i < 3 ? 0.5 : 0.07)\n"
    << "  i = i + 1\n"
    << "  set title fam font ',13'\n"
    << "  plot f every ::1 u (in(fam, 4)):(e(10)) " << kStyles[0] << ", \\\n"
    << "       '' every ::1 u (in(fam, 6)):(e(11)) " << kStyles[1] << ", \\\n"
    << "       '' every ::1 u (in(fam, 7)):(e(12)) " << kStyles[2] << ", \\\n"
    << "       '' every ::1 u (in(fam, 8)):(e(13)) " << kStyles[3] << ", \\\n"
    << "       '' every ::1 u (in(fam, 16)):(e(17)) " << kStyles[4] << ", \\\n"
    << "       '' every ::1 u (in(fam, 5)):(floor) " << kStyles[5] << "\n"
    << "}\n"
    // The legend: a strip along the bottom with nothing in range but the key.
    << "set origin 0, 0\nset size 1, 0.06\nunset title\nunset border\nunset tics\n"
    << "unset xlabel\nunset ylabel\nunset grid\nunset logscale\n"
    << "set xrange [0:1]\nset yrange [0:1]\n"
    << "set key center center horizontal maxrows 1 font ',11' samplen 1 width 2\n"
    << "plot 2 " << kStyles[0] << ", 2 " << kStyles[1] << ", 2 " << kStyles[2] << ", 2 "
    << kStyles[3] << ", 2 " << kStyles[4] << ", 2 " << kStyles[5] << "\n"
    << "unset multiplot\n";
  return s.str();
}

}  // namespace

void write_plot(const std::string& csv_path, const std::string& png_path,
                const std::vector<std::string>& panel_families) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0)
    throw std::runtime_error(
        "bench_table: gnuplot not found on PATH (apt-get install gnuplot-nox); the .md and .csv "
        "were written, the plot " +
        png_path + " was not");
  FILE* p = popen("gnuplot", "w");
  if (!p) throw std::runtime_error("bench_table: cannot start gnuplot");
  const std::string s = script(csv_path, png_path, panel_families);
  std::fwrite(s.data(), 1, s.size(), p);
  if (pclose(p) != 0) throw std::runtime_error("bench_table: gnuplot failed writing " + png_path);
}

}  // namespace blb
