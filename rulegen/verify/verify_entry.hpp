// blverify: checks one registry entry over the grid against the references.
#pragma once

#include <limits>
#include <map>
#include <string>
#include <vector>

#include "reference.hpp"
#include "registry_view.hpp"

namespace blv {

struct VerifyOptions {
  double bound_double = 1e-9;  // rel = |value - ref| / max(1, |ref|)
  double bound_float = 2e-5;
  int mp_cap = 160;  // most 50-digit references per entry
  bool use_mp = true;
};

struct Where {
  double x = std::numeric_limits<double>::quiet_NaN();
  double sigma = std::numeric_limits<double>::quiet_NaN();
};

struct EntryResult {
  int index = 0;
  std::string name, atomic, kernel, rule;
  bool bounded = true;           // rule "convolution"/"moment": the error bounds apply
  long points = 0, skipped = 0;  // double comparisons made / skipped
  long float_points = 0, float_skipped = 0;
  long domain_checks = 0;                // NaN checks outside the domain (compact entries)
  long mp_points = 0, mp_declined = 0;   // 50-digit references made / wanted but not possible
  long undecided = 0;                    // double points judged against an undecided double reference
  long over_double = 0, over_float = 0;  // points over the bound
  double worst_d = 0, worst_f = 0;
  Where worst_d_at, worst_f_at;
  double formula50 = std::numeric_limits<double>::quiet_NaN();  // worst 50-digit formula error
  Where formula50_at;
  double ref_crosscheck = 0;  // worst |ref_double - ref_50| / max(1, |ref|) where both exist
  std::map<std::string, long> skip_reasons;
  std::vector<std::string> problems;  // first few invariant violations
  long problem_count = 0;
  std::string period_model;
  std::string notes;   // e.g. a numerically inferred period
  std::string status;  // "pass" | "fail" | "approximation" (rule without a bound)
  double seconds = 0;
  bool failed() const { return status == "fail"; }
};

EntryResult verify_entry(const EntryView& entry, const VerifyOptions& opt);

// Double cannot decide the reference to well within `bound` when the quadrature's own error
// estimate is large (1e-12 for the double bound, as specified), when cancellation makes its rounding
// error large (eps * integral of |integrand|), or when g moves too much under one ulp of its
// argument (next to a pole whose position is not a double).
bool undecided(const Ref& r, double bound);

// "%.1e" rounding used for every reported error (so reruns do not flap).
double round2(double v);
std::string fmt_err(double v);  // "1.2e-16", "0", "-" for NaN
std::string fmt_where(const Where& w);

}  // namespace blv
