// See plots.hpp.
#include "plots.hpp"

#include <algorithm>
#include <cmath>

#include "notebook.hpp"
#include "plot.hpp"

namespace nb::clamped {

namespace cp = clamped_paper;

std::string colour(const std::string& key) {
  if (key == "adaptive") return "#1f77b4";
  if (key == "yang_fract") return "#e6b800";
  if (key == "rule1") return "#d62728";
  if (key == "rule2") return "#9467bd";
  if (key == "rule3") return "#e377c2";
  return "#000000";
}

// A rule key as a plot title (gnuplot's enhanced text would subscript after '_').
std::string pretty(const std::string& key) {
  return key == "yang_fract" ? "Yang-fract" : key;
}

std::string curves_script(const std::string& png, const std::string& title,
                          const std::vector<Panel>& panels) {
  std::string s;
  for (std::size_t p = 0; p < panels.size(); ++p) {
    const cp::Evaluation& ev = *panels[p].eval;
    std::vector<std::vector<double>> rows;
    for (std::size_t i = 0; i < ev.mu.size(); ++i) {
      std::vector<double> r = {ev.mu[i], panels[p].example->f(ev.mu[i]), ev.truth[i]};
      for (const auto& v : ev.values) r.push_back(v[i]);
      for (const auto& v : ev.values) r.push_back(std::max(1e-9, std::fabs(v[i] - ev.truth[i])));
      rows.push_back(r);
    }
    s += nb::datablock("D" + std::to_string(p), rows);
  }
  const int cols = static_cast<int>(panels.size());
  s += "set terminal pngcairo size " + std::to_string(std::max(900, 520 * cols)) +
       ",1000 font 'sans,10'\nset output '" + png + "'\n";
  s += "set multiplot layout 2," + std::to_string(cols) + " title '" + title + "'\n";
  s += "set xlabel 'mu_X'\n";
  for (const Panel& p : panels) {
    const cp::Example& e = *p.example;
    const std::string d = "$D" + std::to_string(&p - panels.data());
    s += "set title '" + p.tag + " " + e.title + ", sigma_X^2 = " + nb::num(e.sigma * e.sigma) + "'\n";
    s += "unset logscale y\nset format y '%g'\nset yrange [*:*]\nset ylabel 'smoothed value'\n"
         "set key below font 'sans,8'\n";
    s += "plot " + d + " u 1:2 w l lc rgb '#aaaaaa' t 'f (not smoothed)', " + d +
         " u 1:3 w l lw 3 dt 2 lc rgb '#000000' t 'ground truth (quadrature)'";
    for (std::size_t m = 0; m < e.methods.size(); ++m)
      s += ", " + d + " u 1:" + std::to_string(4 + m) + " w l lw 1.5 lc rgb '" + colour(e.methods[m].key) +
           "' t '" + e.methods[m].label + "'";
    s += "\n";
  }
  for (const Panel& p : panels) {
    const cp::Example& e = *p.example;
    const std::string d = "$D" + std::to_string(&p - panels.data());
    const std::size_t n = e.methods.size();
    s += "set title '" + p.tag + " |error| against the ground truth'\n";
    s += "set logscale y\nset format y '10^{%L}'\nset yrange [1e-9:10]\nset ylabel '|error|'\n"
         "set key inside top right font 'sans,8'\n";
    s += "plot ";
    for (std::size_t m = 0; m < n; ++m)
      s += std::string(m ? ", " : "") + d + " u 1:" + std::to_string(4 + n + m) + " w l lw 1.5 lc rgb '" +
           colour(e.methods[m].key) + "' t '" + pretty(e.methods[m].key) + "'";
    s += "\n";
  }
  s += "unset multiplot\n";
  return s;
}

std::string densities_script(const std::string& png, const cp::Figure3& f) {
  const std::vector<std::string> keys = {"adaptive", "rule1", "rule2"};
  const std::vector<std::string> labels = {"adaptive Gaussian [YB18]", "Rule 1 (renormalized on [0, inf))",
                                           "Rule 2 (mode fit)"};
  std::vector<std::vector<double>> rows;
  for (const double y : cp::grid(-0.5, 4, 901)) {
    std::vector<double> r = {y, f.lognormal(y)};
    for (const auto& k : keys) r.push_back(f.density(k, y));
    rows.push_back(r);
  }
  std::string s = nb::datablock("D", rows);
  s += "set terminal pngcairo size 900,560 font 'sans,10'\nset output '" + png + "'\n";
  s += "set title 'Figure 3: density of Y = exp(X), X from N(0, 0.5^2)'\nset xlabel 'y'\nset ylabel "
       "'density'\n";
  s += "set key top right\nset xrange [-0.5:4]\n";
  s += "set arrow from " + nb::num(cp::kDensityLo) + ",graph 0 to " + nb::num(cp::kDensityLo) +
       ",graph 1 nohead dt 3 lc rgb '#888888'\n";
  s += "plot $D u 1:2 w l lw 3 dt 2 lc rgb '#000000' t 'log-normal (exact)'";
  for (std::size_t k = 0; k < keys.size(); ++k)
    s += ", $D u 1:" + std::to_string(3 + k) + " w l lw 1.5 lc rgb '" + colour(keys[k]) + "' t '" +
         labels[k] + "'";
  s += "\n";
  return s;
}

std::string range_script(const std::string& png, const std::vector<cp::Example>& fns,
                         const std::vector<std::string>& keys, const std::vector<double>& rs,
                         const std::vector<std::vector<std::vector<double>>>& mse) {
  std::string s;
  for (std::size_t f = 0; f < fns.size(); ++f) {
    std::vector<std::vector<double>> rows;
    for (std::size_t i = 0; i < rs.size(); ++i) {
      std::vector<double> r = {rs[i]};
      for (std::size_t k = 0; k < keys.size(); ++k) r.push_back(mse[f][k][i]);
      rows.push_back(r);
    }
    s += nb::datablock("R" + std::to_string(f), rows);
  }
  s += "set terminal pngcairo size 1500,480 font 'sans,10'\nset output '" + png + "'\n";
  s += "set multiplot layout 1," + std::to_string(fns.size()) +
       " title 'Table 1: MSE over mu_X in [-R, R] against R (solid), the paper''s printed MSE (dashed)'\n";
  s += "set logscale y\nset format y '10^{%L}'\nset xlabel 'R'\nset ylabel 'MSE'\nset key bottom right "
       "font 'sans,8'\n";
  s += "set xrange [" + nb::num(rs.front()) + ":" + nb::num(rs.back()) + "]\n";
  for (std::size_t f = 0; f < fns.size(); ++f) {
    s += "set title '" + fns[f].title + "'\nplot ";
    bool first = true;
    for (std::size_t k = 0; k < keys.size(); ++k) {
      s += std::string(first ? "" : ", ") + "$R" + std::to_string(f) + " u 1:" + std::to_string(2 + k) +
           " w l lw 2 lc rgb '" + colour(keys[k]) + "' t '" + pretty(keys[k]) + "'";
      first = false;
      const auto it = fns[f].paper_mse.find(keys[k]);
      if (it != fns[f].paper_mse.end())
        s += ", " + nb::num(it->second) + " w l dt 2 lw 1.5 lc rgb '" + colour(keys[k]) + "' t '" +
             pretty(keys[k]) + ", paper'";
    }
    s += "\n";
  }
  s += "unset multiplot\n";
  return s;
}

}  // namespace nb::clamped
