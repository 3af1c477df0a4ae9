// bl::deriv::<atomic>_d1/_d2 (C++) and bl_deriv_<atomic>_d1/_d2 (GLSL), plus their registry.
#include "derivatives.hpp"
#include "emit_clamped.hpp"
#include "emit_common.hpp"

namespace bl::rulegen::clamped {
using sym::Lang;

namespace {

std::string domain_guard(const sym::Atomic& a, Lang lang) {
  const std::string nan = lang == Lang::Cpp ? "detail::nan<T>()" : "bl_nan()";
  std::string out;
  if (a.domain_lo.finite())
    out +=
        "  if (x < " + sym::print(a.domain_lo.value, lang) + ") return " + nan + ";  // outside the domain\n";
  if (a.domain_hi.finite())
    out +=
        "  if (x > " + sym::print(a.domain_hi.value, lang) + ") return " + nan + ";  // outside the domain\n";
  return out;
}

// One period's pieces as straight-line code (emit_common's periodic_straight, periodic_eval's
// semantics): Rule 3 calls f' and f'' beside f at every node, and the generic table walk with fmod
// cost more than the rule's own arithmetic. A NaN r (x NaN or infinite) is returned as is, so
// constant pieces (fract' = 1) do not turn it into a number. Neighbours with the same polynomial are
// one piece (square' is 0 on both halves).
std::string periodic_derivative(const Derivative& d, Lang lang) {
  std::vector<std::pair<GiNaC::ex, GiNaC::ex>> pieces;
  const std::vector<GiNaC::numeric>* last = nullptr;
  for (const auto& pc : d.pieces) {
    bool same = last && last->size() == pc.c.size();
    for (size_t k = 0; same && k < pc.c.size(); ++k) same = (*last)[k].is_equal(pc.c[k]);
    if (same) {
      pieces.back().first = pc.hi.value;
      continue;
    }
    pieces.emplace_back(pc.hi.value, poly_in_x(pc.c));
    last = &pc.c;
  }
  return periodic_straight(d.period, pieces, lang, true);
}

std::string body(const Derivative& d, Lang lang) {
  const bool cpp = lang == Lang::Cpp;
  std::string out = cpp ? "  BL_MATH_USING\n" : "";
  out += domain_guard(*d.atomic, lang);
  const std::string n = std::to_string(d.pieces.size());
  switch (d.kind) {
    case Derivative::Kind::Closed:
      return out + "  return " + sym::print(d.closed, lang) + ";\n";
    case Derivative::Kind::Pieces:
      return out + piece_table("p", d.pieces, lang) + "  return " +
             (cpp ? "detail::pw_eval(x, p)" : "bl_pw_eval(x, " + n + ", p)") + ";\n";
    case Derivative::Kind::Periodic:
      return out + periodic_derivative(d, lang);
    case Derivative::Kind::Chain:
      for (size_t i = 0; i + 1 < d.chain.size(); ++i)
        out += "  if (x < " + sym::print(d.chain[i].first.value, lang) + ") return " +
               sym::print(d.chain[i].second, lang) + ";\n";
      return out + "  return " + sym::print(d.chain.back().second, lang) + ";\n";
    case Derivative::Kind::Combination: {
      std::string v = sym::print(d.closed, lang);
      for (const auto& t : d.terms) {
        const std::string f = "deriv_" + t.atomic + "_d" + std::to_string(d.order);
        v += " + " + sym::print(t.coeff, lang) + " * " + (cpp ? f + "<T>" : "bl_" + f) + "(" +
             (t.arg_sign < 0 ? "-x" : "x") + ")";
      }
      return out + "  return " + v + ";\n";
    }
  }
  return out;
}

}  // namespace

void emit_derivatives(const sym::Catalog& cat, const std::vector<sym::Derived>& ds, Output& out) {
  const auto dv = derive_derivatives(cat, ds);
  std::string decl, impl, api = "namespace deriv {\n", reg;
  for (const auto& d : dv) decl += "template <class T>\nT " + d.impl() + "(T x);\n";
  for (const auto& d : dv) {
    impl += "// " + d.formula + "\ntemplate <class T>\nT " + d.impl() + "(T x) {\n" + body(d, Lang::Cpp) +
            "}\n\n";
    out.glsl += "float " + d.glsl() + "(float x) {\n" + body(d, Lang::Glsl) + "}\n\n";
    const std::string short_name = d.atomic->name + "_d" + std::to_string(d.order);
    for (const char* T : {"float", "double"})
      api += std::string("inline ") + T + " " + short_name + "(" + T +
             " x) { return ::bl::detail::gen::" + d.impl() + "<" + T + ">(x); }\n";
    reg += "      {&kAtomics[" + std::to_string(atomic_index(cat, d.atomic)) + "], " +
           std::to_string(d.order) + ", \"" + d.cpp() + "\", \"" + d.glsl() +
           "\", &detail::gen::" + d.impl() + "<T>},\n";
    nlohmann::ordered_json e;
    e["atomic"] = d.atomic->name;
    e["kernel"] = "none";
    e["squared"] = false;
    e["rule"] = "derivative";
    e["order"] = d.order;
    e["cpp"] = d.cpp();
    e["glsl"] = d.glsl();
    e["signature"] = "T f(T x)";
    e["method"] = "GiNaC diff of the catalog definition";
    e["formula"] = d.formula;
    out.manifest.push_back(e);
  }
  out.impl += decl + "\n" + impl;
  out.api += api + "}  // namespace deriv\n\n";
  out.registry +=
      "// Every atomic's first and second derivative (rule \"derivative\").\ntemplate <class T>\nconst "
      "DerivativeEntry<T>* "
      "derivative_entries(int* count) {\n  static const DerivativeEntry<T> e[] = {\n" +
      reg + "  };\n  *count = static_cast<int>(sizeof(e) / sizeof(e[0]));\n  return e;\n}\n\n";
}

}  // namespace bl::rulegen::clamped
