// blverify: the rules beyond convolution that carry their own checks (issue 3, part A): every
// bivariate operator against a seeded Monte Carlo of 10^6 samples per case, and Rule 2 (mode fit)
// against an independent numeric maximisation of the density of Y and that density's value from
// the probability of a small interval. Results go to stdout and, with --record, to the manifest.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

namespace blv {

struct RuleCheck {
  std::string cpp;   // bl::bivariate::mul, bl::rule2::exp
  std::string kind;  // "monte carlo" | "mode reference"
  long cases = 0, skipped = 0;
  double worst_mean = 0;  // bivariate: |mean - MC| / tolerance; rule 2: |mY - ref| / sY_ref
  double worst_var = 0;   // bivariate: |var - MC| / tolerance; rule 2: |sY / sY_ref - 1|
  double bound_mean = 1, bound_var = 1;
  std::string tolerance;   // how the bounds are set
  std::string worst_case;  // inputs of the worst case
  double seconds = 0;
  // Not empty: the tree has no such rule (rulegen emits div and mod only when the catalog derives the
  // table entries they call), so nothing was checked; why, for the report.
  std::string absent;
  bool failed() const { return absent.empty() && (!(worst_mean <= bound_mean) || !(worst_var <= bound_var)); }
};

bool rules_compiled_in();
std::vector<RuleCheck> check_bivariate();  // samples per case: kMcSamples
std::vector<RuleCheck> check_rule2();
constexpr long kMcSamples = 1000000;

void print_rule_checks(std::FILE* out, const std::vector<RuleCheck>& rs);
// Writes each check's "verification" into the manifest entry with the same "cpp".
bool record_rule_checks(const std::string& manifest_path, const std::vector<RuleCheck>& rs,
                        std::string* error);
// Runs both, prints, records (when asked); returns rc, or 1 / 2 on a failed check / record. A check
// the tree lacks (absent) fails when the manifest lists that rule.
int run_rule_checks(const std::string& manifest_path, bool record, int rc);

}  // namespace blv
