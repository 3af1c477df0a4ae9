// See stat_check.hpp.
#include "stat_check.hpp"

#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cmath>

#include "grid.hpp"
#include "reference.hpp"

namespace blv {

int run_stat_checks(const std::vector<EntryView>& entries, const std::vector<StatView>& stats,
                    const VerifyOptions& opt, std::FILE* out) {
  int rc = 0;
  if (!stats.empty())
    std::fprintf(out,
                 "\none-pass stat entries {E f, Var f} against the references of f and f^2 (mean / var)\n");
  for (const StatView& st : stats) {
    const auto t0 = std::chrono::steady_clock::now();
    const EntryView *f = nullptr, *f2 = nullptr;
    for (const EntryView& e : entries) {
      if (e.cpp == st.f_cpp) f = &e;
      if (e.cpp == st.f2_cpp) f2 = &e;
    }
    if (!f || !f2) {
      std::fprintf(out, "%-28s FAIL: the registry has no %s or %s\n", st.cpp.c_str(), st.f_cpp.c_str(),
                   st.f2_cpp.c_str());
      rc = 1;
      continue;
    }
    RefEngine ef(f->spec), ef2(f2->spec);
    long points = 0, skipped = 0;
    double wm_d = 0, wv_d = 0, wm_f = 0, wv_f = 0;
    Where worst;
    // The errors of one evaluation against the references at (x, s); false: reference not decided.
    auto compare = [&](double x, double s, double bound, double m, double v, double* em, double* ev) {
      const Ref r = ef.at(x, s), r2 = ef2.at(x, s);
      if (!r.ok || !r2.ok || undecided(r, bound) || undecided(r2, bound) ||
          !(std::fabs(r2.value) < 0.5 * FLT_MAX))
        return false;
      const double var = r2.value - r.value * r.value;
      *em = std::fabs(m - r.value) / std::max(1.0, std::fabs(r.value));
      *ev = std::fabs(v - var) / std::max(1.0, r2.value);
      if (std::isnan(m) || std::isnan(v)) *em = *ev = HUGE_VAL;
      return true;
    };
    for (const GridPoint& p : grid(ef.effective_spec(), false)) {
      double md, vd, em, ev;
      st.eval_d(p.x, p.sigma, &md, &vd);
      if (!compare(p.x, p.sigma, opt.bound_double, md, vd, &em, &ev)) {
        ++skipped;
        continue;
      }
      ++points;
      if (std::max(em / opt.bound_double, ev / opt.bound_double) >
          std::max(wm_d / opt.bound_double, wv_d / opt.bound_double))
        worst = {p.x, p.sigma};
      wm_d = std::max(wm_d, em), wv_d = std::max(wv_d, ev);
      const float xf = static_cast<float>(p.x), sf = static_cast<float>(p.sigma);
      float mf, vf;
      st.eval_f(xf, sf, &mf, &vf);
      if (compare(xf, sf, opt.bound_float, mf, vf, &em, &ev))
        wm_f = std::max(wm_f, em), wv_f = std::max(wv_f, ev);
    }
    const bool pass = points > 0 && wm_d <= opt.bound_double && wv_d <= opt.bound_double &&
                      wm_f <= opt.bound_float && wv_f <= opt.bound_float;
    std::fprintf(out, "%-28s %4ld points (%ld skipped)  double %s / %s  float %s / %s  %s (%.1f s)\n",
                 st.cpp.c_str(), points, skipped, fmt_err(round2(wm_d)).c_str(),
                 fmt_err(round2(wv_d)).c_str(), fmt_err(round2(wm_f)).c_str(), fmt_err(round2(wv_f)).c_str(),
                 pass ? "pass" : ("FAIL (worst double at " + fmt_where(worst) + ")").c_str(),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    if (!pass) rc = 1;
  }
  return rc;
}

}  // namespace blv
