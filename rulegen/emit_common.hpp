// Shared by the C++ and GLSL emitters: prints the body of one derived entry in either language.
#pragma once

#include <string>
#include <vector>

#include "derived.hpp"
#include "emit_gauss_periodic.hpp"
#include "printer.hpp"

namespace bl::rulegen {

using sym::Derived;
using sym::Lang;

// Internal function name: gaussian_sin_sq, plain_fract, gaussian_moment.
std::string impl_name(const Derived& d);
std::string plain_impl_name(const std::string& atomic);

// The statements of the function body, in C++ (template over T, with x and sigma in scope) or
// GLSL (float). ds: all derived entries (a Gaussian combination fuses the entries of its periodic
// atomic from them; null: no fusion).
std::string body(const Derived& d, Lang lang, const std::vector<Derived>* ds = nullptr);

// The statements of an entry's body that clamp its value `v` to the range the true value lies in
// ([inf f, sup f] for E[f(x+U)], the range of f^2 for E[f^2]), or "" when the atomic's range is
// unbounded on both sides or the entry is not a convolution. Averages cannot leave that range, but
// their rounding can (gaussian saturate at z = -14 gave -1.4e-45, and sqrt of it a NaN downstream).
// NaN passes through.
std::string range_clamp(const Derived& d, Lang lang);
// Body of E[U g(x+U)] for a periodic entry (not squared): impl_name(d) + "_u".
std::string body_u(const Derived& d, Lang lang);
// Antiderivative entries: the Taylor series in the half-width hh, impl_name(d) + "_series"(x, hh).
std::string series_body(const Derived& d, Lang lang);
// Antiderivative entries: the difference quotient of F (F2) at half-width hh, impl_name(d) + "_diff".
std::string diff_body(const Derived& d, Lang lang);
inline bool has_series(const Derived& d) {
  return d.body == sym::Body::Antiderivative;
}
// True for the entries that get such a first-moment companion.
inline bool has_first_moment(const Derived& d) {
  return d.body == sym::Body::PeriodicTable && !d.squared;
}
// Body of E[f(x+U) 1{x+U >= 0}] for a periodic entry (not squared): impl_name(d) + "_right", used by
// products of f with a piecewise-constant atomic (trunc^2's fract * step).
std::string body_half_line(const Derived& d, Lang lang);
inline bool has_half_line(const Derived& d) {
  return d.body == sym::Body::PeriodicTable && !d.squared;
}
// Body of the plain (unsmoothed) function f(x).
std::string plain_body(const sym::Atomic& a, const std::vector<Derived>& ds, Lang lang);
// A straight-line chain "v < hi_0 ? p_0(v) : v < hi_1 ? ... : p_last(v)" over sorted pieces
// (right-continuous at the breaks, as pw_eval), one expression.
std::string piece_chain(const std::vector<sym::PolyPiece>& ps, const std::string& v, Lang lang);
// sum_k c[k] x^k in sym::var_x(), lowest coefficient first (numeric or symbolic coefficients).
template <class C>
GiNaC::ex poly_in_x(const std::vector<C>& c) {
  GiNaC::ex f = 0;
  for (size_t k = 0; k < c.size(); ++k) f += GiNaC::ex(c[k]) * GiNaC::pow(sym::var_x(), static_cast<int>(k));
  return f;
}
// A periodic function of x given on one period [0, P) by pieces (hi_i, f_i(sym::var_x())), as
// straight-line statements on the exact signed remainder r (periodic_eval's piece choice). With
// nan_guard a NaN r (x NaN or infinite) is returned as is (constant pieces would hide it). `arg`:
// the variable reduced (x, or y where the caller mirrored it); `lead`: printed before each returned
// piece ("rest + ").
std::string periodic_straight(const GiNaC::ex& P, const std::vector<std::pair<GiNaC::ex, GiNaC::ex>>& pieces,
                              Lang lang, bool nan_guard, const std::string& arg = "x",
                              const std::string& lead = "");

// The straight-line plan's input (emit_gauss_periodic.hpp) of a Gaussian periodic entry (an empty
// spec when its period or breaks are not numbers).
GaussPeriodicSpec periodic_spec(const Derived& d);
// C++ only: the body of a periodic entry that takes pixel-sized kernels by the nearest break
// (box_tent_periodic_hot, gauss_periodic_hot) and calls `general` (its full body, out of line) for
// the rest; "" for every other entry. When every value the pixel-sized path returns lies in the
// entry's range by construction (a 0/1 pulse train, fract), the body ends in the general call under
// `clamp` (range_clamp's text) and *in_range is set: the entry needs no clamping wrapper.
std::string periodic_hot(const Derived& d, const std::string& general, const std::string& clamp,
                         bool* in_range);
// The last statement of such a body: the general body's value, range-clamped by `clamp` (range_clamp's
// text, reading v) unless it is empty.
std::string general_call(const std::string& general, const std::string& clamp);
// The Gaussian entries of a one-piece periodic atomic A (fract) and of A^2, when both were derived
// with polynomial pieces of degree <= 1 (A) and <= 2 (A^2) and no interior break; both null else.
struct FusablePair {
  const Derived* a = nullptr;
  const Derived* a2 = nullptr;
};
FusablePair fusable_pair(const std::string& atomic, const std::vector<Derived>* ds);

// a's row in the registry's kAtomics (the catalog's order; null: the raw moments' row after them).
// Throws for an atomic of another catalog.
int atomic_index(const sym::Catalog& cat, const sym::Atomic* a);

std::string read_file(const std::string& path);
// Writes only if the content changed; creates parent directories.
void write_file(const std::string& path, const std::string& content);

// Emitters.
void emit_cpp(const sym::Catalog& cat, const std::vector<Derived>& ds, const std::string& out_dir);
void emit_glsl(const sym::Catalog& cat, const std::vector<Derived>& ds, const std::string& out_dir);
void emit_manifest(const sym::Catalog& cat, const std::vector<Derived>& ds,
                   const std::vector<sym::NotDerived>& not_derived, const std::string& out_dir,
                   const std::string& catalog_label);

}  // namespace bl::rulegen
