// bl::deriv::<atomic>_d1/_d2 (C++) and bl_deriv_<atomic>_d1/_d2 (GLSL), plus their registry.
#include "derivatives.hpp"

#include <cmath>

#include "emit_clamped.hpp"

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

// One period's pieces as straight-line code on the exact signed remainder r (periodic_eval's
// semantics: for r < 0 the piece is found against hi - P, so a jump just below a period boundary
// stays on its side): Rule 3 calls f' and f'' beside f at every node, and the generic table walk
// with fmod cost more than the rule's own arithmetic. A NaN r (x NaN or infinite) is returned as is,
// so constant pieces (fract' = 1) do not turn it into a number.
std::string periodic_straight(const Derivative& d, Lang lang) {
  const bool cpp = lang == Lang::Cpp;
  const GiNaC::symbol r("r"), t("t");
  bool pow2 = false;
  if (GiNaC::is_a<GiNaC::numeric>(d.period)) {
    const double pd = GiNaC::ex_to<GiNaC::numeric>(d.period).to_double();
    int e = 0;
    pow2 = pd > 0 && std::frexp(pd, &e) == 0.5;
  }
  auto poly = [&](const sym::PolyPiece& pc, const GiNaC::symbol& v) {
    GiNaC::ex e = 0;
    for (size_t k = 0; k < pc.c.size(); ++k) e += pc.c[k] * GiNaC::pow(v, static_cast<int>(k));
    return sym::print(e, lang);
  };
  const std::string P = sym::print(d.period, lang), T = cpp ? "const T" : "float";
  const std::string reduce =
      cpp ? (pow2 ? "detail::reduce_signed_pow2" : "detail::reduce_signed") : "bl_reduce_signed";
  // Neighbours with the same polynomial are one piece (square' is 0 on both halves).
  std::vector<sym::PolyPiece> ps;
  for (const auto& pc : d.pieces) {
    auto same = [](const std::vector<GiNaC::numeric>& a, const std::vector<GiNaC::numeric>& b) {
      if (a.size() != b.size()) return false;
      for (size_t k = 0; k < a.size(); ++k)
        if (!a[k].is_equal(b[k])) return false;
      return true;
    };
    if (!ps.empty() && same(ps.back().c, pc.c))
      ps.back().hi = pc.hi;
    else
      ps.push_back(pc);
  }
  std::string o = "  " + T + " r = " + reduce + "(x, " + P + ");\n  if (r != r) return r;\n";
  o += "  if (!(r < " + std::string(cpp ? "T(0)" : "0.0") + ")) {\n";
  for (size_t i = 0; i + 1 < ps.size(); ++i)
    o += "    if (r < " + sym::print(ps[i].hi.value, lang) + ") return " + poly(ps[i], r) + ";\n";
  o += "    return " + poly(ps.back(), r) + ";\n  }\n";
  bool uses_t = false;
  for (const auto& pc : ps) uses_t = uses_t || pc.c.size() > 1;
  if (uses_t) o += "  " + T + " t = r + " + P + ";\n";
  for (size_t i = 0; i + 1 < ps.size(); ++i)
    o += "  if (r < " + sym::print(ps[i].hi.value - d.period, lang) + ") return " + poly(ps[i], t) + ";\n";
  return o + "  return " + poly(ps.back(), t) + ";\n";
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
      return out + periodic_straight(d, lang);
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
