// blverify: per-entry verification (see verify_entry.hpp).
#include "verify_entry.hpp"

#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>
#include <utility>

#include "grid.hpp"
#include "reference.hpp"
#include "reference_mp.hpp"

namespace blv {

double round2(double v) {
  if (!std::isfinite(v)) return v;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1e", v);
  return std::strtod(buf, nullptr);
}

std::string fmt_err(double v) {
  if (std::isnan(v)) return "-";
  if (v == 0) return "0";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1e", v);
  return buf;
}

std::string fmt_where(const Where& w) {
  if (std::isnan(w.x)) return "";
  char buf[64];
  std::snprintf(buf, sizeof buf, "x=%.10g s=%.3g", w.x, w.sigma);
  return buf;
}

namespace {

std::string at(double x, double s) {
  char buf[80];
  std::snprintf(buf, sizeof buf, " at x=%.17g sigma=%.17g", x, s);
  return buf;
}

}  // namespace

bool undecided(const Ref& r, double bound) {
  const double m = std::fmax(1.0, std::fabs(r.value));
  const double est = bound <= 1e-9 ? 1e-12 : bound * 1e-2;
  const double tol = bound * 1e-2;
  return !(r.err <= est * m) || !(4 * DBL_EPSILON * r.l1 <= tol * m) || !(r.sens <= tol * m);
}

namespace {

struct Checker {
  const EntryView& e;
  const VerifyOptions& opt;
  EntryResult& res;

  void problem(const std::string& msg) {
    ++res.problem_count;
    if (res.problems.size() < 8) res.problems.push_back(msg);
  }
  void skip(const std::string& why) {
    ++res.skipped;
    ++res.skip_reasons[why];
  }
  // Range invariant for a value computed in double or float.
  void check_range(double v, double tol, const char* prec, double x, double s) {
    if (e.rule == "moment") return;
    double lo = e.spec.range_lo, hi = e.spec.range_hi;
    if (e.squared) {
      hi = std::fmax(lo * lo, hi * hi);
      lo = 0;
    }
    if (v < lo - tol * std::fmax(1.0, std::fabs(lo)) || v > hi + tol * std::fmax(1.0, std::fabs(hi))) {
      char buf[200];
      std::snprintf(buf, sizeof buf, "%s value %.17g outside the range [%g, %g]", prec, v, lo, hi);
      problem(buf + at(x, s));
    }
  }
};

// Points that get a 50-digit reference whatever double says: next to each break, and two ordinary
// points for the formula check.
std::set<std::pair<double, double>> mp_selection(const Spec& sp, bool moment) {
  std::set<std::pair<double, double>> sel;
  int nb = 0;
  for (double b : sp.breaks) {
    if (nb++ >= 8) break;
    for (auto p : {std::pair<double, double>{b + 1e-9, 1e-8}, {b - 1e-4, 1e-4}, {b, 0.01}})
      if (sp.in_domain(p.first) && sp.singular_distance(p.first) > 0) sel.insert(p);
  }
  const std::pair<double, double> ordinary[] = {{0.25, 0.3}, {-1.5, 1}, {3.7, 0.1},
                                                {1.5, 0.01}, {0.5, 3},  {10, 1}};
  int n = 0;
  for (auto p : ordinary) {
    if (n >= 2) break;
    if (moment && p.first == 0.25) p.first = 0.5;
    if (!sp.in_domain(p.first) || !(sp.singular_distance(p.first) > 0)) continue;
    sel.insert(p);
    ++n;
  }
  return sel;
}

}  // namespace

EntryResult verify_entry(const EntryView& e, const VerifyOptions& opt) {
  auto t0 = std::chrono::steady_clock::now();
  EntryResult res;
  res.index = e.index;
  res.name = e.cpp;
  if (e.rule == "moment" && e.cpp.find(std::to_string(e.order)) == std::string::npos)
    res.name += " [n=" + std::to_string(e.order) + "]";  // one C++ name for all orders
  res.atomic = e.atomic;
  res.kernel = e.kernel;
  res.rule = e.rule;
  res.bounded = e.exact_rule;
  Checker ck{e, opt, res};
  const bool moment = e.rule == "moment";

  if (!e.kernel_known) ck.problem("unknown kernel '" + e.kernel + "'");
  if (e.compact && e.spec.kernel == Kernel::Gaussian)
    ck.problem("compact flag on a Gaussian entry: not defined");
  if (!e.smoothed_d || !e.smoothed_f || !e.spec.plain) ck.problem("missing function pointer");
  if (res.problem_count) {
    res.status = "fail";
    return res;
  }

  RefEngine eng(e.spec);
  const Spec& sp = eng.effective_spec();  // with a numerically inferred period, if any
  res.notes = eng.inferred_period_note();
  const auto sel = mp_selection(sp, moment);
  for (const GridPoint& p : grid(sp, moment)) {
    const double x = p.x, s = p.sigma;
    const float xf = static_cast<float>(x), sf = static_cast<float>(s);
    if (!sp.in_domain(x)) {
      // The grid is limited to the domain; compact entries must return NaN outside it (at an end
      // of the domain itself f's own value is accepted too: log(0) = -inf, sqrt(0)^2 = 0).
      if (!e.compact) continue;
      ++res.domain_checks;
      auto bad = [&sp](double xx, double v) {  // at an end of the domain: NaN or f's own value there
        bool edge = xx == sp.domain_lo || xx == sp.domain_hi;
        return edge ? !(std::isnan(v) || v == sp.g(xx)) : !std::isnan(v);
      };
      double v = e.smoothed_d(x, s);
      if (bad(x, v))
        ck.problem("returns " + std::to_string(v) + " outside the domain (expected NaN)" + at(x, s));
      if (!sp.in_domain(xf)) {
        float vf = e.smoothed_f(xf, sf);
        if (bad(xf, vf))
          ck.problem("float returns " + std::to_string(vf) + " outside the domain (expected NaN)" +
                     at(xf, sf));
      }
      continue;
    }

    Ref r = eng.at(x, s);
    if (!r.ok) {
      ck.skip(r.why);
      continue;
    }
    if (!std::isfinite(r.value) || std::fabs(r.value) > DBL_MAX) {
      ck.skip("reference overflows double");
      continue;
    }
    double ref = r.value;
    const bool selected = sel.count({x, s}) > 0;
    const bool undec = undecided(r, opt.bound_double);
    // 50 digits help with precision, not with resolution: when double quadrature did not even
    // converge to 1e-8 of its own scale (an oscillation it cannot resolve), Gauss-Kronrod would
    // grind to its depth.
    const bool converged =
        r.err <= 1e-8 * std::fmax(r.l1, std::fmax(1.0, std::fabs(r.value)));  // vs its own scale
    bool have_mp = false;
    if (opt.use_mp && (selected || undec) && converged) {
      if (res.mp_points >= opt.mp_cap) {
        ++res.mp_declined;
      } else {
        MpResult m = mp_check(e.index, sp, x, s);
        if (m.ok) {
          ++res.mp_points;
          have_mp = true;
          double d = std::fabs(m.ref - r.value) / std::fmax(1.0, std::fabs(m.ref));
          if (!undec && d > res.ref_crosscheck) res.ref_crosscheck = d;
          ref = m.ref;
          if (!m.formula_finite) {
            ck.problem("smoothed<cpp_bin_float_50> not finite" + at(x, s));
          } else if (std::isnan(res.formula50) || m.formula_rel > res.formula50) {
            res.formula50 = m.formula_rel;
            res.formula50_at = {x, s};
          }
        } else {
          ++res.mp_declined;
        }
      }
    }

    // double
    double v = e.smoothed_d(x, s);
    if (!std::isfinite(v)) {
      ++res.points;
      ck.problem("double result " + std::to_string(v) + " where the reference is " + std::to_string(ref) +
                 at(x, s));
    } else {
      double rel = std::fabs(v - ref) / std::fmax(1.0, std::fabs(ref));
      if (undec && !have_mp && rel > opt.bound_double) {
        // Neither the value nor double quadrature can be trusted here, and 50 digits were not possible.
        ++res.undecided;
        ck.skip(converged ? "reference undecided in double, no 50-digit reference possible"
                          : "double quadrature did not converge (unresolved oscillation?)");
        continue;
      }
      ++res.points;
      if (rel > opt.bound_double) ++res.over_double;
      if (std::isnan(res.worst_d_at.x) || rel > res.worst_d) {
        res.worst_d = std::fmax(res.worst_d, rel);
        res.worst_d_at = {x, s};
      }
      ck.check_range(v, opt.bound_double, "double", x, s);
    }

    // float, at the float-rounded inputs
    double rf = ref;
    if (static_cast<double>(xf) != x || static_cast<double>(sf) != s) {
      if (!sp.in_domain(xf)) {
        ++res.float_skipped;
        continue;
      }
      Ref rr = eng.at(xf, sf);
      if (!rr.ok || !std::isfinite(rr.value)) {
        ++res.float_skipped;
        continue;
      }
      rf = rr.value;
      if (undecided(rr, opt.bound_float)) {
        MpResult m;
        const bool conv = rr.err <= 1e-8 * std::fmax(rr.l1, std::fmax(1.0, std::fabs(rr.value)));
        if (opt.use_mp && conv && res.mp_points < opt.mp_cap) m = mp_check(e.index, sp, xf, sf);
        if (!m.ok) {
          ++res.float_skipped;
          ++res.mp_declined;
          continue;
        }
        ++res.mp_points;
        rf = m.ref;
      }
    }
    if (std::fabs(rf) > 0.5 * FLT_MAX) {
      ++res.float_skipped;
      continue;
    }
    ++res.float_points;
    float vf = e.smoothed_f(xf, sf);
    if (!std::isfinite(vf)) {
      ck.problem("float result " + std::to_string(vf) + " where the reference is " + std::to_string(rf) +
                 at(xf, sf));
    } else {
      double rel = std::fabs(static_cast<double>(vf) - rf) / std::fmax(1.0, std::fabs(rf));
      if (rel > opt.bound_float) ++res.over_float;
      if (std::isnan(res.worst_f_at.x) || rel > res.worst_f) {
        res.worst_f = std::fmax(res.worst_f, rel);
        res.worst_f_at = {static_cast<double>(xf), static_cast<double>(sf)};
      }
      ck.check_range(vf, opt.bound_float, "float", xf, sf);
    }
  }
  res.period_model = eng.period_model_summary();

  if (res.points == 0) ck.problem("no point could be verified");
  if (res.problem_count) {
    res.status = "fail";
  } else if (!e.exact_rule) {
    res.status = "approximation";
  } else {
    res.status = (res.worst_d <= opt.bound_double && res.worst_f <= opt.bound_float) ? "pass" : "fail";
  }
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

}  // namespace blv
