// See plots.hpp.
#include "plots.hpp"

#include <cmath>
#include <sstream>

#include "bandlimit/table.hpp"
#include "naive.hpp"
#include "plot.hpp"

namespace nbf {
namespace {

const char* const kColors[] = {"#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e", "#e6ab02"};

// Errors that are exactly 0 are drawn at 1e-17 (log axes).
double floor17(double e) {
  return e > 0 ? e : 1e-17;
}

}  // namespace

void plot_curves(const std::string& png) {
  std::ostringstream s;
  for (size_t p = 0; p < kCurveSigmas.size(); ++p) {
    const double sg = kCurveSigmas[p];
    std::vector<std::vector<double>> rows;
    for (int i = 0; i <= 1200; ++i) {
      const double x = -1.0 + 3.0 * i / 1200;
      std::vector<double> r = {x, x - std::floor(x)};
      for (int K : kCurveTerms) r.push_back(nb::naive::fourier_fract(x, sg, K));
      r.push_back(bl::gaussian::fract(x, sg));
      r.push_back(bl::box::fract(x, sg));
      r.push_back(bl::tent::fract(x, sg));
      rows.push_back(r);
    }
    s << nb::datablock("c" + std::to_string(p), rows);
  }
  s << "set terminal pngcairo size 1500,1350 font 'Sans,11'\n"
    << "set output '" << png << "'\n"
    << "set multiplot layout " << kCurveSigmas.size() << ",1 title 'fract smoothed with sigma: Dorn et al. "
    << "truncated Fourier series (K terms) against bl::gaussian/box/tent::fract' font ',14'\n"
    << "set grid\nset xrange [-1:2]\nset yrange [-0.25:1.25]\nset key outside right top\n"
    << "set xlabel 'x'\n";
  for (size_t p = 0; p < kCurveSigmas.size(); ++p) {
    s << "set title 'sigma = " << kCurveSigmas[p] << "'\n"
      << "plot $c" << p << " u 1:2 w l lw 1 lc rgb '#bbbbbb' t 'fract(x)'";
    for (size_t k = 0; k < kCurveTerms.size(); ++k)
      s << ", '' u 1:" << 3 + k << " w l lw 1.2 dt 2 lc rgb '" << kColors[k]
        << "' t 'series, K = " << kCurveTerms[k] << "'";
    const size_t c = 3 + kCurveTerms.size();
    s << ", '' u 1:" << c + 1 << " w l lw 1.5 lc rgb '#2b8cbe' t 'bl::box::fract'"
      << ", '' u 1:" << c + 2 << " w l lw 1.5 lc rgb '#74c476' t 'bl::tent::fract'"
      << ", '' u 1:" << c << " w l lw 2.5 lc rgb '#000000' t 'bl::gaussian::fract'\n";
  }
  s << "unset multiplot\n";
  nb::run_gnuplot(s.str());
}

void plot_errors(const std::string& png, const std::vector<Errors>& errs, const std::vector<Timings>& times) {
  std::ostringstream s;
  std::vector<std::vector<double>> byk, ours;
  for (size_t k = 0; k < kTerms.size(); ++k) {
    std::vector<double> r = {double(kTerms[k])};
    for (const Errors& e : errs) r.push_back(floor17(e.naive[k]));
    byk.push_back(r);
  }
  for (double K : {double(kTerms.front()), double(kTerms.back())}) {
    std::vector<double> r = {K};
    for (const Errors& e : errs) r.push_back(floor17(e.ours));
    ours.push_back(r);
  }
  s << nb::datablock("byk", byk) << nb::datablock("ours", ours);
  for (size_t i = 0; i < errs.size(); ++i) {
    std::vector<std::vector<double>> pareto;
    for (size_t k = 0; k < kTerms.size(); ++k)
      pareto.push_back({times[i].naive[k], floor17(errs[i].naive[k])});
    s << nb::datablock("p" + std::to_string(i), pareto);
    s << nb::datablock("o" + std::to_string(i), {{times[i].ours, floor17(errs[i].ours)},
                                                 {times[i].box, floor17(errs[i].box_vs_gauss)},
                                                 {times[i].tent, floor17(errs[i].tent_vs_gauss)}});
  }
  s << "set terminal pngcairo size 1700,700 font 'Sans,11'\n"
    << "set output '" << png << "'\n"
    << "set multiplot layout 1,2 title 'fract under the Gaussian: worst error over x against the 50-digit "
       "reference (errors of 0 drawn at 1e-17)' font ',13'\n"
    << "set logscale xy\nset grid\nset format y '10^{%L}'\nset yrange [1e-17:2]\n"
    << "set key at graph 0.98, 0.98 right top box opaque font ',10'\n"
    << "set title '(a) Dorn et al. series truncated after K terms (solid) vs bl::gaussian::fract (dashed)'\n"
    << "set xlabel 'K (terms)'\nset ylabel 'max |error| / max(1, |ref|)'\nset xrange [0.8:160]\n"
    << "plot ";
  for (size_t i = 0; i < errs.size(); ++i)
    s << (i ? ", " : "") << "$byk u 1:" << i + 2 << " w lp pt 7 ps 0.8 lw 1.5 lc rgb '" << kColors[i]
      << "' t 'sigma = " << errs[i].sigma << "', $ours u 1:" << i + 2 << " w l dt 2 lw 1.5 lc rgb '"
      << kColors[i] << "' notitle";
  s << "\n"
    << "set title '(b) accuracy against cost: series K = 1..128 (line), ours (filled circle), box (square), "
       "tent (triangle)'\n"
    << "set xlabel 'ns per call (double)'\nset xrange [*:*]\nset key off\nplot ";
  for (size_t i = 0; i < errs.size(); ++i)
    s << (i ? ", " : "") << "$p" << i << " u 1:2 w lp pt 6 ps 0.7 lc rgb '" << kColors[i] << "' notitle, $o"
      << i << " every ::0::0 u 1:2 w p pt 7 ps 2 lc rgb '" << kColors[i] << "' notitle, $o" << i
      << " every ::1::1 u 1:2 w p pt 5 ps 1.5 lc rgb '" << kColors[i] << "' notitle, $o" << i
      << " every ::2::2 u 1:2 w p pt 9 ps 1.5 lc rgb '" << kColors[i] << "' notitle";
  s << "\nunset multiplot\n";
  nb::run_gnuplot(s.str());
}

}  // namespace nbf
