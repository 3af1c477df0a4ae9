#include "printer.hpp"

#include <algorithm>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "functions.hpp"

namespace bl::sym {
using namespace GiNaC;

namespace {

std::string integer_literal(const numeric& v, Lang lang) {
  std::ostringstream s;
  s << v;
  if (lang == Lang::Cpp) return "T(" + s.str() + ")";
  if (lang == Lang::Glsl) return s.str() + ".0";
  return s.str();
}

std::string numeric_literal(const numeric& n, Lang lang) {
  if (!n.is_real()) throw std::runtime_error("printer: complex constant in a real formula");
  if (n.is_integer()) {
    const std::string body = integer_literal(n, lang);
    return n.is_negative() ? "(" + body + ")" : body;
  }
  if (n.is_rational()) {
    const std::string p = integer_literal(n.numer(), lang);
    const std::string q = integer_literal(n.denom(), lang);
    return "(" + p + "/" + q + ")";
  }
  std::ostringstream s;
  s.precision(17);
  s << n.to_double();
  if (lang == Lang::Cpp) return "T(" + s.str() + ")";
  return "(" + s.str() + ")";
}

std::string call(const std::string& name, const std::vector<std::string>& args) {
  std::string s = name + "(";
  for (size_t i = 0; i < args.size(); ++i) s += (i ? ", " : "") + args[i];
  return s + ")";
}

std::string helper(const std::string& name, Lang lang) {
  if (lang == Lang::Cpp) return "detail::" + name;
  if (lang == Lang::Glsl) return "bl_" + name;
  return name;
}

std::string pr(const ex& e, Lang lang);
std::string print_power(const ex& base, const ex& expo, Lang lang);

// GiNaC keeps a - b, and (a - b)^n, as either itself or -(b - a) (times (-1)^n) depending on hash
// order, i.e. on the run. Returns the sign s and text t with f = s * t, choosing between the two
// forms by their text, so that the output does not depend on the run.
std::pair<int, std::string> signed_print(const ex& f, Lang lang) {
  if (is_a<add>(f)) {
    const ex neg = (-f).expand();
    const std::string pf = pr(f, lang), pn = pr(neg, lang);
    return pn < pf ? std::make_pair(-1, pn) : std::make_pair(1, pf);
  }
  if (is_a<power>(f) && is_a<add>(f.op(0)) && is_a<numeric>(f.op(1)) && ex_to<numeric>(f.op(1)).is_integer()) {
    const ex neg = (-f.op(0)).expand();
    if (pr(neg, lang) < pr(f.op(0), lang))
      return {ex_to<numeric>(f.op(1)).is_even() ? 1 : -1, print_power(neg, f.op(1), lang)};
    return {1, print_power(f.op(0), f.op(1), lang)};
  }
  if (is_a<power>(f)) return {1, print_power(f.op(0), f.op(1), lang)};
  return {1, pr(f, lang)};
}

std::string print_power(const ex& base, const ex& expo, Lang lang) {
  const std::string b = pr(base, lang);
  if (lang == Lang::Text) return "(" + b + ")^(" + pr(expo, lang) + ")";
  if (is_a<numeric>(expo)) {
    const numeric n = ex_to<numeric>(expo);
    if (n.is_integer()) {
      const long k = n.to_long();
      const long m = k < 0 ? -k : k;
      if (m > 32) throw std::runtime_error("printer: power too large");
      std::string prod;
      for (long i = 0; i < m; ++i) prod += (i ? "*" : "") + b;
      if (m == 0) prod = lang == Lang::Cpp ? "T(1)" : "1.0";
      if (k < 0) return "(" + numeric_literal(1, lang) + "/(" + prod + "))";
      return "(" + prod + ")";
    }
    if (n.is_rational() && n.denom() == 2) {
      // b^(k/2) = b^((k-1)/2) * sqrt(b)
      const ex rest = power(base, (n - numeric(1, 2)));
      const std::string root = call("sqrt", {b});
      if (rest.is_equal(1)) return root;
      return "(" + print_power(base, n - numeric(1, 2), lang) + "*" + root + ")";
    }
  }
  // (-1)^k for the integer symbol k of a Fourier series.
  if (base.is_equal(-1)) return call(helper("parity", lang), {pr(expo, lang)});
  throw std::runtime_error("printer: unsupported power " + b);
}

std::string pr(const ex& e, Lang lang) {
  if (is_a<numeric>(e)) return numeric_literal(ex_to<numeric>(e), lang);
  if (is_a<symbol>(e)) return ex_to<symbol>(e).get_name();
  if (is_a<constant>(e)) {
    if (e.is_equal(Pi)) {
      if (lang == Lang::Text) return "pi";
      return lang == Lang::Cpp ? "detail::pi<T>()" : "bl_pi()";
    }
    throw std::runtime_error("printer: unknown constant");
  }
  if (is_a<add>(e)) {
    std::vector<std::string> terms;
    for (size_t i = 0; i < e.nops(); ++i) terms.push_back(pr(e.op(i), lang));
    std::sort(terms.begin(), terms.end());
    std::string s = "(";
    for (size_t i = 0; i < terms.size(); ++i) s += (i ? " + " : "") + terms[i];
    return s + ")";
  }
  if (is_a<mul>(e)) {
    std::vector<std::string> factors;
    numeric coeff = 1;
    for (size_t i = 0; i < e.nops(); ++i) {
      const ex f = e.op(i);
      if (is_a<numeric>(f)) {
        coeff *= ex_to<numeric>(f);
      } else if (is_a<add>(f) || is_a<power>(f)) {
        const auto [sign, text] = signed_print(f, lang);
        if (sign < 0) coeff = -coeff;
        factors.push_back(text);
      } else {
        factors.push_back(pr(f, lang));
      }
    }
    std::sort(factors.begin(), factors.end());
    std::string s;
    for (size_t i = 0; i < factors.size(); ++i) s += (i ? "*" : "") + factors[i];
    if (coeff.is_equal(1)) return "(" + s + ")";
    if (coeff.is_equal(-1)) return "(-" + s + ")";
    return "(" + numeric_literal(coeff, lang) + "*" + s + ")";
  }
  if (is_a<power>(e)) {
    const auto [sign, text] = signed_print(e, lang);
    return sign < 0 ? "(-" + text + ")" : text;
  }
  if (is_a<function>(e)) {
    const std::string name = ex_to<function>(e).get_name();
    std::vector<std::string> args;
    for (size_t i = 0; i < e.nops(); ++i) args.push_back(pr(e.op(i), lang));
    static const std::map<std::string, std::string> builtin = {
        {"sin", "sin"},   {"cos", "cos"},   {"tan", "tan"},   {"exp", "exp"},
        {"log", "log"},   {"sinh", "sinh"}, {"cosh", "cosh"}, {"tanh", "tanh"},
        {"abs", "abs"},   {"sqrt", "sqrt"},
        {"asin", "asin"}, {"acos", "acos"}, {"atan", "atan"}, {"asinh", "asinh"}, {"acosh", "acosh"},
        {"atanh", "atanh"}};  // inverses: Rule 2's mode equations in y
    auto it = builtin.find(name);
    if (it != builtin.end()) return call(it->second, args);
    static const char* helpers[] = {"Phi", "phi", "sinc", "sinhc", "logcosh", "exp_sinhc",
                                    "exp_sinhc2", "clausen2", "prod0", "sgn"};
    for (const char* h : helpers)
      if (name == h) return call(helper(h, lang), args);
    if (name == "Li2") return call(helper("li2", lang), args);
    throw std::runtime_error("printer: no runtime equivalent for function " + name);
  }
  std::ostringstream s;
  s << e;
  throw std::runtime_error("printer: cannot print " + s.str());
}

}  // namespace

std::string print(const ex& e, Lang lang) { return pr(e, lang); }

}  // namespace bl::sym
