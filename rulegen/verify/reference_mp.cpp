// blverify: 50-digit references (see reference_mp.hpp).
#include "reference_mp.hpp"

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>

#include <cmath>
#include <exception>

// BLVERIFY_HAVE_REGISTRY is set by CMakeLists.txt (whether generated/bandlimit/registry.hpp exists).
#ifndef BLVERIFY_HAVE_REGISTRY
#define BLVERIFY_HAVE_REGISTRY __has_include(<bandlimit/registry.hpp>)
#endif
#if BLVERIFY_HAVE_REGISTRY
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

// Adaptive Gauss-Kronrod 61, tolerance 1e-40, depth 12 (shared/TOOLCHAIN.md). Boost's criterion is
// relative to the running estimate, so an integral that is zero up to rounding (trunc(x) = 0 near
// x = 0.25 comes out as 1e-52 noise) would recurse to full depth: a constant C of the integrand's
// size is added twice (and its integral subtracted), which turns the criterion into ~1e-40 * C.
mp gk(const std::function<mp(mp)>& f, const mp& a, const mp& b, mp* err, mp* l1) {
  try {
    mp c = mp(1e-10);
    for (double u : {-0.9, -0.5, -0.1, 0.0, 0.1, 0.5, 0.9}) {
      mp v = abs(f(a + (b - a) * (u + 1) / 2));
      if (v > c) c = v;
    }
    c *= 2;  // f + c stays away from 0 even where f is negative
    mp r = GK::integrate([&](const mp& t) { return f(t) + c; }, a, b, 12, mp(1e-40), err, l1);
    return r - c * (b - a);
  } catch (const std::exception&) {
    *err = std::numeric_limits<mp>::infinity();
    *l1 = *err;
    return std::numeric_limits<mp>::quiet_NaN();
  }
}

// The pole of f nearest to s0 (Newton on 1/f), or s0 when f has no pole within 1e-12 of it.
template <class F>
mp refine_pole(F plain, const mp& s0) {
  using boost::math::isfinite;
  auto h = [&](const mp& t) { return mp(1) / plain(t); };
  mp s = s0, hs = h(s);
  if (!isfinite(hs) || hs == 0) return s0;
  const mp lim = mp(1e-12) * (abs(s0) > 1 ? mp(abs(s0)) : mp(1));
  for (int it = 0; it < 8; ++it) {
    mp d = mp(1e-25) * (abs(s) > 1 ? mp(abs(s)) : mp(1));
    mp dh = (h(s + d) - h(s - d)) / (2 * d);
    if (!isfinite(dh) || dh == 0) return s0;
    mp s1 = s - hs / dh;
    if (!(abs(s1 - s0) <= lim)) return s0;
    s = s1;
    hs = h(s);
    if (!isfinite(hs)) return s0;
    if (abs(hs) < mp(1e-45)) break;
  }
  return abs(hs) < mp(1e-40) ? s : s0;
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
  long evals = 0;  // budget: 50-digit evaluations are slow; give up rather than grind
  struct Budget {};
  auto g = [&e, power, &evals](const mp& s) -> mp {
    if (++evals > 400000) throw Budget{};
    if (power == 0) return mp(1);
    mp f = e.plain(s), v = f;
    for (int i = 1; i < power; ++i) v *= f;
    return v;
  };
  const mp x = xd, sigma = sigmad;
  if (!sp.in_domain(xd)) { r.why = "outside the domain"; return r; }

  // Kernel scale in 50 digits (the formula computes sqrt(3) sigma in 50 digits too). For compact
  // entries two half-widths: from the catalog's singular points (doubles, as the double code sees
  // them; used for the double comparison) and from the true poles of plain<cpp_bin_float_50> near
  // them (used for the 50-digit formula check): pi/2 is not a double.
  mp c_cat = sigma, c_true = sigma;
  if (sp.kernel != Kernel::Gaussian) {
    c_cat = c_true = sqrt(mp(sp.kernel == Kernel::Box ? 3 : 6)) * sigma;
    if (sp.compact) {
      mp r_cat = std::numeric_limits<mp>::infinity(), r_true = r_cat;
      for (double s : sp.singular) {
        std::vector<mp> cand;
        if (sp.period > 0) {
          mp k = floor((x - mp(s)) / mp(sp.period));
          for (int dk = -1; dk <= 2; ++dk) cand.push_back(mp(s) + (k + dk) * mp(sp.period));
        } else {
          cand.push_back(mp(s));
        }
        for (const mp& c : cand) {
          mp d = abs(x - c);
          if (d < r_cat) r_cat = d;
          mp dt = abs(x - refine_pole(e.plain, c));
          if (dt < r_true) r_true = dt;
        }
      }
      if (mp(sp.lambda) * r_cat < c_cat) c_cat = mp(sp.lambda) * r_cat;
      if (mp(sp.lambda) * r_true < c_true) c_true = mp(sp.lambda) * r_true;
    }
  }
  auto reference = [&](const mp& c, mp* out) -> bool {
    if (!(sigmad > 0) || !(c > 0)) {
      *out = g(x);
      return true;
    }
    std::vector<mp> fixed;
    std::function<mp(mp)> w;
    const mp inv_sqrt_2pi = 1 / sqrt(2 * boost::math::constants::pi<mp>());
    if (sp.kernel == Kernel::Gaussian) {
      w = [inv_sqrt_2pi](mp t) { return inv_sqrt_2pi * exp(-t * t / 2); };
      // Unbounded g: integrate 16..40 sigma too unless the integrand is below 1e-60 there (no
      // overflow in 50 digits, so probes every 2 sigma are conclusive for exp-like growth).
      bool tails = false;
      if (!sp.bounded()) {
        mp gx = abs(g(x));
        mp lim = mp(1e-60) * (gx > 1 ? gx : mp(1));
        for (int k = 16; k <= 40 && !tails; k += 2)
          for (int sgn : {1, -1}) {
            mp t = mp(sgn * k), v = abs(w(t) * g(x + c * t));
            if (!(v <= lim)) tails = true;
          }
      }
      fixed = tails ? std::vector<mp>{-kWindowWide, -kWindow, kWindow, kWindowWide} : std::vector<mp>{-kWindow, kWindow};
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
      return false;
    }
    QuadSum<mp> q = integrate_pieces<mp>(pieces, x, c, g, w, gk);
    if (!q.finite) {
      r.why = "integrand not finite";
      return false;
    }
    // Enough for judging double (1e-9) by a wide margin; the 50-digit formula error it yields
    // is then limited to this level (odd moments with sigma >> |x| cancel 25 digits).
    if (!(q.err <= mp(1e-15) * (abs(q.value) > 1 ? mp(abs(q.value)) : mp(1)))) {
      r.why = "50-digit quadrature did not converge";
      return false;
    }
    *out = q.value;
    r.ref_err = std::fmax(r.ref_err, static_cast<double>(q.err));
    r.pieces += q.pieces;
    return true;
  };
  mp ref, ref_true;
  try {
    if (!reference(c_cat, &ref)) return r;
    if (c_true == c_cat) {
      ref_true = ref;
    } else if (!reference(c_true, &ref_true)) {
      return r;
    }
  } catch (const Budget&) {
    r.why = "50-digit quadrature over its evaluation budget";
    return r;
  }
  using boost::math::isfinite;
  if (!isfinite(ref)) { r.why = "reference not finite"; return r; }
  r.ref = static_cast<double>(ref);
  if (!std::isfinite(r.ref)) {
    r.why = "reference overflows double";
    return r;
  }
  r.ok = true;
  mp v = e.smoothed(x, sigma);
  r.formula_finite = isfinite(v);
  if (r.formula_finite) {
    mp den = abs(ref_true) > 1 ? mp(abs(ref_true)) : mp(1);
    r.formula_rel = static_cast<double>(mp(abs(v - ref_true) / den));
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
