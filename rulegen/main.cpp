// rulegen: derive the smoothed atomic-function table from the catalog and emit it.
//   rulegen derive [--catalog FILE]          derive and print every formula
//   rulegen emit   [--catalog FILE] --out DIR derive and write C++, GLSL and manifest.json
#include <CLI/CLI.hpp>

#include <chrono>
#include <iostream>

#include "catalog.hpp"
#include "clamped/emit_clamped.hpp"
#include "derived.hpp"
#include "emit_common.hpp"
#include "emit_rules.hpp"

int main(int argc, char** argv) {
  CLI::App app{"rulegen: derive, and emit the bandlimit smoothing table"};
  app.require_subcommand(1);
  std::string catalog = BL_DEFAULT_CATALOG, out = "generated", label = "symbolic/catalog.json";
  bool quiet = false;
  auto* derive = app.add_subcommand("derive", "derive every entry and print its formula");
  auto* emit = app.add_subcommand("emit", "derive and write generated/ (C++, GLSL, manifest)");
  for (auto* sc : {derive, emit}) {
    sc->add_option("--catalog", catalog, "catalog JSON")->check(CLI::ExistingFile);
    sc->add_flag("--quiet", quiet, "print only the summary");
  }
  emit->add_option("--out", out, "output directory (generated/)");
  emit->add_option("--catalog-label", label, "catalog path recorded in the manifest");
  CLI11_PARSE(app, argc, argv);

  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  try {
    const bl::sym::Catalog cat = bl::sym::load_catalog(catalog);
    const auto t1 = clock::now();
    std::vector<bl::sym::NotDerived> nd;
    const auto ds = bl::sym::derive_all(cat, 16, &nd);
    const auto t2 = clock::now();
    if (!quiet)
      for (const auto& d : ds)
        std::cout << d.cpp_name() << (d.rule == "moment" ? "(" + std::to_string(d.order) + ")" : "") << " = "
                  << d.formula << "\n";
    double emit_s = 0;
    if (emit->parsed()) {
      const auto t3 = clock::now();
      bl::rulegen::emit_cpp(cat, ds, out);
      bl::rulegen::emit_glsl(cat, ds, out);
      bl::rulegen::emit_manifest(cat, ds, nd, out, label);
      bl::rulegen::clamped::emit_clamped(cat, ds, out);  // appends to the manifest
      bl::rulegen::emit_rules(cat, ds, out);  // bivariate rules and Rule 2 (after the manifest)
      emit_s = std::chrono::duration<double>(clock::now() - t3).count();
    }
    if (!quiet)
      for (const auto& n : nd)
        std::cout << "not derived: " << n.kernel << " " << n.atomic << (n.squared ? "^2" : "") << ": " << n.reason << "\n";
    auto sec = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
    std::cerr << "rulegen: " << cat.atomics.size() << " atomics, " << ds.size() << " entries (" << nd.size() << " not derivable, see the manifest); catalog "
              << sec(t0, t1) << " s, derive " << sec(t1, t2) << " s"
              << (emit->parsed() ? ", emit " + std::to_string(emit_s) + " s into " + out : std::string()) << "\n";
  } catch (const bl::sym::CatalogError& e) {
    std::cerr << "rulegen: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "rulegen: internal error: " << e.what() << "\n";
    return 3;
  }
  return 0;
}
