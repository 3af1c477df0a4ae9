#include "pipeline.hpp"

#include <chrono>

#include "catalog.hpp"
#include "clamped/emit_clamped.hpp"
#include "derived.hpp"
#include "emit_common.hpp"
#include "emit_rules.hpp"

namespace bl::rulegen {

int run(const Options& opt, std::ostream& out, std::ostream& err) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  const std::string origin = opt.catalog_text.empty() ? opt.catalog : "catalog text";
  try {
    const sym::Catalog cat = opt.catalog_text.empty() ? sym::load_catalog(opt.catalog)
                                                      : sym::parse_catalog(opt.catalog_text, origin);
    const auto t1 = clock::now();
    std::vector<sym::NotDerived> nd;
    std::vector<sym::Derived> ds;
    try {
      ds = sym::derive_all(cat, opt.max_moment, &nd);
    } catch (const sym::CatalogError& e) {
      throw sym::CatalogError(origin + ": " + e.what());  // derivation errors name the entry; add the file
    }
    const auto t2 = clock::now();
    if (!opt.quiet)
      for (const auto& d : ds)
        out << d.cpp_name() << (d.rule == "moment" ? "(" + std::to_string(d.order) + ")" : "") << " = "
            << d.formula << "\n";
    double emit_s = 0;
    if (!opt.out.empty()) {
      const auto t3 = clock::now();
      emit_cpp(cat, ds, opt.out);
      emit_glsl(cat, ds, opt.out);
      emit_manifest(cat, ds, nd, opt.out, opt.label);
      clamped::emit_clamped(cat, ds, opt.out);  // appends to the manifest
      emit_rules(cat, ds, opt.out);             // bivariate rules and Rule 2 (after the manifest)
      emit_s = std::chrono::duration<double>(clock::now() - t3).count();
    }
    if (!opt.quiet)
      for (const auto& n : nd)
        out << "not derived: " << n.kernel << " " << n.atomic << (n.squared ? "^2" : "") << ": " << n.reason
            << "\n";
    auto sec = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
    err << "rulegen: " << cat.atomics.size() << " atomics, " << ds.size() << " entries (" << nd.size()
        << " not derivable, see the manifest); catalog " << sec(t0, t1) << " s, derive " << sec(t1, t2)
        << " s"
        << (!opt.out.empty() ? ", emit " + std::to_string(emit_s) + " s into " + opt.out : std::string())
        << "\n";
  } catch (const sym::CatalogError& e) {
    err << "rulegen: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    err << "rulegen: internal error: " << e.what() << "\n";
    return 3;
  }
  return 0;
}

}  // namespace bl::rulegen
