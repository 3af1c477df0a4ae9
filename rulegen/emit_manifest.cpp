// generated/manifest.json: the contract with runtime/ (DESIGN.md). `blverify --record` adds each
// entry's verification record afterwards.
#include <nlohmann/json.hpp>

#include "emit_common.hpp"

namespace bl::rulegen {

void emit_manifest(const sym::Catalog& cat, const std::vector<Derived>& ds,
                   const std::vector<sym::NotDerived>& not_derived, const std::string& out_dir,
                   const std::string& catalog_label) {
  (void)cat;
  nlohmann::ordered_json m;
  m["generator"] = "rulegen emit";
  m["catalog"] = catalog_label;
  m["cpp_header"] = "generated/bandlimit/table.hpp";
  m["glsl_file"] = "generated/bandlimit.glsl";
  m["conventions"] =
      "kernel(x, sigma) = E[f(x + U)]; sigma is the kernel's standard deviation: gaussian N(0, sigma^2), "
      "box U[-sqrt(3) sigma, sqrt(3) sigma], tent triangle on [-sqrt(6) sigma, sqrt(6) sigma]. sigma = 0 "
      "gives f(x) (right-continuous at jumps); sigma < 0 or NaN gives NaN.";
  auto& entries = m["entries"] = nlohmann::ordered_json::array();
  for (const auto& d : ds) {
    nlohmann::ordered_json e;
    e["atomic"] = d.atomic_name;
    e["kernel"] = sym::to_string(d.kernel);
    e["squared"] = d.squared;
    e["rule"] = d.rule;
    if (d.rule == "moment") {
      e["order"] = d.order;
      e["cpp"] = std::string("bl::") + sym::to_string(d.kernel) + "::moment(" + std::to_string(d.order) + ", x, sigma)";
      e["glsl"] = d.glsl_name() + "(" + std::to_string(d.order) + ", x, sigma)";
    } else {
      e["cpp"] = d.cpp_name();
      e["glsl"] = d.glsl_name();
      e["class"] = sym::to_string(d.atomic->cls);
    }
    if (d.body == sym::Body::Antiderivative && !d.atomic->singular.empty()) {
      e["compact"] = true;
      e["lambda"] = d.lambda;
    }
    e["formula"] = d.formula;
    entries.push_back(e);
  }
  auto& nd = m["not_derived"] = nlohmann::ordered_json::array();
  for (const auto& n : not_derived)
    nd.push_back({{"atomic", n.atomic}, {"kernel", n.kernel}, {"squared", n.squared}, {"reason", n.reason}});
  write_file(out_dir + "/manifest.json", m.dump(2) + "\n");
}

}  // namespace bl::rulegen
