// The emitters' spelling of the few constructs the generated bodies use, in C++ (template over T)
// or GLSL (float): one description of a body prints to both through it.
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include "derived.hpp"
#include "printer.hpp"

namespace bl::rulegen {

using sym::Lang;

// Language-specific spelling of the few constructs the bodies use.
struct Syntax {
  Lang lang;
  bool cpp() const { return lang == Lang::Cpp; }
  std::string T() const { return cpp() ? "T" : "float"; }
  std::string ex(const GiNaC::ex& e) const { return sym::print(e, lang); }
  std::string num(const GiNaC::ex& e) const { return sym::print(e, lang); }
  std::string dbl(double v) const {
    // Shortest text that reads back as v.
    std::string t;
    for (int prec = 6; prec <= 17; ++prec) {
      std::ostringstream s;
      s.precision(prec);
      s << v;
      t = s.str();
      if (std::stod(t) == v) break;
    }
    if (t.find_first_of(".e") == std::string::npos) t += ".0";
    return cpp() ? "T(" + t + ")" : "(" + t + ")";
  }
  std::string helper(const std::string& n) const { return cpp() ? "detail::" + n : "bl_" + n; }
  std::string nan() const { return cpp() ? "detail::nan<T>()" : "bl_nan()"; }
  std::string pi() const { return cpp() ? "detail::pi<T>()" : "bl_pi()"; }
  std::string min(const std::string& a, const std::string& b) const {
    return cpp() ? "detail::min2(" + a + ", " + b + ")" : "min(" + a + ", " + b + ")";
  }
  std::string bound(const sym::Bound& b) const {
    if (b.inf) return std::string(b.inf < 0 ? "-" : "") + (cpp() ? "detail::inf<T>()" : "1e30");
    return ex(b.value);
  }
  std::string fn(const std::string& impl) const { return cpp() ? impl + "<T>" : "bl_" + impl; }
  std::string decl(const std::string& name, const std::string& value) const {
    // GLSL ES only allows constant expressions after const: plain locals there.
    return std::string("  ") + (cpp() ? "const " : "") + T() + " " + name + " = " + value + ";\n";
  }
};

// Horner form of sum_k c[k] v^k; an empty c[k] is a zero coefficient.
inline std::string horner(const Syntax& s, const std::vector<std::string>& c, const std::string& v) {
  int top = static_cast<int>(c.size()) - 1;
  while (top >= 0 && c[top].empty()) --top;
  if (top < 0) return s.dbl(0);
  std::string r = c[top];
  for (int k = top - 1; k >= 0; --k) r = "(" + r + ") * " + v + (c[k].empty() ? "" : " + " + c[k]);
  return r;
}

}  // namespace bl::rulegen
