#include "gauss_expect.hpp"

#include <stdexcept>

#include "functions.hpp"

namespace bl::sym {
using namespace GiNaC;

namespace {

// E[Z^k] = (k-1)!! for even k, 0 for odd k.
ex normal_moment(int k) {
  if (k % 2) return 0;
  numeric r = 1;
  for (int j = k - 1; j > 1; j -= 2) r *= j;
  return r;
}

// Replaces every power z^k of one standard normal by its moment (p expanded, polynomial in z).
ex integrate_out(const ex& p, const symbol& z) {
  if (!p.is_polynomial(z)) throw std::runtime_error("gauss_expect: not a polynomial in " + z.get_name());
  ex r = 0;
  for (int k = p.ldegree(z); k <= p.degree(z); ++k) r += p.coeff(z, k) * normal_moment(k);
  return r;
}

}  // namespace

ex normal_expect(const ex& p, const std::vector<symbol>& zs) {
  ex r = p.expand();
  for (const symbol& z : zs) r = integrate_out(r, z).expand();
  return r;
}

ex gauss_expect(const ex& p, const symbol& w, const std::vector<symbol>& others, const symbol& q,
                const ex& t) {
  ex e = normal_expect(p, others);
  if (!e.is_polynomial(q)) throw std::runtime_error("gauss_expect: not a polynomial in the indicator");
  // q^k = q for k >= 1: split into the part without q and the coefficient of the indicator.
  ex plain = e.coeff(q, 0), with_q = 0;
  for (int k = 1; k <= e.degree(q); ++k) with_q += e.coeff(q, k);
  with_q = with_q.expand();
  ex r = integrate_out(plain.expand(), w);
  const int deg = with_q.degree(w);
  std::vector<ex> J(deg + 1);
  for (int k = 0; k <= deg; ++k)
    J[k] = k == 0 ? ex(Phi(t)) : k == 1 ? ex(phi(t)) : pow(-t, k - 1) * phi(t) + (k - 1) * J[k - 2];
  for (int k = 0; k <= deg; ++k) r += with_q.coeff(w, k) * J[k];
  return r.expand();
}

}  // namespace bl::sym
