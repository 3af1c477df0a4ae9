#include "ir/ranges.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "ir/atomics.hpp"

namespace bl::ir {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
const Interval kAll{-kInf, kInf};

Interval hull(std::initializer_list<double> v) {
  Interval r{kInf, -kInf};
  for (double x : v) {
    if (std::isnan(x)) return kAll;  // inf - inf, 0 * inf: give up rather than guess
    r.lo = std::min(r.lo, x);
    r.hi = std::max(r.hi, x);
  }
  return r;
}

// Atomics that are continuous and monotone on (-inf, 0] and on [0, inf) where defined: on [a, b]
// their values lie between f(a), f(b) and f(0) (0 only when inside). A singularity or a domain
// edge gives a non-finite value there, and then the catalog's range is used instead.
bool monotone_each_side(const char* name) {
  static const char* const names[] = {"exp",  "sinh",     "cosh",       "pow2",  "pow3", "pow4",
                                      "pow5", "pow6",     "pow7",       "pow8",  "abs",  "sign",
                                      "step", "saturate", "smoothstep", "floor", "ceil", "trunc",
                                      "tanh", "log",      "sqrt",       "inv",   "inv2", "atan"};
  for (const char* n : names)
    if (std::strcmp(n, name) == 0) return true;
  return false;
}

Interval call_range(int atomic, const Interval& x) {
  Interval cat;
  atomic_range(atomic, &cat.lo, &cat.hi);
  if (!monotone_each_side(atomic_name(atomic)) || !std::isfinite(x.lo) || !std::isfinite(x.hi)) return cat;
  const double fa = plain_atomic(atomic, x.lo), fb = plain_atomic(atomic, x.hi);
  double f0 = fa;
  if (x.lo < 0 && 0 < x.hi) f0 = plain_atomic(atomic, 0.0);
  if (!std::isfinite(fa) || !std::isfinite(fb) || !std::isfinite(f0)) return cat;
  const Interval img = hull({fa, fb, f0});
  return {std::max(img.lo, cat.lo), std::min(img.hi, cat.hi)};
}

}  // namespace

bool Interval::bounded() const {
  return std::isfinite(lo) || std::isfinite(hi);
}

std::vector<Interval> node_ranges(const Graph& g) {
  std::vector<Interval> r(g.size(), kAll);
  for (int i = 0; i < g.size(); ++i) {  // index order is a topological order
    const Node& n = g.node(i);
    const Interval a = n.a >= 0 ? r[n.a] : kAll, b = n.b >= 0 ? r[n.b] : kAll;
    switch (n.op) {
      case Op::Const:
        r[i] = {n.value, n.value};
        break;
      case Op::Input:
      case Op::Texture:
        break;
      case Op::Add:
        r[i] = hull({a.lo + b.lo, a.hi + b.hi});
        break;
      case Op::Sub:
        r[i] = hull({a.lo - b.hi, a.hi - b.lo});
        break;
      case Op::Neg:
        r[i] = {-a.hi, -a.lo};
        break;
      case Op::Mul:
        if (n.a == n.b) {  // a square (x * x, as (u - c) * (u - c) traces): never negative
          const double l2 = a.lo * a.lo, h2 = a.hi * a.hi;
          r[i] = {a.lo <= 0 && a.hi >= 0 ? 0.0 : std::min(l2, h2), std::max(l2, h2)};
        } else {
          r[i] = hull({a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi});
        }
        break;
      case Op::Div:
        if (b.lo > 0 || b.hi < 0) r[i] = hull({a.lo / b.lo, a.lo / b.hi, a.hi / b.lo, a.hi / b.hi});
        break;
      case Op::Min:
        r[i] = {std::min(a.lo, b.lo), std::min(a.hi, b.hi)};
        break;
      case Op::Max:
        r[i] = {std::max(a.lo, b.lo), std::max(a.hi, b.hi)};
        break;
      case Op::Less:
        r[i] = {0, 1};
        break;
      case Op::Select: {  // condition n.a in {0, 1}: one of n.b, n.c
        const Interval c = r[n.c];
        r[i] = {std::min(b.lo, c.lo), std::max(b.hi, c.hi)};
        break;
      }
      case Op::Mod:
        r[i] = n.value > 0 ? Interval{0, n.value} : Interval{n.value, 0};
        break;
      case Op::Call:
        r[i] = call_range(n.atomic, a);
        break;
    }
  }
  return r;
}

}  // namespace bl::ir
