// gnuplot scripts of the clamped_paper notebook: curves of an example's rules against the ground
// truth (and their errors), the densities of Figure 3, and MSE against the mu range (Table 1).
#pragma once

#include <string>
#include <vector>

#include "paper_examples.hpp"

namespace nb::clamped {

// One example: its evaluation on the plot grid and the plain function there.
struct Panel {
  std::string tag;  // "(a)", ...
  const clamped_paper::Example* example;
  const clamped_paper::Evaluation* eval;
};

// Values (top row) and |error| against the truth (bottom row), one column per panel.
std::string curves_script(const std::string& png, const std::string& title, const std::vector<Panel>& panels);

// Figure 3: the log-normal density of exp(X) and the Gaussians of the rules.
std::string densities_script(const std::string& png, const clamped_paper::Figure3& f);

// MSE against the half-width R of the mu range [-R, R], one panel per Table 1 function, with the
// paper's printed values as horizontal lines. mse[f][m][i] at rs[i], for the keys of `keys`.
std::string range_script(const std::string& png, const std::vector<clamped_paper::Example>& fns,
                         const std::vector<std::string>& keys, const std::vector<double>& rs,
                         const std::vector<std::vector<std::vector<double>>>& mse);

// The colour of a rule key (the paper's where it names one: adaptive blue, Yang-fract yellow, Rule 1
// red, Rule 2 yellow in Figs. 3-4 is drawn purple here to keep Yang-fract apart, Rule 3 magenta).
std::string colour(const std::string& key);

}  // namespace nb::clamped
