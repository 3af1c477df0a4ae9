#include "monotone.hpp"

#include <cmath>
#include <optional>
#include <sstream>

#include "catalog_checks.hpp"
#include "exp_poly.hpp"

namespace bl::sym {
using namespace GiNaC;

namespace {

[[noreturn]] void fail(const Atomic& a, const std::string& msg) {
  throw CatalogError("catalog entry '" + a.name + "', field 'monotone': " + msg);
}

bool contains(const Bound& lo, const Bound& hi, const Bound& plo, const Bound& phi_) {
  const double a = lo.to_double(), b = hi.to_double(), pa = plo.to_double(), pb = phi_.to_double();
  return pa <= a + 1e-12 && b <= pb + 1e-12;
}

// Evaluates e (in x, y) at 30 digits; NaN when it is not a real number there.
double eval30(const ex& e, const symbol& v, double at) {
  const int saved = Digits;
  Digits = 30;
  double r = std::nan("");
  try {
    const ex val = e.subs(v == numeric(at)).evalf();
    if (is_a<numeric>(val) && ex_to<numeric>(val).is_real()) r = ex_to<numeric>(val).to_double();
  } catch (const std::exception&) {
  }
  Digits = saved;
  return r;
}

// f' = q(x) e^{a x} with q a rational polynomial and one real rate a (polynomials: a = 0; the
// exp-polynomial pieces x^n e^{ax}): q, else nothing (then only the samples below check).
std::optional<ex> single_rate_factor(const ex& fp) {
  try {
    const ExpPoly e = ExpPoly::from(fp.expand());
    std::optional<numeric> rate;
    ex q = 0;
    for (const auto& [k, c] : e.terms()) {
      if (!k.a.is_real() || !c.is_rational() || (rate && *rate != k.a)) return std::nullopt;
      rate = k.a;
      q += c * pow(var_x(), k.n);
    }
    return q;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

}  // namespace

std::vector<double> interior_points(const Bound& lo, const Bound& hi, int n) {
  std::vector<double> xs;
  const double a = lo.to_double(), b = hi.to_double();
  for (int k = 1; k <= n; ++k) {
    const double u = static_cast<double>(k) / (n + 1);
    if (lo.finite() && hi.finite())
      xs.push_back(a + (b - a) * u);
    else if (lo.finite())
      xs.push_back(a + 8 * u * u);
    else if (hi.finite())
      xs.push_back(b - 8 * u * u);
    else
      xs.push_back(6 * (u - 0.5) + 0.1);
  }
  return xs;
}

ex monotone_f(const Atomic& a, const Monotone& m) {
  if (a.cls == AtomicClass::Entire || a.cls == AtomicClass::Antiderivative) return a.f;
  if (a.cls == AtomicClass::Piecewise || a.cls == AtomicClass::Periodic)
    for (const Piece& p : a.pieces)
      if (contains(m.lo, m.hi, p.lo, p.hi)) return p.f;
  fail(a, "a monotone piece must lie inside one piece of the definition");
}

void check_monotone(const Atomic& a) {
  if (a.monotone.empty()) return;
  if (a.cls == AtomicClass::Combination) fail(a, "not supported for class 'combination'");
  const symbol& x = var_x();
  for (size_t i = 0; i < a.monotone.size(); ++i) {
    const Monotone& m = a.monotone[i];
    const ex f = monotone_f(a, m);
    const ex fp = f.diff(x);
    // Proof where f' = q e^{ax}: q has no real root strictly inside the piece (e^{ax} > 0).
    if (const auto q = single_rate_factor(fp)) {
      // (a root within 1e-30 of an end is that end: roots are isolated to ~1e-40)
      auto end = [](const Bound& b) {
        if (is_a<numeric>(b.value)) return ex_to<numeric>(b.value);
        const int saved = Digits;
        Digits = 50;
        const numeric v = ex_to<numeric>(b.value.evalf());
        Digits = saved;
        return v;
      };
      const numeric tol("1e-30");
      for (const numeric& r : real_roots(*q)) {
        const bool above = !m.lo.finite() || r > end(m.lo) + tol * (1 + abs(end(m.lo)));
        const bool below = !m.hi.finite() || r < end(m.hi) - tol * (1 + abs(end(m.hi)));
        if (above && below) {
          std::ostringstream o;
          o << "piece " << i << ": f is not strictly monotone inside it (f' = 0 at x = " << r.to_double() << ")";
          fail(a, o.str());
        }
      }
    }
    int sign = 0;
    for (double xv : interior_points(m.lo, m.hi, 7)) {
      const double d = eval30(fp, x, xv);
      const int s = d > 0 ? 1 : (d < 0 ? -1 : 0);
      if (s == 0 || (sign != 0 && s != sign)) {
        std::ostringstream o;
        o << "piece " << i << ": f is not strictly monotone inside it (f'(" << xv << ") = " << d << ")";
        fail(a, o.str());
      }
      sign = s;
      const double y = eval30(f, x, xv);
      const double back = eval30(m.inverse, var_y(), y);
      if (!(std::abs(back - xv) <= 1e-12 * std::max(1.0, std::abs(xv)))) {
        std::ostringstream o;
        o << "piece " << i << ": the inverse does not invert f: g(f(" << xv << ")) = " << back;
        fail(a, o.str());
      }
    }
  }
}

}  // namespace bl::sym
