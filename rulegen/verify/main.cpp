// blverify: verifies every entry of a generated table (any tree `rulegen emit` wrote, without
// rebuilding blverify: tree_loader.hpp) against independent quadrature references, and (--published) the
// published tables of Dorn et al. 2015 and Yang & Barnes 2018.
//
//   blverify [--generated DIR] [--record] [--only NAME]... [--threads N] [--report FILE.md] [--verbose]
//   blverify --published [--report FILE.md]
//
// stdout is deterministic (registry order, errors rounded to 2 digits); progress and the total
// time go to stderr. Exit status: 0 all pass, 1 an entry failed (named on stderr), 2 usage/setup.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "clamped/verify_clamped.hpp"
#include "manifest_record.hpp"
#include "published_tables.hpp"
#include "reference_mp.hpp"
#include "registry_view.hpp"
#include "report.hpp"
#include "rules_check.hpp"
#include "stat_check.hpp"
#include "tree_loader.hpp"
#include "verify_entry.hpp"

#ifndef BLVERIFY_GENERATED_DIR
#define BLVERIFY_GENERATED_DIR "generated"
#endif

namespace {

bool selected(const blv::EntryView& e, const std::vector<std::string>& only) {
  if (only.empty()) return true;
  for (const auto& n : only)
    if (e.cpp == n || e.atomic == n || e.cpp.find(n) != std::string::npos) return true;
  return false;
}

bool write_file(const std::string& path, const std::string& text) {
  std::ofstream o(path, std::ios::binary | std::ios::trunc);
  return o && (o << text) && o.flush();
}

// Cost estimate, so the slow entries start first (results do not depend on the order).
double cost(const blv::EntryView& e) {
  return (e.spec.period > 0 ? 4.0 : 1.0) * (1.0 + e.spec.breaks.size()) * (e.squared ? 1.5 : 1.0);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"blverify: verify the generated bandlimit table against quadrature"};
  std::string generated = BLVERIFY_GENERATED_DIR, report;
  bool record = false, published = false, verbose = false, no_mp = false;
  std::vector<std::string> only;
  unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  app.add_option(
      "--generated", generated,
      "generated tree to verify (any `rulegen emit` output): its manifest.json is read (and written by "
      "--record); its registry is the plugin CMake built when the tree is the one blverify was built "
      "against, else compiled at run time and cached by content hash (tree_loader.hpp)");
  app.add_flag("--record", record, "write each entry's verification record into manifest.json");
  app.add_option("--only", only, "verify only entries whose C++ name or atomic matches (repeatable)");
  app.add_option("--threads", threads, "worker threads (default: all cores)")->check(CLI::Range(1u, 256u));
  app.add_option("--report", report, "also write a Markdown report");
  app.add_flag("--published", published, "compare the published tables (Dorn 2015, Yang & Barnes 2018)");
  app.add_flag("--verbose", verbose, "details for every entry");
  app.add_flag("--no-mp", no_mp, "no 50-digit references (faster, for development)");
  bool rules_only = false;
  app.add_flag("--rules-only", rules_only,
               "only the checks of the bivariate rules and Rule 2 (rules_check.hpp)");
  CLI11_PARSE(app, argc, argv);
  {
    std::string why;
    if (!blv::load_tree(generated, &why) && !published) {  // --published also runs without a tree
      std::fprintf(stderr, "blverify: %s\n", why.c_str());
      return 2;
    }
  }
  if (rules_only) return blv::run_rule_checks(generated + "/manifest.json", record, 0);

  const auto t0 = std::chrono::steady_clock::now();
  std::string error;
  std::vector<blv::EntryView> entries = blv::load_registry(&error);
  if (!error.empty() && !(published && !blv::registry_compiled_in())) {
    std::fprintf(stderr, "blverify: %s\n", error.c_str());
    return 2;
  }
  if (blv::registry_compiled_in() && !blv::mp_registry_matches(entries, &error)) {
    std::fprintf(stderr, "blverify: %s\n", error.c_str());
    return 2;
  }

  if (published) {
    int rc = blv::run_published(entries, report, stdout);
    std::fflush(stdout);
    std::fprintf(stderr, "blverify --published: %.1f s\n",
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    return rc;
  }

  const std::string manifest = generated + "/manifest.json";
  {
    std::vector<int> match;
    std::vector<std::string> warnings;
    bool ok = blv::match_manifest(manifest, entries, &match, &warnings);
    for (const auto& w : warnings) std::fprintf(stderr, "blverify: warning: %s\n", w.c_str());
    if (!ok && record) {
      std::fprintf(stderr, "blverify: --record needs %s\n", manifest.c_str());
      return 2;
    }
  }

  std::vector<const blv::EntryView*> todo;
  for (const auto& e : entries)
    if (selected(e, only)) todo.push_back(&e);
  if (todo.empty()) {
    std::fprintf(stderr, "blverify: no registry entry matches --only\n");
    return 2;
  }
  std::vector<const blv::EntryView*> order = todo;
  std::stable_sort(order.begin(), order.end(),
                   [](const blv::EntryView* a, const blv::EntryView* b) { return cost(*a) > cost(*b); });

  blv::VerifyOptions opt;
  opt.use_mp = !no_mp;
  if (opt.use_mp) blv::mp_warm_up();
  std::vector<blv::EntryResult> results(entries.size());
  std::atomic<std::size_t> next{0};
  std::atomic<int> done{0};
  std::mutex io;
  auto worker = [&] {
    for (;;) {
      std::size_t i = next++;
      if (i >= order.size()) return;
      const blv::EntryView& e = *order[i];
      blv::EntryResult r = blv::verify_entry(e, opt);
      {
        std::lock_guard<std::mutex> lock(io);
        std::fprintf(stderr, "[%3d/%zu] %-40s %-13s %6.2f s\n", ++done, order.size(), e.cpp.c_str(),
                     r.status.c_str(), r.seconds);
      }
      results[e.index] = std::move(r);
    }
  };
  std::vector<std::thread> pool;
  const unsigned n = std::min<unsigned>(threads, static_cast<unsigned>(order.size()));
  for (unsigned k = 0; k < n; ++k) pool.emplace_back(worker);
  for (auto& t : pool) t.join();

  std::vector<blv::EntryResult> out;
  for (const auto* e : todo) out.push_back(results[e->index]);
  blv::print_table(stdout, out, opt, verbose);
  std::fflush(stdout);

  int rc = 0;
  std::string failed;
  for (const auto& r : out)
    if (r.failed()) failed += (failed.empty() ? "" : ", ") + r.name;
  if (!failed.empty()) {
    std::fprintf(stderr, "blverify: FAILED: %s\n", failed.c_str());
    rc = 1;
  }
  if (!report.empty() && !write_file(report, blv::markdown_report(out, opt))) {
    std::fprintf(stderr, "blverify: cannot write %s\n", report.c_str());
    rc = 2;
  }
  if (record) {
    std::vector<std::string> warnings;
    if (!blv::record_manifest(manifest, entries, out, opt, &error, &warnings)) {
      std::fprintf(stderr, "blverify: --record: %s\n", error.c_str());
      rc = 2;
    } else {
      std::fprintf(stderr, "blverify: recorded %zu entries in %s\n", out.size(), manifest.c_str());
    }
  }
  if (only.empty() && blv::rules_compiled_in())
    rc = blv::run_rule_checks(manifest, record, rc);                                 // issue 3 rules
  if (only.empty()) rc = std::max(rc, blv::clamped::run(manifest, record, stdout));  // rules_clamped.hpp
  if (only.empty()) {  // the one-pass stat entries (rulegen/emit_stat_pairs.hpp)
    const std::vector<blv::StatView> stats = blv::load_stats(&error);
    if (!error.empty()) {
      std::fprintf(stderr, "blverify: %s\n", error.c_str());
      rc = std::max(rc, 2);
    }
    rc = std::max(rc, blv::run_stat_checks(entries, stats, opt, stdout));
  }
  std::fprintf(stderr, "blverify: %zu entries in %.1f s (%u threads)\n", out.size(),
               std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), n);
  return rc;
}
