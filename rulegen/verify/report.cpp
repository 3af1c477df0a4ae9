// blverify: table and Markdown report (see report.hpp). Deterministic: no timings, registry order.
#include "report.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "grid.hpp"

namespace blv {
namespace {

std::string err_at(double e, const Where& w) {
  std::string s = fmt_err(e);
  if (!std::isnan(w.x) && e > 0) s += " (" + fmt_where(w) + ")";
  return s;
}

std::string status_word(const EntryResult& r) {
  if (r.status == "pass") return "PASS";
  if (r.status == "fail") return "FAIL";
  return "APPROX";
}

struct Totals {
  long pass = 0, fail = 0, approx = 0, points = 0, skipped = 0, fpoints = 0, mp = 0, mp_declined = 0;
  double xcheck = 0;
};
Totals totals(const std::vector<EntryResult>& rs) {
  Totals t;
  for (const auto& r : rs) {
    (r.status == "pass" ? t.pass : r.status == "fail" ? t.fail : t.approx)++;
    t.points += r.points;
    t.skipped += r.skipped;
    t.fpoints += r.float_points;
    t.mp += r.mp_points;
    t.mp_declined += r.mp_declined;
    t.xcheck = std::max(t.xcheck, r.ref_crosscheck);
  }
  return t;
}

std::vector<std::string> reasons(const EntryResult& r, const VerifyOptions& opt) {
  std::vector<std::string> out;
  if (r.bounded && r.worst_d > opt.bound_double)
    out.push_back(std::to_string(r.over_double) + " double point(s) over " + fmt_err(opt.bound_double) + ", worst " +
                  err_at(r.worst_d, r.worst_d_at));
  if (r.bounded && r.worst_f > opt.bound_float)
    out.push_back(std::to_string(r.over_float) + " float point(s) over " + fmt_err(opt.bound_float) + ", worst " +
                  err_at(r.worst_f, r.worst_f_at));
  for (const auto& p : r.problems) out.push_back(p);
  if (r.problem_count > static_cast<long>(r.problems.size()))
    out.push_back("... " + std::to_string(r.problem_count - r.problems.size()) + " more invariant violation(s)");
  return out;
}

}  // namespace

void print_table(std::FILE* out, const std::vector<EntryResult>& results, const VerifyOptions& opt, bool verbose) {
  std::size_t w = 5;
  for (const auto& r : results) w = std::max(w, r.name.size());
  std::fprintf(out, "%-*s %7s %7s  %-36s %-36s %9s  %s\n", int(w), "entry", "points", "skipped",
               "worst double error (where)", "worst float error (where)", "50-digit", "status");
  for (const auto& r : results) {
    std::fprintf(out, "%-*s %7ld %7ld  %-36s %-36s %9s  %s\n", int(w), r.name.c_str(), r.points, r.skipped,
                 err_at(r.worst_d, r.worst_d_at).c_str(), err_at(r.worst_f, r.worst_f_at).c_str(),
                 fmt_err(r.formula50).c_str(), status_word(r).c_str());
  }
  Totals t = totals(results);
  std::fprintf(out,
               "\n%zu entries: %ld pass, %ld fail, %ld approximation (no bound). %ld double and %ld float points, %ld "
               "skipped; %ld 50-digit references (%ld wanted but not possible); double vs 50-digit reference: worst "
               "%s. Bounds: double %s, float %s.\n",
               results.size(), t.pass, t.fail, t.approx, t.points, t.fpoints, t.skipped, t.mp, t.mp_declined,
               fmt_err(t.xcheck).c_str(), fmt_err(opt.bound_double).c_str(), fmt_err(opt.bound_float).c_str());
  for (const auto& r : results) {
    auto rs = reasons(r, opt);
    bool show = r.status != "pass" || verbose;
    if (!show) continue;
    if (!rs.empty() || verbose) std::fprintf(out, "\n%s %s:\n", status_word(r).c_str(), r.name.c_str());
    for (const auto& s : rs) std::fprintf(out, "  %s\n", s.c_str());
    if (verbose) {
      for (const auto& kv : r.skip_reasons) std::fprintf(out, "  skipped %ld: %s\n", kv.second, kv.first.c_str());
      if (r.float_skipped) std::fprintf(out, "  float skipped %ld\n", r.float_skipped);
      if (r.domain_checks) std::fprintf(out, "  NaN checks outside the domain: %ld\n", r.domain_checks);
      if (!r.period_model.empty()) std::fprintf(out, "  period model: %s\n", r.period_model.c_str());
      if (!r.notes.empty()) std::fprintf(out, "  note: %s\n", r.notes.c_str());
      std::fprintf(out, "  50-digit references: %ld (declined %ld); 50-digit formula error %s %s\n", r.mp_points,
                   r.mp_declined, fmt_err(r.formula50).c_str(), fmt_where(r.formula50_at).c_str());
    }
  }
}

std::string markdown_report(const std::vector<EntryResult>& results, const VerifyOptions& opt) {
  std::ostringstream o;
  Totals t = totals(results);
  o << "# blverify: verification of the generated table\n\n";
  o << "Reference: Boost.Math quadrature of E[g(x+U)] split at every break (see rulegen/verify/reference.hpp), "
       "50-digit Gauss-Kronrod where double cannot decide. Error: |value - ref| / max(1, |ref|); bounds: double "
    << fmt_err(opt.bound_double) << ", float " << fmt_err(opt.bound_float)
    << " (float: the float instantiation at the float-rounded inputs).\n\n";
  o << "Grid: " << grid_description() << "\n\n";
  o << results.size() << " entries: " << t.pass << " pass, " << t.fail << " fail, " << t.approx
    << " approximation (no bound); " << t.points << " double and " << t.fpoints << " float points, " << t.skipped
    << " skipped; " << t.mp << " 50-digit references; double vs 50-digit reference worst " << fmt_err(t.xcheck)
    << ".\n\n";
  o << "| entry | points | skipped | worst double (x, sigma) | worst float (x, sigma) | formula error (50 digits) | "
       "status |\n|---|---:|---:|---|---|---:|---|\n";
  for (const auto& r : results)
    o << "| `" << r.name << "` | " << r.points << " | " << r.skipped << " | " << err_at(r.worst_d, r.worst_d_at)
      << " | " << err_at(r.worst_f, r.worst_f_at) << " | " << fmt_err(r.formula50) << " | " << status_word(r)
      << " |\n";
  bool any = false;
  for (const auto& r : results) {
    auto rs = reasons(r, opt);
    std::map<std::string, long> sk = r.skip_reasons;
    if (rs.empty() && sk.empty() && r.notes.empty()) continue;
    if (!any) o << "\n## Details\n";
    any = true;
    o << "\n### `" << r.name << "` (" << status_word(r) << ")\n\n";
    for (const auto& s : rs) o << "- " << s << "\n";
    for (const auto& kv : sk) o << "- skipped " << kv.second << ": " << kv.first << "\n";
    if (!r.notes.empty()) o << "- note: " << r.notes << "\n";
  }
  return o.str();
}

}  // namespace blv
