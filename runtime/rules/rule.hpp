// Approximation rules (the "schedule"): one per DAG node, chosen by hand or by the tuner.
// A value is a random variable with mean and variance; a rule maps the input (mean, variance) pairs
// of a node to its output pair. See docs/rules.md for each rule's formulas.
#pragma once

#include <string>
#include <vector>

namespace bl::rules {

enum class Kind {
  None,        // plain: mean = f(means); variance 0 (all-None is the plain shader, 1 sample)
  Dorn,        // Dorn et al. 2015 as improved by Yang & Barnes 4.3: Gaussian mean, heuristic sd
  Gaussian,    // adaptive Gaussian (Yang & Barnes 4.4), correlation per `rho`
  MonteCarlo,  // n Gaussian samples of the inputs (Yang & Barnes 4.5)
  Box,         // compact box kernel of the same sd (with singularity truncation)
  Tent,        // compact tent kernel
  Rule1,       // renormalized kernel in the clamped domain (Li et al. 2020), kernel per `kernel`
  Rule2,       // mode fit (Li et al. 2020)
  Rule3,       // Taylor in the clamped domain (Li et al. 2020)
};

// Correlation of a binary node's inputs: 0, a constant, the normalised dot product of the inputs'
// screen gradients (Yang & Barnes), or the linearised covariance sigma_px^2 (ga . gb) / (sa sb).
enum class Rho { Zero, Constant, Gradient, Covariance };

struct Rule {
  Kind kind = Kind::None;
  Rho rho = Rho::Zero;
  double rho_value = 0;        // for Rho::Constant
  int samples = 0;             // for MonteCarlo: 2, 4, 8, 16 or 32
  std::string kernel = "box";  // for Rule1: "box" | "tent" | "gaussian"
  double sigma_scale = 1;      // multiplies the input sd the rule smooths with (Nelder-Mead tunes it)

  bool operator==(const Rule& o) const;
};

// Text form used in schedules, reports and the CLI: "none", "dorn", "gaussian", "gaussian:rho=grad",
// "gaussian:rho=0.3", "gaussian:rho=cov", "mc8", "box", "tent", "rule1:tent", "rule2", "rule3", with an
// optional
// "@1.25" sd scale suffix. parse_rule throws std::invalid_argument naming the bad text.
std::string to_string(const Rule& r);
Rule parse_rule(const std::string& text);
const char* kind_name(Kind k);

// Every rule the search may assign (each MC count and rho mode), in a fixed order.
std::vector<Rule> all_rules();

}  // namespace bl::rules
