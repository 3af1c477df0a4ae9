// Per-atomic entries of Rule 3 (every atomic), Rule 1 (atomics with a restricted domain), the
// bimodal box truncation (atomics with jumps) and the compact half-widths (atomics with
// singularities), for C++ and GLSL, with their registry and manifest entries.
#include <set>

#include "emit_clamped.hpp"
#include "emit_common.hpp"

namespace bl::rulegen::clamped {
using sym::Lang;

namespace {

std::string dom_d(const sym::Bound& b);
std::string dom(const sym::Bound& b, Lang lang) {
  if (b.inf)
    return std::string(b.inf < 0 ? "-" : "") + (lang == Lang::Cpp ? "truncnorm::detail::inf()" : "BL_INF");
  return lang == Lang::Cpp ? dom_d(b) : sym::print(b.value, Lang::Glsl);
}
// Catalog bounds print as T(...) in C++: the domain helpers instantiate them at double.
std::string dom_d(const sym::Bound& b) {
  if (b.inf) return std::string(b.inf < 0 ? "-" : "") + "truncnorm::detail::inf()";
  return lit(b.to_double(), Lang::Glsl);  // (0.0): a double literal
}

nlohmann::ordered_json manifest_entry(const sym::Atomic& a, const std::string& rule,
                                      const std::string& kernel, const std::string& cpp,
                                      const std::string& glsl, const std::string& method,
                                      const std::string& formula) {
  nlohmann::ordered_json e;
  e["atomic"] = a.name;
  e["kernel"] = kernel;
  e["squared"] = false;
  e["rule"] = rule;
  e["cpp"] = cpp;
  e["glsl"] = glsl;
  e["signature"] = rule == "compact" ? "T f(T x, T sigma)"
                                     : "bl::stat<T> f(T mu, T sigma) / vec2 f(float mu, float sigma)";
  e["method"] = method;
  e["formula"] = formula;
  return e;
}

struct Ctx {
  const sym::Catalog& cat;
  Output& out;
  std::string api_rule3, api_bimodal, api_compact;
  std::string api_rule1[3];
  std::string reg;
  void api(std::string& to, const std::string& name, const std::string& impl) {
    for (const char* T : {"float", "double"})
      to += std::string("inline stat<") + T + "> " + name + "(" + T + " mu, " + T +
            " sigma) { return ::bl::detail::gen::" + impl + "<" + T + ">(mu, sigma); }\n";
  }
  void add_reg(const sym::Atomic& a, const std::string& rule, const std::string& kernel,
               const std::string& method, const std::string& cpp, const std::string& glsl,
               const std::string& impl) {
    reg += "      {&kAtomics[" + std::to_string(atomic_index(cat, &a)) + "], \"" + rule + "\", \"" + kernel +
           "\", \"" + method + "\", \"" + cpp + "\", \"" + glsl + "\", &detail::gen::" + impl + "<T>},\n";
  }
};

void rule3(Ctx& x, const sym::Atomic& a) {
  const std::string impl = "rule3_" + a.name, cpp = "bl::rule3::" + a.name, glsl = "bl_rule3_" + a.name;
  const std::string lo = dom_d(a.domain_lo), hi = dom_d(a.domain_hi);
  const bool bounded = a.range_lo.finite() || a.range_hi.finite();  // the Taylor rule is clamped to f's range
  // On the whole line nothing is truncated: the normal's own moments (mass 1, mean mu, var sigma^2,
  // mu3 0, mu4 3 sigma^4), not the generic truncated-moment code (fract: 18.8 ns a call).
  const bool whole = a.domain_lo.inf < 0 && a.domain_hi.inf > 0;
  const std::string moments_cpp =
      whole ? "  const double k2 = double(sigma) * double(sigma);  // the whole line: nothing truncated\n"
              "  const truncnorm::Moments<double> m{1.0, double(mu), k2, 0.0, 3.0 * k2 * k2};\n"
            : "  const auto m = truncnorm::moments<double>(double(mu), double(sigma), lo, hi);\n";
  const std::string moments_glsl =
      whole ? "  float k2 = sigma * sigma;  // the whole line: nothing truncated\n"
              "  BlTruncMoments m = BlTruncMoments(1.0, mu, k2, 0.0, 3.0 * k2 * k2);\n"
            : "  BlTruncMoments m = bl_truncnorm_moments(mu, sigma, " + dom(a.domain_lo, Lang::Glsl) + ", " +
                  dom(a.domain_hi, Lang::Glsl) + ");\n";
  x.out.impl +=
      "// Rule 3: second-order Taylor of " + a.name +
      " at the mean of N(mu, sigma^2) truncated to the domain.\n" + "template <class T>\nstat<T> " + impl +
      "(T mu, T sigma) {\n" + "  const double lo = " + lo + ", hi = " + hi + ";\n" +
      "  if (!(sigma >= T(0)) || mu != mu || (sigma == T(0) && !(double(mu) >= lo && double(mu) <= hi)))\n" +
      "    return {detail::nan<T>(), detail::nan<T>()};\n" + moments_cpp + "  const double c = m.mean;\n" +
      "  const stat<double> s = rule3::from_derivatives<double>(plain_" + a.name + "<double>(c), deriv_" +
      a.name + "_d1<double>(c), deriv_" + a.name + "_d2<double>(c), m);\n" +
      (bounded ? "  const stat<double> r = rule3::in_range<double>(s, " + dom_d(a.range_lo) + ", " +
                     dom_d(a.range_hi) + ");  // f's range\n  return {T(r.mean), T(r.var)};\n}\n\n"
               : "  return {T(s.mean), T(s.var)};\n}\n\n");
  x.out.glsl += "vec2 " + glsl +
                "(float mu, float sigma) {\n  if (!(sigma >= 0.0) || mu != mu) return vec2(bl_nan());\n" +
                moments_glsl + "  float c = m.mean;\n  vec2 s = bl_rule3_from_derivatives(bl_clamped_plain_" +
                a.name + "(c), bl_deriv_" + a.name + "_d1(c), bl_deriv_" + a.name + "_d2(c), m);\n" +
                (bounded ? "  return bl_rule3_in_range(s, " + dom(a.range_lo, Lang::Glsl) + ", " +
                               dom(a.range_hi, Lang::Glsl) + ");\n}\n\n"
                         : "  return s;\n}\n\n");
  x.api(x.api_rule3, a.name, impl);
  x.add_reg(a, "rule3", "gaussian", "closed form (truncated-normal moments)", cpp, glsl, impl);
  x.out.manifest.push_back(
      manifest_entry(a, "rule3", "gaussian", cpp, glsl,
                     "closed form: truncated-normal moments (continued fraction in the tails)",
                     "X ~ N(mu, sigma^2) on the domain [" +
                         std::string(a.domain_lo.inf ? "-inf" : sym::print(a.domain_lo.value, Lang::Text)) +
                         ", " + (a.domain_hi.inf ? "inf" : sym::print(a.domain_hi.value, Lang::Text)) +
                         "], c = E[X], f ~ f(c) + f'(c)(X-c) + f''(c)(X-c)^2/2: mean = f(c) + f''(c) k2/2, "
                         "var = f'^2 k2 + f' f'' k3 + "
                         "f''^2 (k4 - k2^2)/4 (k_j central moments of the truncated normal)"));
}

const char* kKernels[3] = {"gaussian", "box", "tent"};

void rule1(Ctx& x, const sym::Atomic& a) {
  {  // GLSL has no function arguments: one expectation per atomic (both passes)
    const std::string f = "bl_clamped_plain_" + a.name;
    x.out.glsl +=
        "vec2 bl_rule1_expect_" + a.name + "(int kernel, vec3 p, float a, float b) {\n" +
        "  if (p.x != p.x || !(p.y >= 0.0)) return vec2(bl_nan());\n" + "  if (p.y == 0.0) return vec2(" + f +
        "(p.x), 0.0);\n" +
        "  vec3 sup = bl_rule1_support(kernel, p, a, b);\n  float zm = bl_rule1_zm(p, a, b);\n  if (!(sup.x "
        "< sup.y)) return vec2(bl_nan());\n" +
        "  float s0 = 0.0, s1 = 0.0, s2 = 0.0;\n" +
        "  for (int pass = 0; pass < 2; ++pass) {\n    float mean = s1 / max(s0, 1e-38);\n" +
        "    for (int part = 0; part < 2; ++part) {\n" +
        "      float l = part == 0 ? sup.x : sup.z, r = part == 0 ? sup.z : sup.y;\n      if (!(l < r)) "
        "continue;\n" +
        "      for (int k = -26; k <= 26; ++k) {\n        vec2 uw = bl_tanh_sinh_node(k, l, r);\n" +
        "        if (uw.y == 0.0) continue;\n        float w = uw.y * bl_rule1_density(kernel, p, zm, uw.x), "
        "g "
        "= " +
        f + "(uw.x);\n" +
        "        if (pass == 0) {\n          s0 += w;\n          s1 += w * g;\n        } else {\n" +
        "          s2 += w * (g - mean) * (g - mean);\n        }\n      }\n    }\n  }\n" +
        "  return vec2(s1 / s0, s2 / s0);\n}\n\n";
  }
  for (int k = 0; k < 3; ++k) {
    const std::string K = kKernels[k];
    const std::string impl = "rule1_" + K + "_" + a.name, cpp = "bl::rule1::" + K + "::" + a.name,
                      glsl = "bl_rule1_" + K + "_" + a.name;
    const std::string lo = dom_d(a.domain_lo), hi = dom_d(a.domain_hi);
    x.out.impl += "// Rule 1 (" + K +
                  "): X with mean mu and deviation sigma, the kernel renormalized on the domain of " +
                  a.name + ".\ntemplate <class T>\nstat<T> " + impl + "(T mu, T sigma) {\n" +
                  "  const double lo = " + lo + ", hi = " + hi + ";\n" +
                  "  if (!(sigma >= T(0)) || !(double(mu) >= lo && double(mu) <= hi)) return "
                  "{detail::nan<T>(), detail::nan<T>()};\n" +
                  "  const auto p = rule1::renormalize<double>(rule1::Kernel::" + K +
                  ", double(mu), double(sigma) * double(sigma), lo, hi);\n" +
                  "  const stat<double> s = rule1::expect<double>(rule1::Kernel::" + K +
                  ", p, lo, hi, [](double u) { return plain_" + a.name + "<double>(u); });\n" +
                  "  return {T(s.mean), T(s.var)};\n}\n\n";
    x.out.glsl += "vec2 " + glsl + "(float mu, float sigma) {\n  float lo = " + dom(a.domain_lo, Lang::Glsl) +
                  ", hi = " + dom(a.domain_hi, Lang::Glsl) +
                  ";\n  if (!(sigma >= 0.0) || !(mu >= lo && mu <= hi)) return vec2(bl_nan());\n" +
                  "  vec3 p = bl_rule1_renormalize(" + std::to_string(k) + ", mu, sigma * sigma, lo, hi);\n" +
                  "  return bl_rule1_expect_" + a.name + "(" + std::to_string(k) + ", p, lo, hi);\n}\n\n";
    x.api(x.api_rule1[k], a.name, impl);
    const std::string method = k == 0 ? "newton (natural parameters, <= 40 steps) + tanh-sinh quadrature"
                                      : "explicit kernel + tanh-sinh quadrature";
    x.add_reg(a, "rule1", K, method, cpp, glsl, impl);
    x.out.manifest.push_back(manifest_entry(
        a, "rule1", K, cpp, glsl, method,
        "p = " + K +
            " kernel restricted to the domain and renormalized with mean mu and variance sigma^2 (eqs. 5-8; "
            "box/tent: the widest symmetric kernel that fits); mean = int f p, var = int (f - mean)^2 p"));
  }
}

void bimodal(Ctx& x, const sym::Atomic& a, const std::vector<sym::Derived>& ds) {
  bool has_sq = false;
  for (const auto& d : ds)
    if (d.atomic == &a && d.kernel == sym::Kernel::Box && d.squared) has_sq = true;
  if (!has_sq) return;  // the variance needs the box entry of f^2
  std::vector<std::string> jumps;
  double period = 0;
  if (a.jumps_at_integers) {
    jumps = {"0.0"};
    period = 1;
  } else {
    for (const auto& j : a.jumps)
      jumps.push_back(lit(GiNaC::ex_to<GiNaC::numeric>(j.evalf()).to_double(), Lang::Glsl));
    if (a.period) period = GiNaC::ex_to<GiNaC::numeric>(a.period->evalf()).to_double();
  }
  std::string jl, jg;
  for (const auto& j : jumps) {
    jl += (jl.empty() ? "" : ", ") + j;
    jg += (jg.empty() ? "" : ", ") + j;
  }
  const std::string n = std::to_string(jumps.size());
  const std::string impl = "bimodal_" + a.name, cpp = "bl::bimodal::" + a.name, glsl = "bl_bimodal_" + a.name;
  x.out.impl +=
      "// Box footprint cut at the single jump it contains (Yang & Barnes 2018, 4.6).\ntemplate <class "
      "T>\nstat<T> " +
      impl + "(T mu, T sigma) {\n  static const double jumps[" + n + "] = {" + jl + "};\n" +
      "  // In double also for float: the variance E[f^2] - E[f]^2 cancels where |f| is large (floor).\n" +
      "  const stat<double> r = bimodal::truncated_box<double>(double(mu), double(sigma), " +
      lit(period, Lang::Glsl) + ", jumps, " + n + ", [](double x, double s) { return box_" + a.name +
      "<double>(x, s); }, [](double x, double s) { return box_" + a.name +
      "_sq<double>(x, s); });\n  return {T(r.mean), T(r.var)};\n}\n\n";
  // GLSL: the jump list is at most 2 long (square); unrolled.
  std::string g = "vec2 " + glsl +
                  "(float mu, float sigma) {\n  if (!(sigma >= 0.0) || mu != mu) return vec2(bl_nan());\n" +
                  "  if (sigma == 0.0) return vec2(bl_box_" + a.name + "(mu, 0.0), 0.0);\n" +
                  "  float h = BL_SQRT3 * sigma, lo = mu - h, hi = mu + h, at = 0.0;\n  int count = 0;\n";
  for (const auto& j : jumps) {
    if (period > 0)
      g += "  { float kh = floor((hi - " + j + ") / " + lit(period, Lang::Glsl) + "), kl = floor((lo - " + j +
           ") / " + lit(period, Lang::Glsl) + "); count += int(kh - kl); if (kh > kl) at = " + j + " + " +
           lit(period, Lang::Glsl) + " * kh; }\n";
    else
      g += "  if (lo < " + j + " && " + j + " <= hi) { count += 1; at = " + j + "; }\n";
  }
  g += "  vec2 cs = bl_bimodal_cut(mu, sigma, lo, hi, at, count);\n  float m = bl_box_" + a.name +
       "(cs.x, cs.y);\n" + "  return vec2(m, max(bl_box_" + a.name + "_sq(cs.x, cs.y) - m * m, 0.0));\n}\n\n";
  x.out.glsl += g;
  x.api(x.api_bimodal, a.name, impl);
  x.add_reg(a, "bimodal", "box", "closed form (box entries on the cut footprint)", cpp, glsl, impl);
  x.out.manifest.push_back(manifest_entry(
      a, "bimodal", "box", cpp, glsl, "closed form: the table's box entries on the cut footprint",
      "footprint [mu - sqrt(3) sigma, mu + sqrt(3) sigma] with exactly one jump J (jumps at " + jl +
          (period > 0 ? " + k*" + lit(period, Lang::Glsl) : std::string()) +
          "): kept side [J, mu + h] if mu >= J else [mu - h, J]; mean, var of f uniform on it; otherwise box "
          "convolution"));
}

void compact(Ctx& x, const sym::Atomic& a) {
  for (int k = 1; k < 3; ++k) {
    const std::string K = kKernels[k];
    const std::string impl = "compact_" + K + "_halfwidth_" + a.name;
    const std::string cpp = "bl::compact::" + K + "_halfwidth_" + a.name,
                      glsl = "bl_compact_" + K + "_halfwidth_" + a.name;
    auto body = [&](Lang lang) {
      const bool c = lang == Lang::Cpp;
      const std::string T = c ? "T" : "float";
      std::string r, s = c ? "  BL_MATH_USING\n" : "";
      s += "  if (!(sigma >= " + std::string(c ? "T(0)" : "0.0") + ")) return " +
           (c ? "detail::nan<T>()" : "bl_nan()") + ";\n";
      if (a.period) {
        s += "  " + T + " period = " + sym::print(*a.period, lang) + ";\n  " + T +
             " xr = x - period * floor(x / period);\n";
        for (const auto& sg : a.singular) {
          const std::string d = "abs(xr - " + sym::print(sg, lang) + ")";
          const std::string ri =
              c ? "detail::min2(" + d + ", period - " + d + ")" : "min(" + d + ", period - " + d + ")";
          r = r.empty() ? ri : (c ? "detail::min2(" + r + ", " + ri + ")" : "min(" + r + ", " + ri + ")");
        }
      } else {
        for (const auto& sg : a.singular) {
          const std::string ri = "abs(x - " + sym::print(sg, lang) + ")";
          r = r.empty() ? ri : (c ? "detail::min2(" + r + ", " + ri + ")" : "min(" + r + ", " + ri + ")");
        }
      }
      const std::string h =
          (k == 1 ? (c ? "T(1.7320508075688772)" : "BL_SQRT3") : (c ? "T(2.4494897427831781)" : "BL_SQRT6")) +
          std::string(" * sigma");
      return s + "  return " +
             (c ? "compact::halfwidth(" + h + ", " + r + ")" : "min(" + h + ", 0.5 * " + r + ")") + ";\n";
    };
    x.out.impl += "// Compact " + K + " half-width near the singularities of " + a.name +
                  ": min(h, lambda r), lambda = 1/2 (Yang & Barnes 2018, 4.6).\ntemplate <class T>\nT " +
                  impl + "(T x, T sigma) {\n" + body(Lang::Cpp) + "}\n\n";
    x.out.glsl += "float " + glsl + "(float x, float sigma) {\n" + body(Lang::Glsl) + "}\n\n";
    for (const char* T : {"float", "double"})
      x.api_compact += std::string("inline ") + T + " " + K + "_halfwidth_" + a.name + "(" + T + " x, " + T +
                       " sigma) { return ::bl::detail::gen::" + impl + "<" + T + ">(x, sigma); }\n";
    x.out.manifest.push_back(
        manifest_entry(a, "compact", K, cpp, glsl, "closed form",
                       "hh = min(h, r/2), h = " + std::string(k == 1 ? "sqrt(3)" : "sqrt(6)") +
                           " sigma, r = distance to the nearest singularity; the table's " + K +
                           " entries of " + a.name + " use it"));
  }
}

}  // namespace

void emit_rules(const sym::Catalog& cat, const std::vector<sym::Derived>& ds, Output& out) {
  Ctx x{cat, out, {}, {}, {}, {}, {}};
  // GLSL has no plain atomics in bandlimit.glsl: this file brings its own (same bodies as C++).
  for (const auto& a : cat.atomics) {
    std::string b = plain_body(a, ds, Lang::Glsl);
    for (size_t p = b.find("bl_plain_"); p != std::string::npos; p = b.find("bl_plain_", p + 17))
      b.replace(p, 9, "bl_clamped_plain_");
    out.glsl += "float bl_clamped_plain_" + a.name + "(float x) {\n" + b + "}\n\n";
  }
  {
    nlohmann::ordered_json e;
    e["atomic"] = "";
    e["kernel"] = "gaussian";
    e["squared"] = false;
    e["rule"] = "truncnorm";
    e["cpp"] = "bl::truncnorm::moments";
    e["glsl"] = "bl_truncnorm_moments";
    e["signature"] =
        "truncnorm::Moments<T> f(T mu, T sigma, T a, T b) / BlTruncMoments f(float mu, float sigma, float a, "
        "float b)";
    e["method"] =
        "closed form in z: Gauss-Legendre where the density drops by < e^4, continued fraction beyond 3 "
        "sigma, erfc partial moments otherwise";
    e["formula"] =
        "mass = P(a <= X <= b), mean and central moments 2-4 of X ~ N(mu, sigma^2) given a <= X <= b; eqs. "
        "18-20: "
        "m0 = mass, m1 = mass (mean - mu), m2 = mass (var + (mean - mu)^2) (bl::truncnorm::partial)";
    out.manifest.push_back(e);
  }
  for (const auto& a : cat.atomics) rule3(x, a);
  for (const auto& a : cat.atomics)
    if (a.domain_lo.finite() || a.domain_hi.finite()) rule1(x, a);
  for (const auto& a : cat.atomics)
    if (!a.jumps.empty() || a.jumps_at_integers) bimodal(x, a, ds);
  for (const auto& a : cat.atomics)
    if (!a.singular.empty()) compact(x, a);
  out.api += "namespace rule3 {\n" + x.api_rule3 + "}  // namespace rule3\n\nnamespace rule1 {\n";
  for (int k = 0; k < 3; ++k)
    out.api += std::string("namespace ") + kKernels[k] + " {\n" + x.api_rule1[k] + "}  // namespace " +
               kKernels[k] + "\n";
  out.api += "}  // namespace rule1\n\nnamespace bimodal {\n" + x.api_bimodal +
             "}  // namespace bimodal\n\nnamespace compact {\n" + x.api_compact +
             "}  // namespace compact\n\n";
  out.registry +=
      "// Rule 1, Rule 3 and bimodal entries: fn(mu, sigma) -> (mean, var).\ntemplate <class T>\nconst "
      "RuleEntry<T>* "
      "clamped_rule_entries(int* count) {\n  static const RuleEntry<T> e[] = {\n" +
      x.reg + "  };\n  *count = static_cast<int>(sizeof(e) / sizeof(e[0]));\n  return e;\n}\n\n";
}

}  // namespace bl::rulegen::clamped
