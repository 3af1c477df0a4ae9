// rulegen: derive the smoothed atomic-function table from the catalog and emit it.
//   rulegen derive [--catalog FILE]          derive and print every formula
//   rulegen emit   [--catalog FILE] --out DIR derive and write C++, GLSL and manifest.json
// Exit status: 0 done, 2 the catalog is wrong (the message names file, entry and field), 3 a bug.
#include <CLI/CLI.hpp>
#include <iostream>

#include "pipeline.hpp"

int main(int argc, char** argv) {
  CLI::App app{"rulegen: derive, and emit the bandlimit smoothing table"};
  app.require_subcommand(1);
  bl::rulegen::Options opt;
  opt.catalog = BL_DEFAULT_CATALOG;
  std::string out = "generated";
  auto* derive = app.add_subcommand("derive", "derive every entry and print its formula");
  auto* emit = app.add_subcommand("emit", "derive and write generated/ (C++, GLSL, manifest)");
  for (auto* sc : {derive, emit}) {
    sc->add_option("--catalog", opt.catalog, "catalog JSON")->check(CLI::ExistingFile);
    sc->add_flag("--quiet", opt.quiet, "print only the summary");
  }
  emit->add_option("--out", out, "output directory (generated/)");
  emit->add_option("--catalog-label", opt.label, "catalog path recorded in the manifest");
  CLI11_PARSE(app, argc, argv);
  if (emit->parsed()) opt.out = out;
  return bl::rulegen::run(opt, std::cout, std::cerr);
}
