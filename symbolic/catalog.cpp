#include "catalog.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>

#include "catalog_checks.hpp"
#include "exp_poly.hpp"
#include "functions.hpp"
#include "monotone.hpp"
#include "printer.hpp"

namespace bl::sym {
using namespace GiNaC;
using nlohmann::json;

const symbol& var_x() {
  static const symbol x("x");
  return x;
}
const symbol& var_y() {
  static const symbol y("y");
  return y;
}

const char* to_string(AtomicClass c) {
  switch (c) {
    case AtomicClass::Entire:
      return "entire";
    case AtomicClass::Piecewise:
      return "piecewise";
    case AtomicClass::Periodic:
      return "periodic";
    case AtomicClass::Combination:
      return "combination";
    case AtomicClass::Antiderivative:
      return "antiderivative";
  }
  return "?";
}

double Bound::to_double() const {
  if (inf) return inf * std::numeric_limits<double>::infinity();
  return ex_to<numeric>(value.evalf()).to_double();
}

const Atomic* Catalog::find(const std::string& name) const {
  for (const auto& a : atomics)
    if (a.name == name) return &a;
  return nullptr;
}

ex parse_expr(const std::string& text) {
  register_functions();
  symtab table;
  table["x"] = var_x();
  table["y"] = var_y();
  table["Pi"] = Pi;
  parser reader(table, /*strict=*/true);
  return reader(text);
}

namespace {

struct Ctx {
  std::string entry;
  mutable std::string field;  // the field being read (names the culprit of an unexpected failure)
  [[noreturn]] void fail(const std::string& f, const std::string& msg) const {
    throw CatalogError("catalog entry '" + entry + "', field '" + f + "': " + msg);
  }
};

// A JSON value's type in words, for messages.
std::string type_of(const json& v) {
  if (v.is_null()) return "null";
  if (v.is_boolean()) return "a boolean";
  if (v.is_number()) return "a number";
  if (v.is_string()) return "a string";
  if (v.is_array()) return "a list";
  return "an object";
}

// The value as a real number (after evaluation), or a failure naming the field.
numeric real_constant(const Ctx& c, const std::string& field, const ex& e, const std::string& text) {
  ex v;
  try {
    v = e.evalf();
  } catch (const std::exception& err) {
    c.fail(field, "cannot evaluate " + text + ": " + err.what());
  }
  if (!is_a<numeric>(v)) c.fail(field, "not a constant: " + text);
  const numeric n = ex_to<numeric>(v);
  if (!n.is_real()) c.fail(field, "not a real number: " + text);
  if (!std::isfinite(n.to_double())) c.fail(field, "too large for double precision: " + text);
  return n;
}

std::string string_field(const Ctx& c, const json& j, const char* field) {
  const json& v = j.at(field);
  if (!v.is_string()) c.fail(field, "expected a string, got " + type_of(v) + " " + v.dump());
  return v.get<std::string>();
}

// A list value; `what` describes its elements for the message.
const json& list_field(const Ctx& c, const json& v, const std::string& field, const std::string& what) {
  if (!v.is_array()) c.fail(field, "expected a list of " + what + ", got " + type_of(v) + " " + v.dump());
  return v;
}

// An object value with exactly the keys `keys` (all required).
void object_with(const Ctx& c, const json& v, const std::string& field, const std::set<std::string>& keys) {
  std::string names;
  for (const auto& k : keys) names += (names.empty() ? "" : ", ") + k;
  if (!v.is_object())
    c.fail(field, "expected an object with " + names + ", got " + type_of(v) + " " + v.dump());
  for (const auto& k : keys)
    if (!v.contains(k)) c.fail(field, "missing '" + k + "' in " + v.dump());
  for (auto& [k, unused] : v.items())
    if (!keys.count(k)) c.fail(field, "unknown key '" + k + "' (expected " + names + ")");
}

ex parse_value(const Ctx& c, const std::string& field, const json& v) {
  try {
    if (v.is_number_integer()) return numeric(v.get<long>());
    if (v.is_number()) {
      c.fail(field, "write non-integers as exact expressions (\"1/2\"), not floating point");
    }
    if (v.is_string()) return parse_expr(v.get<std::string>());
  } catch (const CatalogError&) {
    throw;
  } catch (const std::exception& e) {
    c.fail(field, std::string("cannot parse expression: ") + e.what());
  }
  c.fail(field, "expected a number or an expression string, got " + type_of(v) + " " + v.dump());
}

Bound parse_bound(const Ctx& c, const std::string& field, const json& v) {
  Bound b;
  if (v.is_string() && (v == "inf" || v == "+inf")) {
    b.inf = 1;
  } else if (v.is_string() && v == "-inf") {
    b.inf = -1;
  } else {
    b.value = parse_value(c, field, v);
    real_constant(c, field, b.value, v.dump());
  }
  return b;
}

std::pair<Bound, Bound> parse_interval(const Ctx& c, const std::string& field, const json& v) {
  if (!v.is_array() || v.size() != 2) c.fail(field, "expected [lo, hi], got " + type_of(v) + " " + v.dump());
  auto lo = parse_bound(c, field, v[0]);
  auto hi = parse_bound(c, field, v[1]);
  if (lo.inf == 1 || hi.inf == -1 || (lo.finite() && hi.finite() && !(lo.to_double() < hi.to_double())))
    c.fail(field, "empty interval " + v.dump());
  return {lo, hi};
}

std::vector<ex> parse_points(const Ctx& c, const std::string& field, const json& v) {
  std::vector<ex> out;
  for (const auto& p : list_field(c, v, field, "points")) {
    out.push_back(parse_value(c, field, p));
    real_constant(c, field, out.back(), p.dump());
  }
  return out;
}

ex parse_fn(const Ctx& c, const std::string& field, const json& v) {
  if (!v.is_string() && !v.is_number_integer())
    c.fail(field, "expected an expression in x, got " + type_of(v) + " " + v.dump());
  const ex e = parse_value(c, field, v);
  if (e.has(var_y())) c.fail(field, "uses y; an expression in x is expected");
  return e;
}

bool same_value(const ex& a, const ex& b) {
  return (a - b).evalf().is_zero() || (a - b).expand().is_zero();
}

// Jumps and kinks of polynomial pieces at their joints (and, for a periodic function, at the
// joint of one period with the next), compared with what the entry declares.
void check_breaks(const Ctx& c, const Atomic& a) {
  const symbol& x = var_x();
  std::vector<ex> jumps, kinks;
  const size_t n = a.pieces.size();
  const bool periodic = a.cls == AtomicClass::Periodic;
  for (size_t i = 0; i < n; ++i) {
    const Piece& left = a.pieces[i];
    const Piece* right = i + 1 < n ? &a.pieces[i + 1] : (periodic ? &a.pieces[0] : nullptr);
    if (!right) break;
    const ex at = left.hi.value;
    const ex at_right = periodic && i + 1 == n ? ex(0) : at;
    const ex joint = periodic && i + 1 == n ? ex(0) : at;
    const ex vl = left.f.subs(x == at), vr = right->f.subs(x == at_right);
    const ex dl = left.f.diff(x).subs(x == at), dr = right->f.diff(x).subs(x == at_right);
    if (!same_value(vl, vr))
      jumps.push_back(joint);
    else if (!same_value(dl, dr))
      kinks.push_back(joint);
  }
  auto sorted = [](std::vector<ex> v) {
    std::vector<double> d;
    for (auto& e : v) d.push_back(ex_to<numeric>(e.evalf()).to_double());
    std::sort(d.begin(), d.end());
    return d;
  };
  auto show = [](const std::vector<double>& v) {
    std::ostringstream s;
    s << "[";
    for (size_t i = 0; i < v.size(); ++i) s << (i ? ", " : "") << v[i];
    return s.str() + "]";
  };
  if (sorted(jumps) != sorted(a.jumps))
    c.fail("jumps", "declares " + show(sorted(a.jumps)) + " but the pieces jump at " + show(sorted(jumps)));
  if (sorted(kinks) != sorted(a.kinks))
    c.fail("kinks",
           "declares " + show(sorted(a.kinks)) + " but the pieces have kinks at " + show(sorted(kinks)));
}

// A piecewise piece outside the polynomials: an exp-polynomial sum c x^n e^{a x} with real rational
// rates a (sin/cos on a finite interval would need a complex erf), polynomial degree <= 3 per rate
// (f^2 then has degree 6 and the tent's weight one more: the runtime's 8 coefficients), and no
// exponential growth towards an infinite end of the piece (the smoothed values would not exist for
// box/tent in a shader's float range, and such an f has no finite range).
void check_exp_piece(const Ctx& c, size_t i, const Piece& p, const ex& f) {
  const std::string which = "piece " + std::to_string(i);
  ExpPoly e;
  try {
    e = ExpPoly::from(f);
  } catch (const std::invalid_argument& err) {
    c.fail("pieces", which + " is neither a polynomial nor an exp-polynomial in x (" + err.what() + ")");
  }
  for (const auto& [k, coeff] : e.terms()) {
    std::ostringstream t;
    t << "x^" << k.n << " e^(" << k.a << " x)";
    if (!k.a.is_real() || !coeff.is_real())
      c.fail(
          "pieces",
          which + ": the term " + t.str() +
              " has a complex rate (sin/cos pieces on an interval are not supported; use the entire class)");
    if (k.n > 3) c.fail("pieces", which + ": the term " + t.str() + " has a power above 3");
    if (p.hi.inf == 1 && k.a > 0)
      c.fail("pieces", which + ": the term " + t.str() + " grows exponentially towards +inf");
    if (p.lo.inf == -1 && k.a < 0)
      c.fail("pieces", which + ": the term " + t.str() + " grows exponentially towards -inf");
  }
}

void check_polynomial_pieces(const Ctx& c, Atomic& a) {
  const symbol& x = var_x();
  if (a.pieces.empty()) c.fail("pieces", "at least one piece is required");
  for (size_t i = 0; i < a.pieces.size(); ++i) {
    const ex f = a.pieces[i].f.expand();
    if (!f.is_polynomial(x)) {
      if (a.cls == AtomicClass::Periodic)
        c.fail("pieces",
               "piece " + std::to_string(i) + " is not a polynomial in x (periodic pieces are polynomials)");
      check_exp_piece(c, i, a.pieces[i], f);
      a.pieces[i].f = f;
      if (i > 0 && (!a.pieces[i - 1].hi.finite() || !a.pieces[i].lo.finite()))
        c.fail("pieces", "piece " + std::to_string(i) +
                             ": only the first piece may start at -inf and the last end at inf");
      if (i > 0 && !same_value(a.pieces[i - 1].hi.value, a.pieces[i].lo.value))
        c.fail("pieces", "piece " + std::to_string(i) + " does not start where piece " +
                             std::to_string(i - 1) + " ends");
      continue;
    }
    if (f.degree(x) > (a.cls == AtomicClass::Periodic ? 2 : 3))
      c.fail("pieces", "piece " + std::to_string(i) +
                           " has too high a degree (max 3, periodic 2: its square and, for a period, its "
                           "second integral must fit the runtime degree-7 pieces)");
    for (int k = 0; k <= f.degree(x); ++k)
      if (!is_a<numeric>(f.coeff(x, k)) || !ex_to<numeric>(f.coeff(x, k)).is_rational())
        c.fail("pieces", "piece " + std::to_string(i) + ": the coefficients must be rational numbers");
    a.pieces[i].f = f;
    if (i > 0 && (!a.pieces[i - 1].hi.finite() || !a.pieces[i].lo.finite()))
      c.fail("pieces", "piece " + std::to_string(i) +
                           ": only the first piece may start at -inf and the last end at inf");
    if (i > 0 && !same_value(a.pieces[i - 1].hi.value, a.pieces[i].lo.value))
      c.fail("pieces",
             "piece " + std::to_string(i) + " does not start where piece " + std::to_string(i - 1) + " ends");
  }
  if (a.cls == AtomicClass::Piecewise) {
    if (a.pieces.front().lo.inf != -1 || a.pieces.back().hi.inf != 1)
      c.fail("pieces", "the pieces must cover the whole line, from -inf to inf");
  } else {
    // The engine integrates one period exactly (and phases its Fourier series at the breaks, any
    // rational fraction of the period): the period and every break must be rational numbers.
    for (size_t i = 0; i < a.pieces.size(); ++i)
      for (const Bound* b : {&a.pieces[i].lo, &a.pieces[i].hi})
        if (b->finite() && !(is_a<numeric>(b->value) && ex_to<numeric>(b->value).is_rational()))
          c.fail("pieces", "piece " + std::to_string(i) +
                               ": periodic piece boundaries must be rational numbers, got " +
                               print(b->value, Lang::Text));
    if (!a.pieces.front().lo.finite() || !a.pieces.front().lo.value.is_zero())
      c.fail("pieces", "the pieces of one period must start at 0");
    if (!a.pieces.back().hi.finite() || !same_value(a.pieces.back().hi.value, *a.period))
      c.fail("period", "the pieces end at " + std::to_string(a.pieces.back().hi.to_double()) +
                           " but the period is " +
                           std::to_string(ex_to<numeric>(a.period->evalf()).to_double()));
  }
  check_breaks(c, a);
}

void require(const Ctx& c, const json& j, const char* field) {
  if (!j.contains(field)) c.fail(field, "missing");
  c.field = field;
}

Atomic parse_atomic_fields(const json& j, const Ctx& c) {
  Atomic a;
  a.name = c.entry;
  c.field = "class";
  require(c, j, "class");
  static const std::map<std::string, AtomicClass> classes = {{"entire", AtomicClass::Entire},
                                                             {"piecewise", AtomicClass::Piecewise},
                                                             {"periodic", AtomicClass::Periodic},
                                                             {"combination", AtomicClass::Combination},
                                                             {"antiderivative", AtomicClass::Antiderivative}};
  auto it = classes.find(j["class"].is_string() ? j["class"].get<std::string>() : "");
  if (it == classes.end())
    c.fail("class", "unknown class " + j["class"].dump() +
                        " (entire, piecewise, periodic, combination, antiderivative)");
  a.cls = it->second;

  static const std::set<std::string> common = {"name",    "class",    "domain", "range",
                                               "comment", "monotone", "jumps",  "kinks"};
  static const std::map<AtomicClass, std::set<std::string>> allowed = {
      {AtomicClass::Entire, {"f", "period"}},
      {AtomicClass::Piecewise, {"pieces"}},
      {AtomicClass::Periodic, {"pieces", "period"}},
      {AtomicClass::Combination, {"of", "builtin"}},
      {AtomicClass::Antiderivative,
       {"f", "F", "F2", "F_sq", "F2_sq", "period", "singular", "scale", "flat", "parity"}}};
  for (auto& [k, v] : j.items())
    if (!common.count(k) && !allowed.at(a.cls).count(k))
      c.fail(k, std::string("unknown field for class '") + to_string(a.cls) + "'");

  require(c, j, "domain");
  std::tie(a.domain_lo, a.domain_hi) = parse_interval(c, "domain", j["domain"]);
  require(c, j, "range");
  {
    const json& r = j["range"];
    if (!r.is_array() || r.size() != 2)
      c.fail("range", "expected [lo, hi], got " + type_of(r) + " " + r.dump());
    a.range_lo = parse_bound(c, "range", r[0]);
    a.range_hi = parse_bound(c, "range", r[1]);
    if (a.range_lo.inf == 1 || a.range_hi.inf == -1 || a.range_lo.to_double() > a.range_hi.to_double())
      c.fail("range", "lo > hi in " + r.dump());
  }
  if (j.contains("comment")) a.comment = string_field(c, j, "comment");
  if (j.contains("period")) {
    c.field = "period";
    a.period = parse_value(c, "period", j["period"]);
    if (!(real_constant(c, "period", *a.period, j["period"].dump()) > 0))
      c.fail("period", "must be a positive constant");
  }
  if (j.contains("jumps")) {
    c.field = "jumps";
    if (j["jumps"] == json::array({"integers"}))
      a.jumps_at_integers = true;
    else
      a.jumps = parse_points(c, "jumps", j["jumps"]);
  }
  if (j.contains("kinks")) {
    c.field = "kinks";
    a.kinks = parse_points(c, "kinks", j["kinks"]);
  }
  if (j.contains("monotone")) {
    c.field = "monotone";
    for (const auto& m : list_field(c, j["monotone"], "monotone", "{\"on\": [lo, hi], \"inverse\": g(y)}")) {
      object_with(c, m, "monotone", {"on", "inverse"});
      Monotone mp;
      std::tie(mp.lo, mp.hi) = parse_interval(c, "monotone", m["on"]);
      if (!m["inverse"].is_string() && !m["inverse"].is_number_integer())
        c.fail("monotone", "expected an expression in y as 'inverse', got " + type_of(m["inverse"]));
      mp.inverse = parse_value(c, "monotone", m["inverse"]);
      if (mp.inverse.has(var_x())) c.fail("monotone", "the inverse is an expression in y, not x");
      a.monotone.push_back(mp);
    }
  }

  switch (a.cls) {
    case AtomicClass::Entire:
      require(c, j, "f");
      a.f = parse_fn(c, "f", j["f"]);
      c.field = "range";
      check_range(a);
      break;
    case AtomicClass::Piecewise:
    case AtomicClass::Periodic:
      if (a.cls == AtomicClass::Periodic) require(c, j, "period");
      require(c, j, "pieces");
      for (const auto& p : list_field(c, j["pieces"], "pieces", "{\"on\": [lo, hi], \"f\": ...}")) {
        object_with(c, p, "pieces", {"on", "f"});
        Piece pc;
        std::tie(pc.lo, pc.hi) = parse_interval(c, "pieces", p["on"]);
        pc.f = parse_fn(c, "pieces", p["f"]);
        a.pieces.push_back(pc);
      }
      c.field = "pieces";
      check_polynomial_pieces(c, a);
      c.field = "range";
      check_range(a);
      break;
    case AtomicClass::Combination:
      require(c, j, "of");
      a.of = string_field(c, j, "of");
      if (j.contains("builtin")) {
        // Built-ins with the same meaning in C++'s <cmath> (std::) and GLSL.
        static const std::set<std::string> builtins = {"trunc", "floor", "ceil"};
        a.builtin = string_field(c, j, "builtin");
        if (!builtins.count(a.builtin))
          c.fail("builtin",
                 "'" + a.builtin + "' is not a built-in of both C++ and GLSL (trunc, floor, ceil)");
      }
      break;
    case AtomicClass::Antiderivative: {
      for (const char* f : {"f", "F", "F_sq"}) require(c, j, f);
      a.f = parse_fn(c, "f", j["f"]);
      a.F = parse_fn(c, "F", j["F"]);
      a.F_sq = parse_fn(c, "F_sq", j["F_sq"]);
      if (j.contains("F2")) a.F2 = parse_fn(c, "F2", j["F2"]);
      if (j.contains("F2_sq")) a.F2_sq = parse_fn(c, "F2_sq", j["F2_sq"]);
      if (j.contains("singular")) {
        c.field = "singular";
        a.singular = parse_points(c, "singular", j["singular"]);
      }
      if (j.contains("scale")) {
        // A positive constant, or a positive expression in x where the Taylor radius grows with
        // |x| (atan: (|x| + 1)/sqrt(2), a lower bound of sqrt(1 + x^2), its distance to the poles
        // at +-i). Checked positive at sample points of the domain.
        c.field = "scale";
        a.scale = parse_fn(c, "scale", j["scale"]);
        for (double x : {-1e6, -30.0, -1.0, -0.25, 0.0, 0.5, 3.0, 1e6}) {
          if (!(x > a.domain_lo.to_double() && x < a.domain_hi.to_double())) continue;
          const numeric v = real_constant(c, "scale", a.scale->subs(var_x() == x),
                                          j["scale"].dump() + " at x = " + std::to_string(x));
          if (!(v > 0))
            c.fail("scale",
                   "must be positive, is " + std::to_string(v.to_double()) + " at x = " + std::to_string(x));
        }
      }
      if (j.contains("flat")) {
        c.field = "flat";
        const json& fl = j["flat"];
        object_with(c, fl, "flat", {"beyond", "left", "right"});
        for (const char* k : {"beyond", "left", "right"})
          if (!fl[k].is_number() || !std::isfinite(fl[k].get<double>()))
            c.fail("flat", std::string("'") + k + "' must be a finite number, got " + type_of(fl[k]) + " " +
                               fl[k].dump());
        a.flat =
            Atomic::Flat{fl["beyond"].get<double>(), fl["left"].get<double>(), fl["right"].get<double>()};
        if (!(a.flat->beyond > 0)) c.fail("flat", "'beyond' must be positive");
      }
      if (j.contains("parity")) {
        c.field = "parity";
        const std::string p = j["parity"].is_string() ? j["parity"].get<std::string>() : "";
        if (p != "odd" && p != "even")
          c.fail("parity", "must be \"odd\" or \"even\", got " + j["parity"].dump());
        a.parity = p == "odd" ? -1 : 1;
        for (int k = 1; k <= 7; ++k) {  // f(-x) = parity f(x) at sample points, 30 digits
          const ex at = numeric(k * 3, 10);
          const ex diff = (a.f.subs(var_x() == -at) - a.parity * a.f.subs(var_x() == at)).evalf();
          if (!is_a<numeric>(diff) || abs(ex_to<numeric>(diff)) > numeric(1, 1000000000000))
            c.fail("parity", "f(-x) != " + std::string(a.parity < 0 ? "-" : "") +
                                 "f(x) at x = " + std::to_string(k * 0.3));
        }
      }
      c.field = "scale";
      if (a.singular.empty() && !a.scale)
        c.fail("scale", "an atomic without singularities needs a scale (its Taylor radius)");
      c.field = "f";
      check_smooth(a);  // may rewrite abs in f (a.f) into a differentiable form
      c.field = "flat";
      check_flat(a);
      struct Anti {
        const char* field;
        const ex* F;
        ex f;
      };
      const Anti antis[] = {
          {"F", &a.F, a.f}, {"F_sq", &a.F_sq, pow(a.f, 2)}, {"F2", &a.F2, a.F}, {"F2_sq", &a.F2_sq, a.F_sq}};
      for (const Anti& an : antis) {
        if (!j.contains(an.field)) continue;
        c.field = an.field;
        check_antiderivative(a, an.field, *an.F, an.f);
        check_continuity(a, an.field, *an.F);
      }
      c.field = "range";
      check_range(a);
      break;
    }
  }
  return a;
}

Atomic parse_atomic(const json& j, size_t index) {
  const bool named = j.is_object() && j.contains("name") && j["name"].is_string();
  Ctx c{named ? j["name"].get<std::string>() : "#" + std::to_string(index)};
  if (!j.is_object()) c.fail("", "an entry must be a JSON object, got " + type_of(j) + " " + j.dump());
  require(c, j, "name");
  if (!named) c.fail("name", "expected a string, got " + type_of(j["name"]) + " " + j["name"].dump());
  if (!std::regex_match(c.entry, std::regex("[a-z][a-z0-9_]*")))
    c.fail("name", "must match [a-z][a-z0-9_]* (it becomes a C++ and GLSL identifier)");
  try {
    return parse_atomic_fields(j, c);
  } catch (const CatalogError&) {
    throw;
  } catch (const std::exception& e) {
    // Safety net: what a check above did not anticipate still names the entry and the field.
    c.fail(c.field, std::string("cannot be processed: ") + e.what());
  }
}

}  // namespace

Catalog parse_catalog(const std::string& text, const std::string& origin) {
  json j;
  try {
    j = json::parse(text);
  } catch (const std::exception& e) {
    throw CatalogError(origin + ": not valid JSON: " + e.what());
  }
  if (!j.is_object() || !j.contains("atomics") || !j["atomics"].is_array())
    throw CatalogError(origin + ": expected an object with an 'atomics' list");
  for (auto& [k, v] : j.items()) {
    if (k != "atomics" && k != "comment")
      throw CatalogError(origin + ": unknown top-level field '" + k + "'");
    if (k == "comment" && !v.is_string())
      throw CatalogError(origin + ": top-level field 'comment': expected a string");
  }
  Catalog cat;
  std::set<std::string> seen;
  try {
    for (size_t i = 0; i < j["atomics"].size(); ++i) {
      Atomic a = parse_atomic(j["atomics"][i], i);
      try {
        check_monotone(a);  // Rule 2 inverts f on these pieces
      } catch (const CatalogError&) {
        throw;
      } catch (const std::exception& e) {
        throw CatalogError("catalog entry '" + a.name +
                           "', field 'monotone': cannot be processed: " + e.what());
      }
      if (!seen.insert(a.name).second)
        throw CatalogError("catalog entry '" + a.name + "', field 'name': defined twice");
      cat.atomics.push_back(std::move(a));
    }
  } catch (const CatalogError& e) {
    throw CatalogError(origin + ": " + e.what());  // the file, then the entry and the field
  }
  return cat;
}

Catalog load_catalog(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw CatalogError("cannot read catalog " + path);
  std::stringstream s;
  s << in.rdbuf();
  return parse_catalog(s.str(), path);
}

}  // namespace bl::sym
