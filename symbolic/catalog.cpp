#include "catalog.hpp"

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>

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
    case AtomicClass::Entire: return "entire";
    case AtomicClass::Piecewise: return "piecewise";
    case AtomicClass::Periodic: return "periodic";
    case AtomicClass::Combination: return "combination";
    case AtomicClass::Antiderivative: return "antiderivative";
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
  [[noreturn]] void fail(const std::string& field, const std::string& msg) const {
    throw CatalogError("catalog entry '" + entry + "', field '" + field + "': " + msg);
  }
};

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
  c.fail(field, "expected a number or an expression string, got " + v.dump());
}

Bound parse_bound(const Ctx& c, const std::string& field, const json& v) {
  Bound b;
  if (v.is_string() && (v == "inf" || v == "+inf")) {
    b.inf = 1;
  } else if (v.is_string() && v == "-inf") {
    b.inf = -1;
  } else {
    b.value = parse_value(c, field, v);
    if (!is_a<numeric>(b.value.evalf())) c.fail(field, "bound is not a constant: " + v.dump());
  }
  return b;
}

std::pair<Bound, Bound> parse_interval(const Ctx& c, const std::string& field, const json& v) {
  if (!v.is_array() || v.size() != 2) c.fail(field, "expected [lo, hi], got " + v.dump());
  auto lo = parse_bound(c, field, v[0]);
  auto hi = parse_bound(c, field, v[1]);
  if (lo.inf == 1 || hi.inf == -1 || (lo.finite() && hi.finite() && !(lo.to_double() < hi.to_double())))
    c.fail(field, "empty interval " + v.dump());
  return {lo, hi};
}

std::vector<ex> parse_points(const Ctx& c, const std::string& field, const json& v) {
  if (!v.is_array()) c.fail(field, "expected a list of points, got " + v.dump());
  std::vector<ex> out;
  for (const auto& p : v) out.push_back(parse_value(c, field, p));
  return out;
}

ex parse_fn(const Ctx& c, const std::string& field, const json& v) {
  if (!v.is_string() && !v.is_number_integer()) c.fail(field, "expected an expression in x");
  return parse_value(c, field, v);
}

bool same_value(const ex& a, const ex& b) { return (a - b).evalf().is_zero() || (a - b).expand().is_zero(); }

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
    c.fail("kinks", "declares " + show(sorted(a.kinks)) + " but the pieces have kinks at " + show(sorted(kinks)));
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
      if (i > 0 && !same_value(a.pieces[i - 1].hi.value, a.pieces[i].lo.value))
        c.fail("pieces", "piece " + std::to_string(i) + " does not start where piece " +
                             std::to_string(i - 1) + " ends");
      continue;
    }
    if (f.degree(x) > (a.cls == AtomicClass::Periodic ? 2 : 3))
      c.fail("pieces", "piece " + std::to_string(i) + " has too high a degree (max 3, periodic 2: its square and, for a period, its second integral must fit the runtime degree-7 pieces)");
    a.pieces[i].f = f;
    if (i > 0 && !same_value(a.pieces[i - 1].hi.value, a.pieces[i].lo.value))
      c.fail("pieces", "piece " + std::to_string(i) + " does not start where piece " + std::to_string(i - 1) + " ends");
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
                           " but the period is " + std::to_string(ex_to<numeric>(a.period->evalf()).to_double()));
  }
  check_breaks(c, a);
}

// F' = f, checked at sample points in the domain away from singularities, at 40 digits.
void check_antiderivative(const Ctx& c, const Atomic& a, const std::string& field, const ex& F, const ex& f) {
  const symbol& x = var_x();
  const ex dF = F.diff(x);
  const double samples[] = {0.3, 0.7, 1.3, 2.9, 5.1, -0.4, -1.1, -2.3};
  const int saved = Digits;
  Digits = 40;
  int used = 0;
  for (double s : samples) {
    if (a.domain_lo.finite() && s <= a.domain_lo.to_double()) continue;
    if (a.domain_hi.finite() && s >= a.domain_hi.to_double()) continue;
    const ex at = numeric(static_cast<long>(s * 10), 10);
    const ex lhs = dF.subs(x == at).evalf(), rhs = f.subs(x == at).evalf();
    if (!is_a<numeric>(lhs) || !is_a<numeric>(rhs)) continue;
    const numeric dl = ex_to<numeric>(lhs), dr = ex_to<numeric>(rhs);
    if (!dl.is_real() || !dr.is_real()) continue;
    ++used;
    if (abs(dl - dr) > numeric(1, 1000000000) * numeric(1, 1000000000) * (1 + abs(dr))) {
      Digits = saved;
      std::ostringstream s;
      s << "d/dx of the given antiderivative differs from the integrand at x = " << at << ": "
        << dl.to_double() << " vs " << dr.to_double();
      c.fail(field, s.str());
    }
  }
  Digits = saved;
  if (used < 3) c.fail(field, "fewer than 3 sample points to check the antiderivative in the domain");
}

void require(const Ctx& c, const json& j, const char* field) {
  if (!j.contains(field)) c.fail(field, "missing");
}

Atomic parse_atomic(const json& j, size_t index) {
  Ctx c{j.contains("name") && j["name"].is_string() ? j["name"].get<std::string>()
                                                      : "#" + std::to_string(index)};
  if (!j.is_object()) c.fail("", "an entry must be a JSON object");
  require(c, j, "name");
  Atomic a;
  a.name = c.entry;
  if (!std::regex_match(a.name, std::regex("[a-z][a-z0-9_]*")))
    c.fail("name", "must match [a-z][a-z0-9_]* (it becomes a C++ and GLSL identifier)");
  require(c, j, "class");
  static const std::map<std::string, AtomicClass> classes = {
      {"entire", AtomicClass::Entire},           {"piecewise", AtomicClass::Piecewise},
      {"periodic", AtomicClass::Periodic},       {"combination", AtomicClass::Combination},
      {"antiderivative", AtomicClass::Antiderivative}};
  auto it = classes.find(j["class"].is_string() ? j["class"].get<std::string>() : "");
  if (it == classes.end()) c.fail("class", "unknown class " + j["class"].dump());
  a.cls = it->second;

  static const std::set<std::string> common = {"name", "class", "domain", "range", "comment",
                                               "monotone", "jumps", "kinks"};
  static const std::map<AtomicClass, std::set<std::string>> allowed = {
      {AtomicClass::Entire, {"f", "period"}},
      {AtomicClass::Piecewise, {"pieces"}},
      {AtomicClass::Periodic, {"pieces", "period"}},
      {AtomicClass::Combination, {"of"}},
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
    if (!r.is_array() || r.size() != 2) c.fail("range", "expected [lo, hi]");
    a.range_lo = parse_bound(c, "range", r[0]);
    a.range_hi = parse_bound(c, "range", r[1]);
  }
  if (j.contains("comment")) a.comment = j["comment"].get<std::string>();
  if (j.contains("period")) {
    a.period = parse_value(c, "period", j["period"]);
    const ex p = a.period->evalf();
    if (!is_a<numeric>(p) || !(ex_to<numeric>(p) > 0)) c.fail("period", "must be a positive constant");
  }
  if (j.contains("jumps")) {
    if (j["jumps"] == json::array({"integers"}))
      a.jumps_at_integers = true;
    else
      a.jumps = parse_points(c, "jumps", j["jumps"]);
  }
  if (j.contains("kinks")) a.kinks = parse_points(c, "kinks", j["kinks"]);
  if (j.contains("monotone")) {
    for (const auto& m : j["monotone"]) {
      if (!m.contains("on") || !m.contains("inverse")) c.fail("monotone", "each piece needs 'on' and 'inverse'");
      Monotone mp;
      std::tie(mp.lo, mp.hi) = parse_interval(c, "monotone", m["on"]);
      mp.inverse = parse_value(c, "monotone", m["inverse"]);
      a.monotone.push_back(mp);
    }
  }

  switch (a.cls) {
    case AtomicClass::Entire:
      require(c, j, "f");
      a.f = parse_fn(c, "f", j["f"]);
      break;
    case AtomicClass::Piecewise:
    case AtomicClass::Periodic:
      if (a.cls == AtomicClass::Periodic) require(c, j, "period");
      require(c, j, "pieces");
      for (const auto& p : j["pieces"]) {
        if (!p.contains("on") || !p.contains("f")) c.fail("pieces", "each piece needs 'on' and 'f'");
        Piece pc;
        std::tie(pc.lo, pc.hi) = parse_interval(c, "pieces", p["on"]);
        pc.f = parse_fn(c, "pieces", p["f"]);
        a.pieces.push_back(pc);
      }
      check_polynomial_pieces(c, a);
      break;
    case AtomicClass::Combination:
      require(c, j, "of");
      a.of = j["of"].get<std::string>();
      break;
    case AtomicClass::Antiderivative: {
      for (const char* f : {"f", "F", "F_sq"}) require(c, j, f);
      a.f = parse_fn(c, "f", j["f"]);
      a.F = parse_fn(c, "F", j["F"]);
      a.F_sq = parse_fn(c, "F_sq", j["F_sq"]);
      if (j.contains("F2")) a.F2 = parse_fn(c, "F2", j["F2"]);
      if (j.contains("F2_sq")) a.F2_sq = parse_fn(c, "F2_sq", j["F2_sq"]);
      if (j.contains("singular")) a.singular = parse_points(c, "singular", j["singular"]);
      if (j.contains("scale")) a.scale = parse_value(c, "scale", j["scale"]);
      if (j.contains("flat")) {
        const json& fl = j["flat"];
        if (!fl.contains("beyond") || !fl.contains("left") || !fl.contains("right"))
          c.fail("flat", "needs beyond, left and right");
        a.flat = Atomic::Flat{fl["beyond"].get<double>(), fl["left"].get<double>(), fl["right"].get<double>()};
      }
      if (j.contains("parity")) {
        const std::string p = j["parity"].is_string() ? j["parity"].get<std::string>() : "";
        if (p != "odd" && p != "even") c.fail("parity", "must be \"odd\" or \"even\"");
        a.parity = p == "odd" ? -1 : 1;
        for (int k = 1; k <= 7; ++k) {  // f(-x) = parity f(x) at sample points, 30 digits
          const ex at = numeric(k * 3, 10);
          const ex diff = (a.f.subs(var_x() == -at) - a.parity * a.f.subs(var_x() == at)).evalf();
          if (!is_a<numeric>(diff) || abs(ex_to<numeric>(diff)) > numeric(1, 1000000000000))
            c.fail("parity", "f(-x) != " + std::string(a.parity < 0 ? "-" : "") + "f(x) at x = " + std::to_string(k * 0.3));
        }
      }
      if (a.singular.empty() && !a.scale) c.fail("scale", "an atomic without singularities needs a scale (its Taylor radius)");
      check_antiderivative(c, a, "F", a.F, a.f);
      check_antiderivative(c, a, "F_sq", a.F_sq, pow(a.f, 2));
      if (j.contains("F2")) check_antiderivative(c, a, "F2", a.F2, a.F);
      if (j.contains("F2_sq")) check_antiderivative(c, a, "F2_sq", a.F2_sq, a.F_sq);
      break;
    }
  }
  return a;
}

}  // namespace

Catalog parse_catalog(const std::string& text, const std::string& origin) {
  json j;
  try {
    j = json::parse(text);
  } catch (const std::exception& e) {
    throw CatalogError(origin + ": not valid JSON: " + e.what());
  }
  if (!j.contains("atomics") || !j["atomics"].is_array())
    throw CatalogError(origin + ": expected an object with an 'atomics' list");
  Catalog cat;
  std::set<std::string> seen;
  for (size_t i = 0; i < j["atomics"].size(); ++i) {
    Atomic a = parse_atomic(j["atomics"][i], i);
    check_monotone(a);  // Rule 2 inverts f on these pieces
    if (!seen.insert(a.name).second)
      throw CatalogError("catalog entry '" + a.name + "', field 'name': defined twice");
    cat.atomics.push_back(std::move(a));
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
