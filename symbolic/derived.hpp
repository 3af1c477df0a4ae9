// What the engine derives for one (atomic, kernel, f or f^2) entry: the formula as text for the
// manifest, and the structured form the emitters print as stable C++ and GLSL.
#pragma once

#include <ginac/ginac.h>

#include <string>
#include <vector>

#include "catalog.hpp"
#include "kernels.hpp"

namespace bl::sym {

// A polynomial piece sum_k c[k] t^k on [lo, hi), exact coefficients.
struct PolyPiece {
  Bound lo, hi;
  std::vector<GiNaC::numeric> c;
};

// One exp-polynomial term e^{a s} sum_k c[k] s^k, s = t - ref, on [lo, hi) (ref a finite end of the
// interval, 0 on the whole line); c exact where rational, else a float constant (e^{a ref}).
struct ExpTermSpec {
  Bound lo, hi;
  GiNaC::numeric a;
  GiNaC::ex ref;
  std::vector<GiNaC::ex> c;
};

// A Fourier phase e^{-2 pi i k p/q} of a periodic piece boundary at p/q of the period (q > 2): the
// Fourier loop defines cph<p>_<q> = cos(2 pi ((k p) mod q)/q) and sph<p>_<q> = sin(...).
struct FourierPhase {
  long p, q;
  bool operator==(const FourierPhase& o) const { return p == o.p && q == o.q; }
};

enum class Body {
  Closed,          // one closed-form expression in x and sigma (exp-polynomial class, moments)
  PiecewiseTable,  // whole-line polynomial pieces, evaluated by the runtime's stable primitives
  PeriodicTable,   // one period of pieces + first/second integrals + Fourier coefficients
  Combination,     // polynomial part + linear combination of other entries of the same kernel
  Antiderivative,  // box/tent from F or F2, Taylor series in the half-width where it cancels
  ExpPieceTable    // exp-polynomial terms on intervals, evaluated by the runtime's *_ept primitives
};

// One smoothed term of a combination. The rules (Kind):
//  Smoothed:    coeff * atomic(arg_sign x)^(squared ? 2 : 1), the atomic's own entry;
//  FirstMoment: coeff * x * atomic(arg_sign x), atomic periodic: x A~ + E[U A(x+U)] (xpow = 1);
//  Pieces:      coeff * x^xpow * atomic(x)^d with a piecewise atomic: again whole-line polynomial
//               pieces (`pieces`, the product), smoothed like a piecewise atomic;
//  HalfLines:   coeff * atomic(x) * factor(x), atomic periodic, factor piecewise with constant
//               pieces whose breaks are multiples of the period: a sum of half-line restrictions,
//               full * A~(x) + sum_i right[i].first * A_right(x - right[i].second), where
//               A_right(x) = E[A(x+U) 1{x+U >= 0}] is the periodic entry's half-line companion.
struct CombinationTerm {
  GiNaC::numeric coeff;
  std::string atomic;
  int arg_sign;  // +1: atomic(x), -1: atomic(-x)
  int xpow = 0;
  bool squared = false;
  enum class Kind { Smoothed, FirstMoment, Pieces, HalfLines } kind = Kind::Smoothed;
  std::vector<PolyPiece> pieces;                            // Pieces
  std::string factor;                                       // HalfLines: the piecewise factor
  GiNaC::numeric full = 0;                                  // HalfLines
  std::vector<std::pair<GiNaC::numeric, GiNaC::ex>> right;  // HalfLines: (coefficient, break b)
};

// An entry the engine cannot derive, and why (reported by rulegen and in the manifest).
struct NotDerived {
  std::string atomic, kernel;
  bool squared;
  std::string reason;
};

struct Derived {
  const Atomic* atomic = nullptr;  // null for moments
  std::string atomic_name;
  Kernel kernel{};
  bool squared = false;
  std::string rule = "convolution";
  int order = 0;  // moment order
  std::string formula;
  Body body{};

  GiNaC::ex closed;  // Closed; Combination: the polynomial part's convolution; PiecewiseTable
                     // (Gaussian): the erf/exp closed form the runtime evaluates stably

  std::vector<ExpTermSpec> eterms;        // ExpPieceTable
  std::vector<PolyPiece> pieces, P1, P2;  // tables (P1, P2: first/second integral over a period)
  GiNaC::ex period;                       // PeriodicTable
  double fmax = 0;                        // max |f| (image-sum tolerance)
  double coef_bound = 0;                  // bound on |a_k| + |b_k|
  GiNaC::ex a0, ak, bk;                   // Fourier coefficients in k (and (-1)^k, the phases)
  std::vector<FourierPhase> phases;       // boundaries at p/q of the period, q > 2
  // PeriodicTable: the period re-origined at each inner break b that float cannot hold (b/T
  // rational, T rational): the pieces of f(t + b) on [0, T) and their integrals P1, P2. Near such a
  // break the emitted code evaluates at x - b, formed from b's exact two-part split, so a kernel
  // narrower than the break's rounding (float: 1.2e-8 at 0.3) still sees it where it is.
  struct BreakOrigin {
    GiNaC::numeric b;    // the break, in (0, T)
    GiNaC::numeric gap;  // half the distance to the nearest other break (cyclic)
    std::vector<PolyPiece> pieces, P1, P2;
  };
  std::vector<BreakOrigin> origins;
  // Periodic, not squared: the half-line companion's boundary series (Euler-Maclaurin at t = 0),
  // half_series[m] = (-1)^(m+1) S_{m+2}(0) with S_1 = f - a0 and S_{j+1} the periodic, mean-free
  // antiderivative of S_j (exact); see docs/derivations.md.
  std::vector<GiNaC::numeric> half_series;

  std::vector<CombinationTerm> terms;  // Combination
  GiNaC::ex poly;                      // Combination: the polynomial part, unsmoothed

  // Antiderivative: value = (F(x+hh) - F(x-hh)) / (2 hh) (box) or the tent's second difference of
  // F2; series[j] multiplies hh^(2j) where that difference cancels.
  GiNaC::ex f_here, F_any;
  std::vector<GiNaC::ex> series;
  double lambda = 0.5;

  std::string cpp_name() const;   // e.g. bl::gaussian::sin
  std::string glsl_name() const;  // e.g. bl_gaussian_sin
  std::string fn_suffix() const;  // e.g. sin_sq
};

const GiNaC::symbol& var_k();   // Fourier index
const GiNaC::symbol& var_pk();  // (-1)^k
const GiNaC::symbol& var_hh();  // the (possibly compacted) half-width in antiderivative rules
const GiNaC::symbol& var_phase(long p, long q, bool cosine);  // cph<p>_<q> / sph<p>_<q>

// The pieces of a piecewise or periodic atomic (of f^2 when squared) with exact coefficients.
std::vector<PolyPiece> polynomial_pieces(const Atomic& a, bool squared);

// True when a piecewise atomic has a piece that is not a polynomial (exp-polynomial pieces).
bool has_exp_pieces(const Atomic& a);
// The exp-polynomial terms of a piecewise atomic (of f^2 when squared), zero terms dropped.
std::vector<ExpTermSpec> exp_terms(const Atomic& a, bool squared);
// The terms of a whole-line exp-polynomial with real rates.
std::vector<ExpTermSpec> exp_terms_whole_line(const GiNaC::ex& f);

// Derives every entry of the catalog, plus raw moments n <= max_moment. Throws CatalogError
// (naming entry and field) when an entry's definition is outside what its class can derive.
std::vector<Derived> derive_all(const Catalog& cat, int max_moment = 16,
                                std::vector<NotDerived>* not_derived = nullptr);

}  // namespace bl::sym
