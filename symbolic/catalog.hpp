// The catalog of atomic functions: parsed from JSON (symbolic/catalog.json), validated, and held
// as GiNaC expressions in the variable x. Every rejection names the entry and the field.
#pragma once

#include <ginac/ginac.h>

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace bl::sym {

// The variables every catalog expression uses.
const GiNaC::symbol& var_x();  // the argument
const GiNaC::symbol& var_y();  // the value (inverses of monotone pieces)

struct CatalogError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A real bound that may be infinite.
struct Bound {
  int inf = 0;  // -1: -inf, +1: +inf, 0: finite
  GiNaC::ex value;
  double to_double() const;
  bool finite() const { return inf == 0; }
};

struct Piece {
  Bound lo, hi;
  GiNaC::ex f;  // polynomial in x
};

struct Monotone {
  Bound lo, hi;
  GiNaC::ex inverse;  // in y
};

enum class AtomicClass { Entire, Piecewise, Periodic, Combination, Antiderivative };
const char* to_string(AtomicClass c);

struct Atomic {
  std::string name;
  AtomicClass cls{};
  GiNaC::ex f;                      // entire / antiderivative: the definition
  std::vector<Piece> pieces;        // piecewise: whole line; periodic: one period [0, period)
  std::optional<GiNaC::ex> period;  // periodic (and periodic singularities, e.g. tan)
  Bound domain_lo, domain_hi;
  Bound range_lo, range_hi;
  std::vector<GiNaC::ex> jumps, kinks, singular;  // as declared (checked against the pieces)
  bool jumps_at_integers = false;                 // combination: "jumps": ["integers"]
  std::vector<Monotone> monotone;
  // antiderivative class: F' = f, F2' = F, F_sq' = f^2, F2_sq' = F_sq (F2 entries optional)
  GiNaC::ex F, F2, F_sq, F2_sq;
  std::optional<GiNaC::ex> scale;  // length over which f varies (radius of convergence bound)
  struct Flat {
    double beyond = 0, left = 0, right = 0;
  };
  std::optional<Flat> flat;  // f is constant to machine precision for |x| > beyond
  int parity = 0;            // +1 even, -1 odd, 0 neither (checked); rules evaluate x < 0 by symmetry
  std::string of;            // combination: linear identity in other atomics
  // combination: the plain function is this C++ (std::) and GLSL built-in, for an identity that
  // holds only almost everywhere (trunc = x - fract(x) + 1 - step(x) is off by one at negative
  // integers, which the convolutions never see but a plain program, int(floor(y)) say, does).
  std::string builtin;
  std::string comment;
};

struct Catalog {
  std::vector<Atomic> atomics;
  const Atomic* find(const std::string& name) const;
};

// Parses and validates. Throws CatalogError naming entry and field.
Catalog load_catalog(const std::string& path);
Catalog parse_catalog(const std::string& json_text, const std::string& origin);

// Parses one expression in x (and y); unknown names are errors.
GiNaC::ex parse_expr(const std::string& text);

}  // namespace bl::sym
