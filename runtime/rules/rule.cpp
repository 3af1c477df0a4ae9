#include "rules/rule.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace bl::rules {

bool Rule::operator==(const Rule& o) const {
  return kind == o.kind && rho == o.rho && rho_value == o.rho_value && samples == o.samples &&
         kernel == o.kernel && sigma_scale == o.sigma_scale;
}

const char* kind_name(Kind k) {
  switch (k) {
    case Kind::None:
      return "none";
    case Kind::Dorn:
      return "dorn";
    case Kind::Gaussian:
      return "gaussian";
    case Kind::MonteCarlo:
      return "mc";
    case Kind::Box:
      return "box";
    case Kind::Tent:
      return "tent";
    case Kind::Rule1:
      return "rule1";
    case Kind::Rule2:
      return "rule2";
    case Kind::Rule3:
      return "rule3";
  }
  return "?";
}

namespace {
// The shortest decimal that reads back as the same double ("0.54", not "0.54000000000000004").
std::string shortest(double v) {
  for (int p = 1; p <= 17; ++p) {
    std::ostringstream os;
    os.precision(p);
    os << v;
    if (std::stod(os.str()) == v) return os.str();
  }
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}
}  // namespace

std::string to_string(const Rule& r) {
  std::ostringstream os;
  if (r.kind == Kind::MonteCarlo) {
    os << "mc" << r.samples;
  } else {
    os << kind_name(r.kind);
  }
  if (r.kind == Kind::Gaussian && r.rho == Rho::Gradient) os << ":rho=grad";
  if (r.kind == Kind::Gaussian && r.rho == Rho::Covariance) os << ":rho=cov";
  if (r.kind == Kind::Gaussian && r.rho == Rho::Constant) os << ":rho=" << shortest(r.rho_value);
  if (r.kind == Kind::Rule1) os << ":" << r.kernel;
  if (r.sigma_scale != 1) os << "@" << shortest(r.sigma_scale);
  return os.str();
}

namespace {
[[noreturn]] void bad(const std::string& text, const std::string& why) {
  throw std::invalid_argument("rule '" + text + "': " + why);
}
double number(const std::string& text, const std::string& s) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(s, &used);
  } catch (const std::exception&) {
    bad(text, "'" + s + "' is not a number");
  }
  if (used != s.size() || !std::isfinite(v)) bad(text, "'" + s + "' is not a finite number");
  return v;
}
}  // namespace

Rule parse_rule(const std::string& text) {
  Rule r;
  std::string s = text;
  const auto at = s.find('@');
  if (at != std::string::npos) {
    r.sigma_scale = number(text, s.substr(at + 1));
    if (!(r.sigma_scale >= 0)) bad(text, "the sd scale must be >= 0");
    s = s.substr(0, at);
  }
  std::string head = s, opt;
  const auto colon = s.find(':');
  if (colon != std::string::npos) {
    head = s.substr(0, colon);
    opt = s.substr(colon + 1);
  }
  if (head.rfind("mc", 0) == 0) {
    r.kind = Kind::MonteCarlo;
    const double n = number(text, head.substr(2));
    r.samples = static_cast<int>(n);
    if (n != r.samples ||
        (r.samples != 2 && r.samples != 4 && r.samples != 8 && r.samples != 16 && r.samples != 32))
      bad(text, "Monte Carlo takes 2, 4, 8, 16 or 32 samples");
  } else {
    bool found = false;
    for (Kind k : {Kind::None, Kind::Dorn, Kind::Gaussian, Kind::Box, Kind::Tent, Kind::Rule1, Kind::Rule2,
                   Kind::Rule3})
      if (head == kind_name(k)) {
        r.kind = k;
        found = true;
      }
    if (!found)
      bad(text, "unknown rule '" + head + "' (none, dorn, gaussian, mcN, box, tent, rule1, rule2, rule3)");
  }
  if (!opt.empty()) {
    if (r.kind == Kind::Gaussian && opt.rfind("rho=", 0) == 0) {
      const std::string v = opt.substr(4);
      if (v == "grad") {
        r.rho = Rho::Gradient;
      } else if (v == "cov") {
        r.rho = Rho::Covariance;
      } else if (v == "0") {
        r.rho = Rho::Zero;
      } else {
        r.rho = Rho::Constant;
        r.rho_value = number(text, v);
        if (!(r.rho_value >= -1 && r.rho_value <= 1)) bad(text, "rho must lie in [-1, 1]");
      }
    } else if (r.kind == Kind::Rule1 && (opt == "box" || opt == "tent" || opt == "gaussian")) {
      r.kernel = opt;
    } else {
      bad(text, "option '" + opt + "' does not apply to " + kind_name(r.kind));
    }
  }
  return r;
}

std::vector<Rule> all_rules() {
  std::vector<Rule> out;
  for (const char* t : {"none", "dorn", "gaussian", "gaussian:rho=grad", "mc2", "mc4", "mc8", "mc16", "mc32",
                        "box", "tent", "rule1:box", "rule1:tent", "rule1:gaussian", "rule2", "rule3"})
    out.push_back(parse_rule(t));
  return out;
}

}  // namespace bl::rules
