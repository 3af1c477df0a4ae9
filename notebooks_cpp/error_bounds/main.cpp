// Notebook: docs/error_bounds.md, generated from generated/manifest.json (the verifier's records),
// so every measured number it quotes is the manifest's. Also draws docs/notebooks/error_bounds.png
// (each entry's worst error against the bounds).
#include <algorithm>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "notebook.hpp"
#include "plot.hpp"

namespace {

using nlohmann::json;
const std::string kName = "error_bounds";

struct Row {
  std::string atomic, kernel, rule, cpp, status;
  bool squared;
  int points, skipped;
  double err_d, err_f, bound_d, bound_f, formula50;
};

double num_or_nan(const json& v, const char* key) {
  return v.contains(key) && v[key].is_number() ? v[key].get<double>() : NAN;
}

std::vector<Row> load(const json& m) {
  std::vector<Row> rows;
  for (const json& e : m.at("entries")) {
    const json& v = e.value("verification", json::object());
    rows.push_back({e.value("atomic", "?"), e.value("kernel", "?"), e.value("rule", "?"), e.value("cpp", "?"),
                    v.value("status", "unverified"), e.value("squared", false), v.value("points", 0),
                    v.value("skipped", 0), num_or_nan(v, "worst_rel_error_double"),
                    num_or_nan(v, "worst_rel_error_float"), num_or_nan(v, "bound_double"),
                    num_or_nan(v, "bound_float"), num_or_nan(v, "formula_error_50digits")});
  }
  return rows;
}

// The distinct values of a field, as text ("1e-09" or "1e-09, 1e-08").
std::string distinct(const std::vector<Row>& rows, double Row::*m) {
  std::vector<double> vs;
  for (const Row& r : rows)
    if (!std::isnan(r.*m) && std::find(vs.begin(), vs.end(), r.*m) == vs.end()) vs.push_back(r.*m);
  std::string s;
  for (double v : vs) s += (s.empty() ? "" : ", ") + nb::sci(v, 2);
  return s;
}

const Row& worst(const std::vector<Row>& rows, double Row::*m) {
  return *std::max_element(rows.begin(), rows.end(), [m](const Row& a, const Row& b) {
    return std::isnan(a.*m) || (!std::isnan(b.*m) && a.*m < b.*m);
  });
}

std::string label(const Row& r) {
  return r.cpp + (r.rule == "moment" ? "" : r.squared ? " (f^2)" : "");
}

void plot(const std::string& png, const std::vector<Row>& rows) {
  std::vector<std::vector<double>> d;
  for (size_t i = 0; i < rows.size(); ++i) d.push_back({double(i + 1), rows[i].err_d, rows[i].err_f});
  std::ostringstream s;
  s << nb::datablock("d", d) << "set terminal pngcairo size 1500,600 font 'Sans,11'\n"
    << "set output '" << png << "'\n"
    << "set title 'generated/manifest.json: worst verified error of every entry (blverify) against the "
       "bounds'\n"
    << "set logscale y\nset format y '10^{%L}'\nset grid\nset yrange [1e-18:1e-3]\nset xrange [0:"
    << rows.size() + 1
    << "]\nset xlabel 'entry (manifest order)'\nset ylabel 'worst |error| / max(1, |ref|)'\nset key top "
       "left\n"
    << "plot $d u 1:3 w p pt 7 ps 0.6 lc rgb '#ff7f0e' t 'float', $d u 1:2 w p pt 7 ps 0.6 lc rgb '#1f77b4' "
       "t "
       "'double', "
    << worst(rows, &Row::bound_f).bound_f << " w l dt 2 lc rgb '#ff7f0e' t 'float bound', "
    << worst(rows, &Row::bound_d).bound_d << " w l dt 2 lc rgb '#1f77b4' t 'double bound'\n";
  nb::run_gnuplot(s.str());
}

}  // namespace

int main(int argc, char** argv) {
  const std::string docs = nb::docs_dir(argc, argv);
  const std::string manifest_path = argc > 2 ? argv[2] : BL_MANIFEST;
  nb::progress(kName, "reading " + manifest_path);
  std::ifstream in(manifest_path);
  if (!in) {
    std::cerr << "cannot read " << manifest_path << "\n";
    return 1;
  }
  const json m = json::parse(in);
  const std::vector<Row> rows = load(m);
  plot(docs + "/notebooks/error_bounds.png", rows);
  nb::Markdown md(docs + "/error_bounds.md");

  std::map<std::string, int> status;
  for (const Row& r : rows) ++status[r.status];
  std::string counts;
  for (const auto& [k, n] : status) counts += (counts.empty() ? "" : ", ") + std::to_string(n) + " " + k;
  const Row& wd = worst(rows, &Row::err_d);
  const Row& wf = worst(rows, &Row::err_f);
  const Row& w50 = worst(rows, &Row::formula50);

  md << "# Error bounds: what the generated table promises\n\n"
     << "Generated from `generated/manifest.json` by `notebooks_cpp/error_bounds/` (run: `cmake --build "
        "build "
        "--target notebook_error_bounds`); do not edit by hand. Every measured number here is the verifier's "
        "record in the manifest (`blverify --record`, `rulegen/verify/`), quoted, not re-measured.\n\n"
     << "## The promise\n\n"
     << "For every entry `bl::<kernel>::<f>(x, sigma)` (and its `_sq`, and the moments), at every (x, sigma) "
        "of "
        "the verification grid (x far out, at and next to every jump, kink and singularity, sigma from tiny "
        "to "
        "huge; docs/derivations.md, *Error bounds*, gives its ranges):\n\n"
     << "- **double**: |value - ref| / max(1, |ref|) <= **" << distinct(rows, &Row::bound_d) << "**;\n"
     << "- **float**: the same measure <= **" << distinct(rows, &Row::bound_f)
     << "**, the reference taken at the float-rounded inputs (a float caller cannot ask for more: the input "
        "itself carries the rounding);\n"
     << "- no NaN or infinity where the reference is finite, and values inside the atomic's range.\n\n"
     << "The measure is relative where |ref| >= 1 and absolute below: smoothed functions cross zero (sin, "
        "fract - 1/2, sign), where a relative error means nothing, and a tiny value next to values of size 1 "
        "needs no relative accuracy in a shader. `ref` is Boost.Math quadrature split at every "
        "break, in double and at 50 digits where double cannot decide; it is independent of the "
        "derivation.\n\n"
     << "What it does not promise:\n\n"
     << "- that the kernel is the right one: box and tent approximate a Gaussian footprint with their own "
        "shape, and their error *as a Gaussian* is not bounded (docs/notebooks/fract_gaussian.md measures it "
        "for "
        "fract);\n"
     << "- anything outside the grid's ranges (for float, periodic arguments are checked only as far out as "
        "the "
        "float argument itself still resolves the period: beyond, the input's own rounding exceeds the "
        "bound);\n"
     << "- the GLSL include to the float bound everywhere: it is the same code in float, but the C++ float "
        "entries of the compact kernels (tan, tanh, log, sqrt, inv, inv2) evaluate in double next to a "
        "singularity, where GLSL cannot; there the GLSL versions lose accuracy as the distance to the "
        "singularity shrinks (docs/derivations.md gives the distance).\n\n"
     << "`formula_error_50digits` is a separate record: the derived formula evaluated at 50 digits against "
        "the "
        "50-digit quadrature, so it measures the mathematics, not the rounding of the emitted code. Entries "
        "whose "
        "emitted code sums a truncated series (periodic Gaussians) show the truncation tolerance there.\n\n";

  md << "## Measured, over all " << rows.size() << " entries\n\n"
     << "- status: " << counts << ";\n"
     << "- worst double error: **" << nb::sci(wd.err_d) << "** (" << label(wd) << "), bound "
     << nb::sci(wd.bound_d, 1) << ", margin " << nb::fixed(wd.bound_d / wd.err_d, 1) << "x;\n"
     << "- worst float error: **" << nb::sci(wf.err_f) << "** (" << label(wf) << "), bound "
     << nb::sci(wf.bound_f, 1) << ", margin " << nb::fixed(wf.bound_f / wf.err_f, 1) << "x;\n"
     << "- worst 50-digit formula error: " << nb::sci(w50.formula50) << " (" << label(w50) << ").\n\n"
     << "![worst error per entry](notebooks/error_bounds.png)\n\n";

  // Worst per kernel, then the full table.
  std::map<std::string, std::pair<double, double>> per_kernel;
  for (const Row& r : rows) {
    auto& w = per_kernel[r.kernel];
    w.first = std::max(w.first, r.err_d), w.second = std::max(w.second, r.err_f);
  }
  std::vector<std::vector<std::string>> kr;
  for (const auto& [k, w] : per_kernel) kr.push_back({k, nb::sci(w.first), nb::sci(w.second)});
  md << "### Worst per kernel\n\n";
  md.table({"kernel", "worst double", "worst float"}, kr);

  md << "### Every entry\n\n";
  std::vector<std::vector<std::string>> tr;
  for (const Row& r : rows)
    tr.push_back({"`" + r.cpp + "`", r.rule == "moment" ? "-" : (r.squared ? "f^2" : "f"), r.rule,
                  std::to_string(r.points), std::to_string(r.skipped), nb::sci(r.err_d), nb::sci(r.err_f),
                  nb::sci(r.formula50), r.status});
  md.table({"entry", "of", "rule", "points", "skipped", "worst double", "worst float", "formula at 50 digits",
            "status"},
           tr);

  md << "## Not derived (no entry, so no promise)\n\n";
  std::vector<std::vector<std::string>> nd;
  for (const json& e : m.value("not_derived", json::array()))
    nd.push_back({e.value("atomic", "?"), e.value("kernel", "?"), e.value("squared", false) ? "f^2" : "f",
                  e.value("reason", "")});
  md.table({"atomic", "kernel", "of", "reason"}, nd);
  nb::progress(kName, "wrote " + md.path());
  return 0;
}
