#include "exp_poly.hpp"

#include <functional>
#include <sstream>
#include <stdexcept>

#include "catalog.hpp"
#include "functions.hpp"

namespace bl::sym {
using namespace GiNaC;

bool ExpPolyKey::operator<(const ExpPolyKey& o) const {
  if (n != o.n) return n < o.n;
  if (a.real() != o.a.real()) return a.real() < o.a.real();
  return a.imag() < o.a.imag();
}

void ExpPoly::add(const ExpPolyKey& k, const numeric& c) {
  if (c.is_zero()) return;
  auto it = terms_.find(k);
  if (it == terms_.end()) {
    terms_.emplace(k, c);
  } else {
    it->second += c;
    if (it->second.is_zero()) terms_.erase(it);
  }
}

ExpPoly ExpPoly::operator+(const ExpPoly& o) const {
  ExpPoly r = *this;
  for (auto& [k, c] : o.terms_) r.add(k, c);
  return r;
}

ExpPoly ExpPoly::operator*(const ExpPoly& o) const {
  ExpPoly r;
  for (auto& [k1, c1] : terms_)
    for (auto& [k2, c2] : o.terms_) r.add({k1.n + k2.n, k1.a + k2.a}, c1 * c2);
  return r;
}

namespace {
[[noreturn]] void outside(const ex& e, const std::string& why) {
  std::ostringstream s;
  s << e << ": " << why;
  throw std::invalid_argument("not in the exp-polynomial class: " + s.str());
}

}  // namespace

ExpPoly ExpPoly::from(const ex& e) {
  const symbol& x = var_x();
  ExpPoly r;
  if (is_a<numeric>(e)) {
    r.add({0, 0}, ex_to<numeric>(e));
    return r;
  }
  if (is_a<symbol>(e)) {
    if (!e.is_equal(x)) outside(e, "unknown variable");
    r.add({1, 0}, 1);
    return r;
  }
  if (is_a<GiNaC::add>(e)) {
    for (size_t i = 0; i < e.nops(); ++i) r = r + from(e.op(i));
    return r;
  }
  if (is_a<GiNaC::mul>(e)) {
    r.add({0, 0}, 1);
    for (size_t i = 0; i < e.nops(); ++i) r = r * from(e.op(i));
    return r;
  }
  if (is_a<power>(e)) {
    const ex n = e.op(1);
    if (!is_a<numeric>(n) || !ex_to<numeric>(n).is_nonneg_integer()) outside(e, "only non-negative integer powers");
    const ExpPoly base = from(e.op(0));
    r.add({0, 0}, 1);
    for (long i = 0; i < ex_to<numeric>(n).to_long(); ++i) r = r * base;
    return r;
  }
  if (is_a<function>(e)) {
    const std::string name = ex_to<function>(e).get_name();
    const ex arg = e.op(0).expand();
    if (!arg.is_polynomial(x) || arg.degree(x) != 1 || !arg.coeff(x, 0).is_zero() ||
        !is_a<numeric>(arg.coeff(x, 1)))
      outside(e, "the argument must be a rational multiple of x");
    const numeric a = ex_to<numeric>(arg.coeff(x, 1));
    const numeric i = I;
    if (name == "exp") {
      r.add({0, a}, 1);
    } else if (name == "sinh") {
      r.add({0, a}, numeric(1, 2));
      r.add({0, -a}, numeric(-1, 2));
    } else if (name == "cosh") {
      r.add({0, a}, numeric(1, 2));
      r.add({0, -a}, numeric(1, 2));
    } else if (name == "sin") {
      r.add({0, i * a}, 1 / (2 * i));
      r.add({0, -i * a}, -1 / (2 * i));
    } else if (name == "cos") {
      r.add({0, i * a}, numeric(1, 2));
      r.add({0, -i * a}, numeric(1, 2));
    } else {
      outside(e, "function " + name + " has no exp-polynomial form");
    }
    return r;
  }
  outside(e, "unsupported expression");
}

ex ExpPoly::to_ex() const {
  ex r = 0;
  for (auto& [k, c] : terms_) r += c * pow(var_x(), k.n) * exp(k.a * var_x());
  return r;
}

ex ExpPoly::convolve(Kernel kern) const {
  const symbol& x = var_x();
  ex real_part_sum = 0;
  std::map<numeric, std::pair<numeric, numeric>, std::function<bool(const numeric&, const numeric&)>>
      trig([](const numeric& p, const numeric& q) { return p < q; });
  numeric imag_check = 0;
  for (auto& [k, c] : terms_) {
    if (k.a.is_zero()) {
      // E[(x+U)^n] = sum_j C(n,j) x^{n-j} E[U^j]
      if (!c.is_real()) imag_check += abs(c);
      for (int j = 0; j <= k.n; ++j)
        real_part_sum += c.real() * binomial(k.n, j) * pow(x, k.n - j) * raw_moment(kern, j);
      continue;
    }
    if (k.n != 0) {
      std::ostringstream s;
      s << "x^" << k.n << " e^(" << k.a << " x)";
      throw std::invalid_argument("exp-polynomial term " + s.str() +
                                  " (a power times an exponential) is not supported by the emitter yet");
    }
    if (k.a.is_real()) {
      if (!c.is_real()) imag_check += abs(c);
      // e^{ax} and e^{-ax} together become cosh/sinh (sinh(x) near 0 would cancel otherwise).
      auto partner = terms_.find({0, -k.a});
      if (partner != terms_.end()) {
        if (k.a < 0) continue;  // handled with its positive partner
        const numeric cp = c.real(), cm = partner->second.real();
        const ex m = kernel_mgf(kern, k.a);
        if (!(cp + cm).is_zero()) real_part_sum += (cp + cm) * cosh(k.a * x) * m;
        if (!(cp - cm).is_zero()) real_part_sum += (cp - cm) * prod0(sinh(k.a * x), m);
        continue;
      }
      real_part_sum += c.real() * exp_times_mgf(kern, k.a, x);
    } else if (k.a.real().is_zero()) {
      // c e^{i w x} -> Re: cr cos(w x) - ci sin(w x); with w < 0 the sine flips sign.
      const numeric w = k.a.imag();
      auto& cs = trig[abs(w)];
      cs.first += c.real();
      cs.second += (w > 0 ? -1 : 1) * c.imag();
    } else {
      throw std::invalid_argument("exp-polynomial term with complex rate: not supported");
    }
  }
  if (!imag_check.is_zero()) throw std::invalid_argument("complex coefficient in a real function");
  ex r = real_part_sum;
  for (auto& [w, cs] : trig)
    r += (cs.first * cos(w * x) + cs.second * sin(w * x)) * characteristic(kern, w);
  return r.expand();
}

}  // namespace bl::sym
