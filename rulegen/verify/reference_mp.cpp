// blverify: 50-digit references (see reference_mp.hpp).
#include "reference_mp.hpp"

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>

#include <cmath>
#include <exception>

#if __has_include(<bandlimit/registry.hpp>)
#include <bandlimit/registry.hpp>
#define BLV_HAVE_REGISTRY 1
#else
#define BLV_HAVE_REGISTRY 0
#endif

#include "quad_core.hpp"

namespace blv {
namespace {

using mp = boost::multiprecision::cpp_bin_float_50;
using GK = boost::math::quadrature::gauss_kronrod<mp, 61>;
constexpr double kWindow = 16;      // exp(-128) ~ 1e-56: below 50 digits
constexpr double kWindowWide = 40;  // unbounded integrands, as in double

mp gk(const std::function<mp(mp)>& f, const mp& a, const mp& b, mp* err, mp* l1) {
  try {
    return GK::integrate(f, a, b, 15, mp(1e-40), err, l1);
  } catch (const std::exception&) {
    *err = std::numeric_limits<mp>::infinity();
    *l1 = *err;
    return std::numeric_limits<mp>::quiet_NaN();
  }
}

}  // namespace

void mp_warm_up() {
  mp e, l;
  gk([](mp t) { return t; }, mp(0), mp(1), &e, &l);
}

#if BLV_HAVE_REGISTRY

bool mp_registry_matches(const std::vector<EntryView>& entries, std::string* error) {
  int n = 0;
  const bl::registry::Entry<mp>* e = bl::registry::entries<mp>(&n);
  if (n != static_cast<int>(entries.size())) {
    *error = "registry: the cpp_bin_float_50 instantiation has " + std::to_string(n) + " entries, double has " +
             std::to_string(entries.size());
    return false;
  }
  for (int i = 0; i < n; ++i)
    if (!e[i].cpp || entries[i].cpp != e[i].cpp) {
      *error = "registry entry " + std::to_string(i) + " (" + entries[i].cpp +
               ") differs between the cpp_bin_float_50 and double instantiations";
      return false;
    }
  return true;
}

MpResult mp_check(int index, const Spec& sp, double xd, double sigmad) {
  MpResult r;
  int n = 0;
  const bl::registry::Entry<mp>* entries = bl::registry::entries<mp>(&n);
  if (index < 0 || index >= n) { r.why = "no such entry"; return r; }
  const bl::registry::Entry<mp>& e = entries[index];
  const int power = sp.power;
  auto g = [&e, power](const mp& s) -> mp {
    mp f = e.plain(s), v = f;
    for (int i = 1; i < power; ++i) v *= f;
    return v;
  };
  const mp x = xd, sigma = sigmad;
  if (!sp.in_domain(xd)) { r.why = "outside the domain"; return r; }
  // Kernel scale in 50 digits (the formula computes sqrt(3) sigma in 50 digits too).
  mp c = sigma;
  if (sp.kernel != Kernel::Gaussian) {
    c = sqrt(mp(sp.kernel == Kernel::Box ? 3 : 6)) * sigma;
    if (sp.compact) {
      mp r_sing = std::numeric_limits<mp>::infinity();
      for (double s : sp.singular) {
        if (sp.period > 0) {
          mp k = floor((x - mp(s)) / mp(sp.period));
          for (int dk = -1; dk <= 2; ++dk) {
            mp d = abs(x - (mp(s) + (k + dk) * mp(sp.period)));
            if (d < r_sing) r_sing = d;
          }
        } else {
          mp d = abs(x - mp(s));
          if (d < r_sing) r_sing = d;
        }
      }
      mp lim = mp(sp.lambda) * r_sing;
      if (lim < c) c = lim;
    }
  }
  mp ref;
  if (!(sigmad > 0) || !(c > 0)) {
    ref = g(x);
  } else {
    std::vector<mp> fixed;
    std::function<mp(mp)> w;
    const mp inv_sqrt_2pi = 1 / sqrt(2 * boost::math::constants::pi<mp>());
    if (sp.kernel == Kernel::Gaussian) {
      fixed = sp.bounded() ? std::vector<mp>{-kWindow, kWindow}
                           : std::vector<mp>{-kWindowWide, -kWindow, kWindow, kWindowWide};
      w = [inv_sqrt_2pi](mp t) { return inv_sqrt_2pi * exp(-t * t / 2); };
    } else if (sp.kernel == Kernel::Box) {
      fixed = {mp(-1), mp(1)};
      w = [](mp) { return mp(0.5); };
    } else {
      fixed = {mp(-1), mp(0), mp(1)};
      w = [](mp t) { return 1 - abs(t); };
    }
    std::vector<Piece<mp>> pieces;
    if (!make_pieces<mp>(sp, x, c, fixed, kMpPieceCap, &pieces)) {
      r.why = "more than " + std::to_string(kMpPieceCap) + " pieces";
      return r;
    }
    QuadSum<mp> q = integrate_pieces<mp>(pieces, x, c, g, w, gk);
    if (!q.finite) { r.why = "integrand not finite"; return r; }
    ref = q.value;
    r.ref_err = static_cast<double>(q.err);
    r.pieces = q.pieces;
  }
  using boost::math::isfinite;
  if (!isfinite(ref)) { r.why = "reference not finite"; return r; }
  r.ok = true;
  r.ref = static_cast<double>(ref);
  mp v = e.smoothed(x, sigma);
  r.formula_finite = isfinite(v);
  if (r.formula_finite) {
    mp den = abs(ref) > 1 ? mp(abs(ref)) : mp(1);
    r.formula_rel = static_cast<double>(mp(abs(v - ref) / den));
  }
  return r;
}

#else

bool mp_registry_matches(const std::vector<EntryView>&, std::string* error) {
  *error = "no registry compiled in";
  return false;
}
MpResult mp_check(int, const Spec&, double, double) {
  MpResult r;
  r.why = "no registry compiled in";
  return r;
}

#endif

}  // namespace blv
