// Notebook: accuracy against time, the tables a user reads before choosing a rule. (1) every entry
// of the generated table, from the benchmark's docs/accuracy_cost.csv (bench_table --summary);
// (2) the 21-scene suite, from the tuner's output directory (bltune --suite DIR: DIR/<scene>/result.json).
// Usage: nb_accuracy_time [docs_dir] [suite_dir] (default suite_dir: <docs_dir>/tuning/suite).
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "bench_csv.hpp"
#include "families.hpp"
#include "notebook.hpp"
#include "plot.hpp"
#include "plots.hpp"
#include "suite.hpp"

namespace {

namespace acc = nb::acc;
const std::string kName = "accuracy_time";
const std::vector<double> kTargets = {0.3, 0.1, 0.03, 0.01, 1e-3, 1e-6};

// A path as the Markdown shows it: relative to the source tree when inside it.
std::string shown(const std::string& path) {
  const std::string root = std::string(BL_SOURCE_DIR) + "/";
  return path.compare(0, root.size(), root) == 0 ? path.substr(root.size()) : path;
}

std::string ns_cell(double ns) {
  return ns < 10 ? nb::fixed(ns, 1) : nb::fixed(ns, 0);
}

struct EntriesSummary {
  std::vector<acc::EntryRow> rows;
  std::vector<acc::FamilyStats> fams;
  std::map<int, int> smoothed_from;  // target index -> families where smoothing is cheapest
  std::vector<std::pair<std::string, std::string>> cheapest_kernel;  // family -> kernel
};

EntriesSummary entries_section(nb::Markdown& md, const std::string& dir, const std::string& csv) {
  EntriesSummary out;
  const std::vector<acc::EntryRow> rows = acc::read_accuracy_csv(csv);
  out.rows = rows;
  std::vector<acc::FamilyStats>& fams = out.fams;
  for (const std::string& f : acc::families_in_order(rows)) fams.push_back(acc::family_stats(rows, f));
  md << "## Every table entry (`" << shown(csv) << "`, " << rows.size() << " entries)\n\n"
     << "Per entry the benchmark times the plain function, the smoothed entry (double and float) and Monte "
        "Carlo "
        "with 4/16/64 samples of the entry's kernel on the same 256 (x, sigma) pairs (x uniform in [-4, 4], "
        "sigma log-uniform in [0.01, 1], as `docs/accuracy_cost.md` states), and measures RMS errors against "
        "the double smoothed entry (exact to blverify's 1e-9, so its own error is not measured). "
        "Errors here are relative: divided by the RMS of the exact smoothed values. See "
        "`docs/accuracy_cost.md` for the run (machine, repetitions); the machine is shared, single rows are "
        "noisy, medians are not.\n\n";
  const std::string png = kName + "_entries.png";
  nb::progress(kName, "plotting " + png);
  nb::run_gnuplot(acc::entries_script(dir + png, rows, fams));
  md << "![ns per call against relative error, every entry, families coloured](" << png << ")\n\n";

  md << "### Medians per family\n\n";
  std::vector<std::vector<std::string>> t;
  for (const acc::FamilyStats& f : fams) {
    std::vector<std::string> r = {f.family, std::to_string(f.entries)};
    for (int w : {acc::kPlain, acc::kSmoothed, acc::kSmoothedF32, acc::kMc4, acc::kMc16, acc::kMc64})
      r.push_back(ns_cell(f.ns[w]));
    for (int w : {acc::kPlain, acc::kMc4, acc::kMc16, acc::kMc64, acc::kSmoothedF32})
      r.push_back(nb::sci(f.err[w]));
    t.push_back(r);
  }
  md.table({"family", "entries", "ns plain", "ns smoothed", "ns smoothed float", "ns MC-4", "ns MC-16",
            "ns MC-64", "rel. err plain", "MC-4", "MC-16", "MC-64", "smoothed float"},
           t);

  md << "### Which kernel is cheapest, per family (median ns of the smoothed entry, double)\n\n";
  t.clear();
  std::vector<std::string> kernels;
  for (const acc::EntryRow& r : rows)
    if (std::find(kernels.begin(), kernels.end(), r.kernel) == kernels.end()) kernels.push_back(r.kernel);
  std::vector<std::string> header = {"family"};
  for (const std::string& k : kernels) header.push_back(k);
  header.push_back("cheapest");
  for (const acc::FamilyStats& f : fams) {
    std::vector<std::string> r = {f.family};
    std::string best;
    double best_ns = INFINITY;
    for (const std::string& k : kernels) {
      const acc::FamilyStats fk = acc::family_stats(rows, f.family, k);
      r.push_back(fk.entries ? ns_cell(fk.ns[acc::kSmoothed]) : "-");
      if (fk.entries && fk.ns[acc::kSmoothed] < best_ns) {
        best_ns = fk.ns[acc::kSmoothed];
        best = k;
      }
    }
    r.push_back(best);
    out.cheapest_kernel.push_back({f.family, best});
    t.push_back(r);
  }
  md.table(header, t);
  md << "(Gaussian entries of the singular family do not exist in the table: tan, tanh, log, sqrt, inv, inv2 "
        "get "
        "their Gaussian from the rules.) The kernels are not interchangeable in accuracy: they are different "
        "filters (box and tent alias more than the Gaussian, see the Fig. 3 notebook's box curve).\n\n";

  md << "### The cheapest way to reach a relative error (family medians)\n\n"
     << "Cell: the cheapest of plain f, MC-4/16/64 and the smoothed entry (all in double; the smoothed entry "
        "counted as 1e-9, blverify's bound) whose median relative error is at most the target, and its "
        "median "
        "ns. Last columns: Monte Carlo samples for 1e-3, extrapolated from MC-64 as 1/sqrt(N), and "
        "what they would cost against the smoothed entry (double).\n\n";
  t.clear();
  header = {"family"};
  for (const double T : kTargets) header.push_back("<= " + nb::num(T));
  header.push_back("MC samples for 1e-3");
  header.push_back("that MC / smoothed time");
  std::map<int, int>& smoothed_from = out.smoothed_from;
  for (const acc::FamilyStats& f : fams) {
    std::vector<std::string> r = {f.family};
    for (std::size_t i = 0; i < kTargets.size(); ++i) {
      const int w = acc::cheapest_way(f, kTargets[i]);
      r.push_back(w < 0 ? "none" : std::string(acc::way_name(w)) + ", " + ns_cell(f.ns[w]));
      if (w == acc::kSmoothed) ++smoothed_from[static_cast<int>(i)];
    }
    const double n = acc::mc_samples_for(f, 1e-3);
    r.push_back(nb::sci(n));
    r.push_back(nb::sci(f.ns[acc::kMc64] * n / 64 / f.ns[acc::kSmoothed]) + "x");
    t.push_back(r);
  }
  md.table(header, t);
  md << "Families whose cheapest way to each target is the smoothed entry: ";
  for (std::size_t i = 0; i < kTargets.size(); ++i)
    md << (i ? ", " : "") << "<= " << nb::num(kTargets[i]) << ": " << smoothed_from[static_cast<int>(i)]
       << " of " << fams.size();
  md << ".\n\n";

  // The most expensive smoothed entries relative to the plain function.
  std::vector<const acc::EntryRow*> by_ratio;
  for (const acc::EntryRow& r : rows) by_ratio.push_back(&r);
  std::sort(by_ratio.begin(), by_ratio.end(), [](const acc::EntryRow* a, const acc::EntryRow* b) {
    return a->smoothed_ns / a->plain_ns > b->smoothed_ns / b->plain_ns;
  });
  md << "### The ten entries whose smoothing costs most against the plain function\n\n";
  t.clear();
  for (std::size_t i = 0; i < std::min<std::size_t>(10, by_ratio.size()); ++i) {
    const acc::EntryRow& r = *by_ratio[i];
    t.push_back({"`" + r.entry + "`", r.family, ns_cell(r.plain_ns), ns_cell(r.smoothed_ns),
                 nb::fixed(r.smoothed_ns / r.plain_ns, 1) + "x", ns_cell(r.mc_ns[1]),
                 nb::sci(r.err_mc[1] / r.ref_rms)});
  }
  md.table({"entry", "family", "ns plain", "ns smoothed", "smoothed / plain", "ns MC-16", "MC-16 rel. err"},
           t);
  return out;
}

std::string mix_text(const std::map<std::string, double>& mix) {
  std::vector<std::pair<double, std::string>> v;
  for (const auto& [k, x] : mix) v.push_back({-x, k});
  std::sort(v.begin(), v.end());
  std::string s;
  for (std::size_t i = 0; i < v.size() && i < 3; ++i)
    s += std::string(i ? ", " : "") + v[i].second + " " + nb::fixed(-100 * v[i].first, 0) + "%";
  return s;
}

struct SuiteSummary {
  int scenes = 0, reach16 = 0, winners = 0;
  double median16 = NAN, median16_eval = NAN;
  std::string winning_mix;
  std::string top_smoothing;  // the most used rule family other than none in those schedules
  double none_share = 0;
};

SuiteSummary suite_section(nb::Markdown& md, const std::string& dir, const acc::Suite& su) {
  SuiteSummary out;
  md << "## The 21-scene suite (tuner output: `" << shown(su.dir) << "`)\n\n";
  if (!su.found || su.scenes.empty()) {
    md << "**No suite results at `" << shown(su.dir) << "`** ("
       << (su.found ? "the directory holds no <scene>/result.json" : "the directory does not exist")
       << "). Run `build/bin/bltune --suite scenes/suite --out " << shown(su.dir)
       << "` (about an hour on 2 cores), or pass the output directory as the second argument: "
          "`build/bin/nb_accuracy_time docs <suite_dir>`.\n\n";
    return out;
  }
  md << su.scenes.size() << " of " << su.scenes.size() + su.missing.size() << " scenes have results";
  if (!su.missing.empty()) {
    md << "; missing (not finished, or not run): ";
    for (std::size_t i = 0; i < su.missing.size(); ++i) md << (i ? ", " : "") << su.missing[i];
  }
  md << ". Time is the tuner's cost model (ns per pixel; deterministic) unless a column says evaluator (the "
        "batch evaluator, measured, all threads); error is RMS in display space over every pixel of every "
        "frame against the cached ground truth. Speed-up at MSAA-n: MSAA-n's time over the fastest front "
        "point "
        "whose error is at most MSAA-n's (the tuner's `speedups`).\n\n";

  std::vector<std::vector<std::string>> t;
  int reach16 = 0;
  std::vector<double> sp16, sp16_eval, best_ratio;
  std::map<std::string, double> winning_mix;  // summed over the points that beat MSAA at equal error
  int winners = 0;
  std::map<int, int> highest_level;  // highest MSAA level reached -> scenes
  for (const auto& r : su.scenes) {
    const bl::tuner::Measured* m16 = acc::msaa(r, 16);
    double best = INFINITY;
    for (const auto& p : r.front) best = std::min(best, p.error);
    const bl::tuner::Speedup s16 = acc::speedup_at(r, 16);
    int hi = 0;
    double hi_model = NAN, hi_eval = NAN;
    for (const bl::tuner::Speedup& s : bl::tuner::speedups(r)) {
      if (s.front_index < 0) continue;
      if (s.msaa > hi) {
        hi = s.msaa;
        hi_model = s.model;
        hi_eval = s.measured;
      }
      if (s.model > 1) {
        for (const auto& [k, x] : r.front[s.front_index].mix) winning_mix[k] += x;
        ++winners;
      }
    }
    ++highest_level[hi];
    if (s16.front_index >= 0) {
      ++reach16;
      sp16.push_back(s16.model);
      sp16_eval.push_back(s16.measured);
    }
    if (m16) best_ratio.push_back(best / m16->error);
    t.push_back({r.scene, std::to_string(r.nodes), std::to_string(r.front.size()),
                 m16 ? nb::fixed(m16->error, 4) : "-", nb::fixed(best, 4),
                 s16.front_index >= 0 ? nb::fixed(s16.model, 1) + "x / " + nb::fixed(s16.measured, 1) + "x"
                                      : "not reached",
                 hi ? "MSAA-" + std::to_string(hi) + ": " + nb::fixed(hi_model, 1) + "x / " +
                          nb::fixed(hi_eval, 1) + "x"
                    : "none",
                 mix_text(r.front.back().mix)});
  }
  md.table(
      {"scene", "nodes", "front", "MSAA-16 RMS", "best front RMS", "speed-up at MSAA-16 error (model / eval)",
       "highest MSAA level reached: speed-up", "rule mix of the most accurate point"},
      t);

  const std::string sp_png = kName + "_speedup.png", fr_png = kName + "_fronts.png";
  nb::progress(kName, "plotting " + sp_png + ", " + fr_png);
  nb::run_gnuplot(acc::speedup_script(dir + sp_png, su));
  nb::run_gnuplot(acc::fronts_script(dir + fr_png, su));
  md << "![speed-up at equal error per scene](" << sp_png << ")\n\n"
     << "![all fronts, normalized by MSAA-16](" << fr_png << ")\n\n";

  md << "### Reading the suite\n\n"
     << "- " << reach16 << " of " << su.scenes.size()
     << " scenes have a front point at or below MSAA-16's error";
  if (reach16)
    md << "; there the median speed-up is " << nb::fixed(acc::median(sp16), 1) << "x (cost model), "
       << nb::fixed(acc::median(sp16_eval), 1) << "x (evaluator)";
  md << ". Highest MSAA level reached at equal error, scenes: ";
  bool first = true;
  for (const auto& [lvl, n] : highest_level) {
    md << (first ? "" : ", ") << (lvl ? "MSAA-" + std::to_string(lvl) : std::string("none")) << " " << n;
    first = false;
  }
  md << ".\n- The most accurate front point has " << nb::fixed(acc::median(best_ratio), 2)
     << "x MSAA-16's error (median over scenes; below 1 means the front gets below MSAA-16's error at "
        "all).\n";
  if (winners) {
    for (auto& [k, x] : winning_mix) x /= winners;
    md << "- Rules in the front points that beat MSAA at equal error (" << winners
       << " (scene, MSAA level) pairs with speed-up > 1, share of genes averaged): " << mix_text(winning_mix)
       << ".\n";
  }
  md << "\n";
  out.scenes = static_cast<int>(su.scenes.size());
  out.reach16 = reach16;
  out.winners = winners;
  if (reach16) {
    out.median16 = acc::median(sp16);
    out.median16_eval = acc::median(sp16_eval);
  }
  if (winners) {
    out.winning_mix = mix_text(winning_mix);
    double top = 0;
    for (const auto& [k, x] : winning_mix)
      if (k != "none" && x > top) top = x, out.top_smoothing = k;
    out.none_share = winning_mix.count("none") ? winning_mix.at("none") : 0;
  }
  return out;
}

void choose_section(nb::Markdown& md, const EntriesSummary& e, const SuiteSummary& s) {
  md << "## How to choose a rule (from the numbers above)\n\n";
  // The loosest target from which on the smoothed entry is the cheapest way for every family.
  int all_from = -1;
  for (int i = static_cast<int>(kTargets.size()) - 1; i >= 0; --i) {
    const auto it = e.smoothed_from.find(i);
    if (it == e.smoothed_from.end() || it->second != static_cast<int>(e.fams.size())) break;
    all_from = i;
  }
  double mc_lo = INFINITY, mc_hi = 0, ratio_lo = INFINITY, ratio_hi = 0, f32_lo = INFINITY, f32_hi = 0;
  std::string mc_lo_f, mc_hi_f, ratio_lo_f, ratio_hi_f;
  for (const acc::FamilyStats& f : e.fams) {
    const double m = f.err[acc::kMc64], r = f.ns[acc::kSmoothed] / f.ns[acc::kPlain];
    if (m < mc_lo) mc_lo = m, mc_lo_f = f.family;
    if (m > mc_hi) mc_hi = m, mc_hi_f = f.family;
    if (r < ratio_lo) ratio_lo = r, ratio_lo_f = f.family;
    if (r > ratio_hi) ratio_hi = r, ratio_hi_f = f.family;
    f32_lo = std::min(f32_lo, f.err[acc::kSmoothedF32]);
    f32_hi = std::max(f32_hi, f.err[acc::kSmoothedF32]);
  }
  md << "- **One function**: ";
  if (all_from >= 0)
    md << "for a relative error of " << nb::num(kTargets[all_from])
       << " or less the smoothed entry is the cheapest way for every family; ";
  md << "Monte Carlo with 64 samples still has a median relative error of " << nb::sci(mc_lo) << " ("
     << mc_lo_f << ") to " << nb::sci(mc_hi) << " (" << mc_hi_f << "), and the smoothed entry costs "
     << nb::fixed(ratio_lo, 1) << "x (" << ratio_lo_f << ") to " << nb::fixed(ratio_hi, 1) << "x ("
     << ratio_hi_f
     << ") the plain function (family medians). Only where a loose error is acceptable is the plain function "
        "(no smoothing) cheaper: ";
  std::string loose;
  for (const acc::FamilyStats& f : e.fams)
    if (acc::cheapest_way(f, kTargets.front()) == acc::kPlain)
      loose += std::string(loose.empty() ? "" : ", ") + f.family + " (plain error " +
               nb::sci(f.err[acc::kPlain]) + ")";
  md << (loose.empty() ? "no family" : loose) << ".\n";
  md << "- **Kernel**: the cheapest smoothed entry per family is ";
  for (std::size_t i = 0; i < e.cheapest_kernel.size(); ++i)
    md << (i ? ", " : "") << e.cheapest_kernel[i].second << " for " << e.cheapest_kernel[i].first;
  md << "; the Gaussian entries of the periodic functions (fract, floor, square, ...) are the expensive ones "
        "(table above), so box (or tent) is the choice there unless the Gaussian's better frequency response "
        "matters.\n";
  md << "- **Float**: the smoothed entries in float carry a median relative error of " << nb::sci(f32_lo)
     << " to " << nb::sci(f32_hi)
     << " per family, far below any antialiasing error: float is enough for shading.\n";
  md << "- **A whole shader**: composing the entries compounds their approximations, so per-entry exactness "
        "does not carry over; the tuner's fronts decide. ";
  if (s.scenes == 0) {
    md << "No suite results were found (see above).\n";
  } else {
    md << s.reach16 << " of " << s.scenes << " scenes reach MSAA-16's error";
    if (s.reach16)
      md << " (median speed-up there " << nb::fixed(s.median16, 1) << "x model, "
         << nb::fixed(s.median16_eval, 1) << "x evaluator)";
    if (s.winners)
      md << "; where the front beats MSAA at equal error its schedules are mostly " << s.winning_mix
         << " (share of nodes): " << nb::fixed(100 * s.none_share, 0)
         << "% of the nodes stay plain and the most used smoothing rule is " << s.top_smoothing;
    md << ". So: run `bltune` on the shader and take the front point at the error you need"
       << (s.winners
               ? "; by hand, start from a schedule that leaves about " + nb::fixed(100 * s.none_share, 0) +
                     "% of the nodes plain and smooths with " + s.top_smoothing + " where the shader aliases"
               : "")
       << ".\n";
  }
  md << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  const std::string docs = nb::docs_dir(argc, argv);
  const std::string dir = docs + "/notebooks/";
  const std::string suite_dir = argc > 2 ? argv[2] : docs + "/tuning/suite";
  nb::Markdown md(dir + kName + ".md");
  md << "# Accuracy against time: every table entry, and the 21-scene suite\n\n"
     << "What a user reads before choosing a rule: how much each way of smoothing costs and how accurate it "
        "is, per function (the benchmark of the generated table) and per shader (the tuner's Pareto fronts "
        "against MSAA). Every number below is read from those two outputs by this run; rerun the notebook "
        "after rerunning them.\n\n";
  nb::progress(kName, "table entries");
  const EntriesSummary entries = entries_section(md, dir, docs + "/accuracy_cost.csv");
  nb::progress(kName, "suite " + suite_dir);
  const acc::Suite su = acc::read_suite(suite_dir, std::string(BL_SOURCE_DIR) + "/scenes/suite");
  if (!su.found) nb::progress(kName, "no suite results at " + suite_dir + " (see the Markdown)");
  const SuiteSummary suite = suite_section(md, dir, su);
  choose_section(md, entries, suite);
  nb::progress(kName, "done");
  return 0;
}
