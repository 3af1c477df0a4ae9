// blverify: printing and manifest records of the rule checks (see rules_check.hpp).
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "rules_check.hpp"

namespace blv {

namespace {
double round2(double v) {
  if (!std::isfinite(v) || v == 0) return v;
  const double e = std::pow(10.0, std::floor(std::log10(std::abs(v))) - 1);
  return std::round(v / e) * e;
}

bool read_manifest(const std::string& path, nlohmann::ordered_json* doc, std::string* error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    *error = "cannot read " + path;
    return false;
  }
  std::stringstream ss;
  ss << in.rdbuf();
  try {
    *doc = nlohmann::ordered_json::parse(ss.str());
  } catch (const std::exception& e) {
    *error = path + ": " + e.what();
    return false;
  }
  return true;
}

// A check the tree lacks fails when the manifest lists the rule: the compiled tree and its manifest
// disagree, and passing would hide an unchecked rule.
void absent_but_listed(const std::string& path, std::vector<RuleCheck>& rs) {
  nlohmann::ordered_json doc;
  std::string error;
  if (!read_manifest(path, &doc, &error)) {
    for (auto& r : rs)
      if (!r.absent.empty()) {
        r.absent.clear();  // cannot tell: fail rather than pass unchecked
        r.worst_case = "absent from the tree, and its manifest is unreadable (" + error + ")";
        r.worst_mean = INFINITY;
      }
    return;
  }
  for (auto& r : rs) {
    if (r.absent.empty()) continue;
    for (const auto& e : doc["entries"])
      if (e.contains("cpp") && e["cpp"] == r.cpp) {
        r.worst_case = "absent from the compiled tree, but " + path + " lists it";
        r.absent.clear();
        r.worst_mean = INFINITY;
        break;
      }
  }
}
}  // namespace

void print_rule_checks(std::FILE* out, const std::vector<RuleCheck>& rs) {
  std::fprintf(out, "\nrules (issue 3): %-26s %-15s %6s %8s %10s %10s  %s\n", "cpp", "check", "cases",
               "skipped", "worst_mean", "worst_var", "status");
  for (const auto& r : rs)
    std::fprintf(out, "                 %-26s %-15s %6ld %8ld %10.2g %10.2g  %s\n", r.cpp.c_str(),
                 r.kind.c_str(), r.cases, r.skipped, round2(r.worst_mean), round2(r.worst_var),
                 !r.absent.empty() ? "absent"
                 : r.failed()      ? "FAIL"
                                   : "pass");
  for (const auto& r : rs)
    if (!r.absent.empty()) std::fprintf(out, "  %s: not checked: %s\n", r.cpp.c_str(), r.absent.c_str());
  for (const auto& r : rs)
    if (r.failed()) std::fprintf(out, "  %s worst case %s\n", r.cpp.c_str(), r.worst_case.c_str());
}

bool record_rule_checks(const std::string& path, const std::vector<RuleCheck>& rs, std::string* error) {
  nlohmann::ordered_json doc;
  if (!read_manifest(path, &doc, error)) return false;
  for (const auto& r : rs) {
    if (!r.absent.empty()) continue;  // not in the tree, so no manifest entry (absent_but_listed)
    bool found = false;
    for (auto& e : doc["entries"]) {
      if (!e.contains("cpp") || e["cpp"] != r.cpp) continue;
      nlohmann::ordered_json v;
      v["check"] = r.kind;
      v["cases"] = r.cases;
      v["skipped"] = r.skipped;
      if (r.kind == "monte carlo") v["samples_per_case"] = kMcSamples;
      v["worst_mean"] = round2(r.worst_mean);
      v["worst_var"] = round2(r.worst_var);
      v["bound_mean"] = r.bound_mean;
      v["bound_var"] = r.bound_var;
      v["tolerance"] = r.tolerance;
      v["status"] = r.failed() ? "fail" : "pass";
      e["verification"] = v;
      found = true;
    }
    if (!found) {
      *error = "no manifest entry for " + r.cpp;
      return false;
    }
  }
  const std::string tmp = path + ".rules.tmp";
  {
    std::ofstream o(tmp, std::ios::binary | std::ios::trunc);
    if (!o || !(o << doc.dump(2) << "\n") || !o.flush()) {
      *error = "cannot write " + tmp;
      return false;
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    *error = "cannot rename " + tmp;
    return false;
  }
  return true;
}

int run_rule_checks(const std::string& manifest, bool record, int rc) {
  std::vector<RuleCheck> rs = check_bivariate();
  for (auto& r : check_rule2()) rs.push_back(r);
  absent_but_listed(manifest, rs);
  print_rule_checks(stdout, rs);
  std::fflush(stdout);
  for (const auto& r : rs)
    if (r.failed()) {
      std::fprintf(stderr, "blverify: FAILED: %s (%s)\n", r.cpp.c_str(), r.worst_case.c_str());
      rc = rc ? rc : 1;
    }
  double secs = 0;
  for (const auto& r : rs) secs += r.seconds;
  int nabsent = 0;
  for (const auto& r : rs) nabsent += !r.absent.empty();
  std::fprintf(stderr,
               "blverify: %zu rule checks (bivariate Monte Carlo, Rule 2 references) in %.1f s, %d rules "
               "absent from this tree (not checked)\n",
               rs.size() - nabsent, secs, nabsent);
  std::string error;
  if (record && !record_rule_checks(manifest, rs, &error)) {
    std::fprintf(stderr, "blverify: --record: %s\n", error.c_str());
    return 2;
  }
  return rc;
}

}  // namespace blv
