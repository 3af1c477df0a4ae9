#include "compiler/functions.hpp"

#include <bandlimit/registry.hpp>
#include <bandlimit/rules_bivariate.hpp>
#include <bandlimit/rules_clamped.hpp>
#include <bandlimit/rules_mode.hpp>
#include <map>
#include <stdexcept>

namespace bl::compiler {

namespace {

std::string glsl_of_cpp(const std::string& cpp) {
  // bl::plain::sin -> bl_plain_sin (the generated GLSL's naming of the same function).
  std::string g;
  for (std::size_t i = 0; i < cpp.size(); ++i) {
    if (cpp.compare(i, 2, "::") == 0) {
      g += '_';
      ++i;
    } else {
      g += cpp[i];
    }
  }
  return g;
}

std::vector<Function> build() {
  std::vector<Function> out;
  std::map<std::string, int> seen;
  auto add = [&](Function f) {
    if (seen.count(f.cpp)) return;
    seen[f.cpp] = static_cast<int>(out.size());
    out.push_back(std::move(f));
  };
  int n = 0;
  const auto* e = bl::registry::entries<float>(&n);
  for (int i = 0; i < n; ++i) {
    if (std::string(e[i].rule) != "convolution") continue;
    Function plain;
    plain.cpp = plain_name(e[i].atomic->name);
    plain.glsl = glsl_of_cpp(plain.cpp);
    plain.arity = 1;
    plain.f1 = e[i].plain;
    add(plain);
    Function f;
    f.cpp = e[i].cpp;
    f.glsl = e[i].glsl;
    f.arity = 2;
    f.f2 = e[i].smoothed;
    add(f);
  }
  // Every other registry table: name, arity, whether it takes (mean, sd) statistics, and the
  // pointer field its arity uses.
  auto add_table = [&](const auto* t, int count, int arity, bool stat, auto set) {
    for (int i = 0; i < count; ++i) {
      Function f;
      f.cpp = t[i].cpp;
      f.glsl = t[i].glsl;
      f.arity = arity;
      f.stat = stat;
      set(f, t[i].fn);
      add(f);
    }
  };
  const auto* b = bl::registry::binary_entries<float>(&n);
  add_table(b, n, 5, true, [](Function& f, auto fn) { f.s5 = fn; });
  const auto* r2 = bl::registry::rule2_entries<float>(&n);
  add_table(r2, n, 2, true, [](Function& f, auto fn) { f.s2 = fn; });
  Function sel;
  sel.cpp = "bl::bivariate::select";
  sel.glsl = "bl_bivariate_select";
  sel.arity = 6;
  sel.stat = true;
  sel.s6 = [](float mc, float sc, float ma, float sa, float mb, float sb) {
    return bl::bivariate::select(mc, sc, ma, sa, mb, sb);
  };
  add(sel);
  Function mod;
  mod.cpp = "bl::bivariate::mod";
  mod.glsl = "bl_bivariate_mod";
  mod.arity = 3;
  mod.stat = true;
  mod.s3 = [](float ma, float sa, float c) { return bl::bivariate::mod(ma, sa, c); };
  add(mod);
  const auto* d = bl::registry::derivative_entries<float>(&n);
  add_table(d, n, 1, false, [](Function& f, auto fn) { f.f1 = fn; });
  const auto* rc = bl::registry::clamped_rule_entries<float>(&n);
  add_table(rc, n, 2, true, [](Function& f, auto fn) { f.s2 = fn; });
  const auto* st = bl::registry::stat_entries<float>(&n);
  add_table(st, n, 2, true, [](Function& f, auto fn) { f.s2 = fn; });
  for (int i = 0; i < n; ++i) {
    const std::string name = st[i].cpp, mean = name.substr(0, name.size() - 5);  // less "_stat"
    if (!seen.count(mean)) throw std::logic_error("generated table: " + name + " without " + mean);
    out[seen.at(name)].mean_entry = seen.at(mean);
  }
  return out;
}

}  // namespace

const std::vector<Function>& functions() {
  static const std::vector<Function> table = build();
  return table;
}

int find_function(const std::string& cpp_name) {
  static const std::map<std::string, int> index = [] {
    std::map<std::string, int> m;
    for (std::size_t i = 0; i < functions().size(); ++i) m[functions()[i].cpp] = static_cast<int>(i);
    return m;
  }();
  auto it = index.find(cpp_name);
  return it == index.end() ? -1 : it->second;
}

std::string plain_name(const std::string& atomic) {
  return "bl::plain::" + atomic;
}

std::string kernel_name(const std::string& kernel, const std::string& atomic, bool squared) {
  return "bl::" + kernel + "::" + atomic + (squared ? "_sq" : "");
}

std::string stat_name(const std::string& kernel, const std::string& atomic) {
  return "bl::" + kernel + "::" + atomic + "_stat";
}

}  // namespace bl::compiler
