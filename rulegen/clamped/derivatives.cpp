#include "derivatives.hpp"

#include <sstream>
#include <stdexcept>

#include "printer.hpp"

namespace bl::rulegen::clamped {
using namespace GiNaC;

std::string Derivative::impl() const {
  return "deriv_" + atomic->name + "_d" + std::to_string(order);
}
std::string Derivative::cpp() const {
  return "bl::deriv::" + atomic->name + "_d" + std::to_string(order);
}
std::string Derivative::glsl() const {
  return "bl_deriv_" + atomic->name + "_d" + std::to_string(order);
}

namespace {

std::vector<sym::PolyPiece> diff_pieces(std::vector<sym::PolyPiece> ps, int order) {
  for (int o = 0; o < order; ++o)
    for (auto& p : ps) {
      std::vector<numeric> d;
      for (size_t k = 1; k < p.c.size(); ++k) d.push_back(p.c[k] * numeric(static_cast<long>(k)));
      if (d.empty()) d.push_back(0);
      p.c = d;
    }
  return ps;
}

std::string pieces_text(const std::vector<sym::PolyPiece>& ps) {
  const symbol& x = sym::var_x();
  std::string s;
  for (const auto& p : ps) {
    ex poly = 0;
    for (size_t k = 0; k < p.c.size(); ++k) poly += p.c[k] * pow(x, static_cast<int>(k));
    auto b = [](const sym::Bound& v) {
      return v.inf ? std::string(v.inf < 0 ? "-inf" : "inf") : sym::print(v.value, sym::Lang::Text);
    };
    s += (s.empty() ? "" : "; ") + sym::print(poly, sym::Lang::Text) + " on [" + b(p.lo) + ", " + b(p.hi) +
         ")";
  }
  return s;
}

}  // namespace

std::vector<Derivative> derive_derivatives(const sym::Catalog& cat, const std::vector<sym::Derived>& ds) {
  const symbol& x = sym::var_x();
  std::vector<Derivative> out;
  for (const auto& a : cat.atomics)
    for (int order = 1; order <= 2; ++order) {
      Derivative d;
      d.atomic = &a;
      d.order = order;
      switch (a.cls) {
        case sym::AtomicClass::Entire:
        case sym::AtomicClass::Antiderivative:
          d.kind = Derivative::Kind::Closed;
          d.closed = a.f.diff(x, order).normal();
          d.formula = sym::print(d.closed, sym::Lang::Text);
          break;
        case sym::AtomicClass::Piecewise:
          if (sym::has_exp_pieces(a)) {
            d.kind = Derivative::Kind::Chain;
            for (const auto& p : a.pieces) {
              d.chain.push_back({p.hi, p.f.diff(x, order).expand()});
              d.formula += (d.formula.empty() ? "" : "; ") +
                           sym::print(d.chain.back().second, sym::Lang::Text) + " below " +
                           (p.hi.finite() ? sym::print(p.hi.value, sym::Lang::Text) : "inf");
            }
            d.formula += "; right piece at a break, jumps' delta functions dropped";
            break;
          }
          [[fallthrough]];
        case sym::AtomicClass::Periodic:
          d.kind =
              a.cls == sym::AtomicClass::Piecewise ? Derivative::Kind::Pieces : Derivative::Kind::Periodic;
          d.pieces = diff_pieces(sym::polynomial_pieces(a, false), order);
          if (a.period) d.period = *a.period;
          d.formula = pieces_text(d.pieces) +
                      (a.period ? " (period " + sym::print(*a.period, sym::Lang::Text) + ")" : "") +
                      "; right piece at a break, jumps' delta functions dropped";
          break;
        case sym::AtomicClass::Combination: {
          const sym::Derived* c = nullptr;
          for (const auto& e : ds)
            if (e.atomic == &a && !e.squared) c = &e;
          if (!c) throw std::runtime_error("derivatives: combination " + a.name + " was not derived");
          d.kind = Derivative::Kind::Combination;
          d.closed = c->poly.diff(x, order);
          std::string text = sym::print(d.closed, sym::Lang::Text);
          for (const auto& t : c->terms) {
            if (t.xpow != 0 || t.squared)
              throw std::runtime_error("derivatives: unsupported combination term");
            // d^n/dx^n g(s x) = s^n g^(n)(s x)
            const numeric k = t.coeff * (order == 1 ? numeric(t.arg_sign) : numeric(1));
            d.terms.push_back({k, t.atomic, t.arg_sign});
            std::ostringstream s;
            s << k;
            text += " + " + s.str() + "*" + t.atomic + "_d" + std::to_string(order) + "(" +
                    (t.arg_sign < 0 ? "-x" : "x") + ")";
          }
          d.formula = text;
          break;
        }
      }
      out.push_back(std::move(d));
    }
  return out;
}

}  // namespace bl::rulegen::clamped
