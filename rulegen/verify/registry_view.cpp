// blverify: adapter from the generated registry to EntryView (double and float instantiations).
#include "registry_view.hpp"

// BLVERIFY_HAVE_REGISTRY is set by CMakeLists.txt (whether generated/bandlimit/registry.hpp exists).
#ifndef BLVERIFY_HAVE_REGISTRY
#define BLVERIFY_HAVE_REGISTRY __has_include(<bandlimit/registry.hpp>)
#endif
#if BLVERIFY_HAVE_REGISTRY
#include <bandlimit/registry.hpp>
#define BLV_HAVE_REGISTRY 1
#else
#define BLV_HAVE_REGISTRY 0
#endif

namespace blv {

bool registry_compiled_in() {
  return BLV_HAVE_REGISTRY != 0;
}

#if BLV_HAVE_REGISTRY
std::vector<EntryView> load_registry(std::string* error) {
  std::vector<EntryView> out;
  int nd = 0, nf = 0;
  const bl::registry::Entry<double>* ed = bl::registry::entries<double>(&nd);
  const bl::registry::Entry<float>* ef = bl::registry::entries<float>(&nf);
  if (nd != nf) {
    *error =
        "registry: " + std::to_string(nd) + " double entries but " + std::to_string(nf) + " float entries";
    return out;
  }
  for (int i = 0; i < nd; ++i) {
    const auto& d = ed[i];
    const auto& f = ef[i];
    EntryView v;
    v.index = i;
    v.cpp = d.cpp ? d.cpp : "";
    if (!f.cpp || v.cpp != f.cpp) {
      *error = "registry entry " + std::to_string(i) + " (" + v.cpp +
               ") differs between the float and double instantiations";
      return {};
    }
    v.glsl = d.glsl ? d.glsl : "";
    v.kernel = d.kernel ? d.kernel : "";
    v.rule = d.rule ? d.rule : "";
    v.squared = d.squared;
    v.compact = d.compact;
    v.order = d.order;
    v.lambda = d.lambda;
    v.smoothed_d = d.smoothed;
    v.smoothed_f = f.smoothed;
    v.plain_f = f.plain;
    const bl::registry::AtomicInfo* a = d.atomic;
    Spec& s = v.spec;
    s.name = v.cpp;
    v.kernel_known = parse_kernel(v.kernel, &s.kernel);
    v.exact_rule = v.rule == "convolution" || v.rule == "moment";
    s.power = v.rule == "moment" ? v.order : (v.squared ? 2 : 1);  // moment 0: g = 1
    s.compact = v.compact;
    s.lambda = v.lambda;
    if (a) {
      v.atomic = a->name ? a->name : "";
      v.cls = a->cls ? a->cls : "";
      s.period = a->period;
      s.periodic = v.cls == "periodic";
      for (int k = 0; k < a->nbreaks && k < 8; ++k) s.breaks.push_back(a->breaks[k]);
      for (int k = 0; k < a->nsingular && k < 4; ++k) s.singular.push_back(a->singular[k]);
      s.domain_lo = a->domain_lo;
      s.domain_hi = a->domain_hi;
      s.range_lo = a->range_lo;
      s.range_hi = a->range_hi;
    }
    if (double (*pl)(double) = d.plain) s.plain = [pl](double x) { return pl(x); };
    out.push_back(std::move(v));
  }
  return out;
}
std::vector<StatView> load_stats(std::string* error) {
  std::vector<StatView> out;
  int nd = 0, nf = 0;
  const bl::registry::RuleEntry<double>* sd = bl::registry::stat_entries<double>(&nd);
  const bl::registry::RuleEntry<float>* sf = bl::registry::stat_entries<float>(&nf);
  if (nd != nf) {
    *error = "registry: " + std::to_string(nd) + " double stat entries but " + std::to_string(nf) + " float";
    return {};
  }
  for (int i = 0; i < nd; ++i) {
    StatView v;
    v.cpp = sd[i].cpp;
    const std::string base = v.cpp.substr(0, v.cpp.size() - 5);  // less "_stat"
    v.f_cpp = base;
    v.f2_cpp = base + "_sq";
    auto fd = sd[i].fn;
    auto ff = sf[i].fn;
    v.eval_d = [fd](double x, double s, double* m, double* var) {
      const bl::stat<double> r = fd(x, s);
      *m = r.mean, *var = r.var;
    };
    v.eval_f = [ff](float x, float s, float* m, float* var) {
      const bl::stat<float> r = ff(x, s);
      *m = r.mean, *var = r.var;
    };
    out.push_back(std::move(v));
  }
  return out;
}
#else
std::vector<StatView> load_stats(std::string* error) {
  *error = "blverify was built without generated/bandlimit/registry.hpp";
  return {};
}
std::vector<EntryView> load_registry(std::string* error) {
  *error =
      "blverify was built without generated/bandlimit/registry.hpp: run `rulegen emit`, then rebuild (cmake "
      "--build build)";
  return {};
}
#endif

}  // namespace blv
