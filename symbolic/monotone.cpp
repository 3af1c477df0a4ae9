#include "monotone.hpp"

#include <cmath>
#include <sstream>

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
