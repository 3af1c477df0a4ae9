#include "glsl/trace.hpp"

#include <glslang/Include/intermediate.h>
#include <glslang/MachineIndependent/localintermediate.h>
#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <unordered_map>

#include "dsl/math.hpp"
#include "glsl/prelude.hpp"
#include "ir/atomics.hpp"

namespace bl::glsl {
namespace {

using dsl::Var;
using glslang::TIntermAggregate;
using glslang::TIntermTyped;
using glslang::TOperator;

constexpr int kMaxLoopIterations = 4096;
constexpr int kMaxCallDepth = 64;

// glslang keeps process-wide tables: initialize once, never finalize (other threads may parse).
void init_glslang() {
  static std::once_flag once;
  std::call_once(once, [] { glslang::InitializeProcess(); });
}

// A value: its scalar components (a float, int or bool is one; vecN is N; arrays are flattened).
// Ints and bools are Vars too (bools are 0/1).
struct Value {
  std::vector<Var> c;
  int size() const { return static_cast<int>(c.size()); }
};

// Which components of which variable an assignment writes (swizzles and constant indices resolved).
struct LRef {
  long long id = 0;
  std::vector<int> comps;
  const TIntermTyped* node = nullptr;
  bool local = false;  // a function's temporary: lanes that returned never read it again
};

// Everything an if/else merges: variables, the function's "still running" mask and return value,
// and the innermost loop's break and continue masks.
struct State {
  std::unordered_map<long long, Value> vars;
  Var alive = Var(1.0), brk = Var(1.0), cont = Var(1.0);
  Value ret;
};

class Walker {
 public:
  Walker(ir::Graph& g, std::string file, std::map<std::string, TIntermAggregate*> functions,
         std::set<std::string> prelude_functions)
      : g_(g),
        file_(std::move(file)),
        functions_(std::move(functions)),
        prelude_functions_(std::move(prelude_functions)) {}

  const std::vector<std::string>& textures() const { return textures_; }

  // Global declarations with initializers (non-const globals), in order.
  void run_globals(TIntermAggregate* root) {
    for (TIntermNode* n : root->getSequence()) {
      TIntermAggregate* a = n->getAsAggregate();
      if (a && (a->getOp() == glslang::EOpFunction || a->getOp() == glslang::EOpLinkerObjects)) continue;
      exec(n);
    }
  }

  Value call_shade(TIntermAggregate* def, Var u, Var v, Var time) {
    std::vector<Value> args{Value{{u, v}}, Value{{time}}};
    return inline_call(def, args, {}, def);
  }

 private:
  // ---------- errors ----------
  [[noreturn]] void unsupported(const TIntermNode* n, const std::string& what) const {
    fail(n, "unsupported " + what);
  }
  [[noreturn]] void fail(const TIntermNode* n, const std::string& what) const {
    const glslang::TSourceLoc& loc = n->getLoc();
    throw Error(file_ + ":" + std::to_string(loc.line) + ":" + std::to_string(loc.column) + ": " + what);
  }

  // ---------- graph helpers (constants fold; trivial identities are skipped) ----------
  bool cval(Var v, double* x) const {
    const ir::Node& n = g_.node(v.id());
    if (n.op != ir::Op::Const) return false;
    if (x) *x = n.value;
    return true;
  }
  bool is(Var v, double k) const {
    double x;
    return cval(v, &x) && x == k;
  }
  Var add(Var a, Var b) {
    if (is(a, 0)) return b;
    if (is(b, 0)) return a;
    return a + b;
  }
  Var sub(Var a, Var b) { return is(b, 0) ? a : a - b; }
  Var mul(Var a, Var b) {
    if (is(a, 1)) return b;
    if (is(b, 1)) return a;
    // x * x is x^2, not a product of independent factors: the smoothing rules differ.
    if (a.id() == b.id() && !cval(a, nullptr)) return dsl::pow2(a);
    return a * b;
  }
  Var div(Var a, Var b) { return is(b, 1) ? a : a / b; }
  Var atomic(const char* name, Var x) { return dsl::call(name, x); }
  Var sel(Var c, Var a, Var b) {  // c is a 0/1 condition
    if (a.id() == b.id()) return a;
    double k;
    if (cval(c, &k)) return k != 0 ? a : b;
    if (is(a, 1) && is(b, 0)) return c;
    return dsl::select(c, a, b);
  }
  Var less(Var a, Var b) { return dsl::less(a, b); }
  Var lnot(Var a) { return sub(Var(1.0), a); }
  Var land(Var a, Var b) {
    if (is(a, 0) || is(b, 0)) return Var(0.0);
    return mul(a, b);
  }
  Var lor(Var a, Var b) {
    if (is(a, 1) || is(b, 1)) return Var(1.0);
    if (is(a, 0)) return b;
    if (is(b, 0)) return a;
    return dsl::max(a, b);
  }
  Var equal(Var a, Var b) {
    if (a.id() == b.id()) return Var(1.0);
    return mul(lnot(less(a, b)), lnot(less(b, a)));
  }
  Value select_value(Var c, const Value& a, const Value& b) {
    Value r;
    for (int i = 0; i < a.size(); ++i) r.c.push_back(sel(c, a.c[i], b.c[i]));
    return r;
  }

  // ---------- types ----------
  int components(const TIntermTyped* n) const { return components(n, n->getType()); }
  // A struct is its members one after another; an array its elements. (n names the culprit.)
  int components(const TIntermNode* n, const glslang::TType& t) const {
    if (t.getBasicType() == glslang::EbtVoid) return 0;
    if (t.getBasicType() == glslang::EbtSampler) unsupported(n, "use of a sampler as a value");
    if (t.getBasicType() == glslang::EbtDouble) unsupported(n, "double precision");
    int per = 0;
    if (t.isStruct()) {
      for (const glslang::TTypeLoc& m : *t.getStruct()) per += components(n, *m.type);
    } else {
      // A matrix is its columns one after another (column-major, as GLSL lays it out): m[i] is the
      // i-th run of `rows` components.
      per = t.isMatrix() ? t.getMatrixCols() * t.getMatrixRows()
                         : (t.getVectorSize() > 0 ? t.getVectorSize() : 1);
    }
    if (t.isArray()) {
      if (!t.isSizedArray()) unsupported(n, "unsized array");
      return t.getCumulativeArraySize() * per;
    }
    return per;
  }
  // Member `index` of the struct `b` indexes: its first component and its size.
  std::pair<int, int> member(glslang::TIntermBinary* b) {
    const int index = b->getRight()->getAsConstantUnion()->getConstArray()[0].getIConst();
    const glslang::TTypeList& members = *b->getLeft()->getType().getStruct();
    int offset = 0;
    for (int i = 0; i < index; ++i) offset += components(b, *members[i].type);
    return {offset, components(b, *members[index].type)};
  }
  bool is_integer(const TIntermTyped* n) const {
    const auto b = n->getType().getBasicType();
    return b == glslang::EbtInt || b == glslang::EbtUint;
  }
  Value zeros(int n) const { return Value{std::vector<Var>(n, Var(0.0))}; }

  // ---------- matrices ----------
  // Column-major: element (column j, row i) of an R-row matrix is component j * R + i.
  // The linear-algebra product of an ra x ca and an rb x cb matrix (ca == rb); a vector on the left
  // is a row (1 x n), on the right a column (n x 1).
  Value matmul(const TIntermNode* n, const Value& a, int ra, int ca, const Value& b, int rb, int cb) {
    if (ca != rb || a.size() != ra * ca || b.size() != rb * cb) fail(n, "matrix product of mismatched sizes");
    Value r;
    for (int c = 0; c < cb; ++c)
      for (int i = 0; i < ra; ++i) {
        Var sum = mul(a.c[i], b.c[c * rb]);
        for (int k = 1; k < ca; ++k) sum = add(sum, mul(a.c[k * ra + i], b.c[c * rb + k]));
        r.c.push_back(sum);
      }
    return r;
  }
  // matrix * vector, vector * matrix and matrix * matrix (also as *=), shapes from the operands' types.
  Value linear_product(glslang::TIntermBinary* b, TOperator op, const Value& x, const Value& y) {
    const glslang::TType &lt = b->getLeft()->getType(), &rt = b->getRight()->getType();
    const bool row_left = op == glslang::EOpVectorTimesMatrix,
               column_right = op == glslang::EOpMatrixTimesVector;
    const int ra = row_left ? 1 : lt.getMatrixRows(), ca = row_left ? x.size() : lt.getMatrixCols();
    const int rb = column_right ? y.size() : rt.getMatrixRows(), cb = column_right ? 1 : rt.getMatrixCols();
    return matmul(b, x, ra, ca, y, rb, cb);
  }
  // The determinant of an n x n matrix by cofactor expansion along row 0 (n <= 4 in GLSL).
  Var det_of(const std::vector<Var>& m, int n) {
    if (n == 1) return m[0];
    Var d(0.0);
    for (int j = 0; j < n; ++j) {
      const Var t = mul(m[j * n], det_of(minor_of(m, n, 0, j), n - 1));
      d = j % 2 ? sub(d, t) : add(d, t);
    }
    return d;
  }
  // m without row `row` and column `col`.
  static std::vector<Var> minor_of(const std::vector<Var>& m, int n, int row, int col) {
    std::vector<Var> r;
    for (int c = 0; c < n; ++c)
      for (int i = 0; i < n && c != col; ++i)
        if (i != row) r.push_back(m[c * n + i]);
    return r;
  }
  // inverse(m) = adjugate / determinant: element (c, r) is the (r, c) cofactor over det. A singular
  // matrix gives inf/NaN, as GLSL leaves it undefined.
  Value inverse_of(const std::vector<Var>& m, int n) {
    const Var det = det_of(m, n);
    Value r;
    for (int c = 0; c < n; ++c)
      for (int i = 0; i < n; ++i) {
        const Var cof = n == 1 ? Var(1.0) : det_of(minor_of(m, n, c, i), n - 1);
        r.c.push_back(div((c + i) % 2 ? -cof : cof, det));
      }
    return r;
  }

  // ---------- masks ----------
  Var active() { return land(land(st_.alive, st_.brk), st_.cont); }
  bool dead() { return is(st_.alive, 0) || is(st_.brk, 0) || is(st_.cont, 0); }

  // ---------- variables ----------
  Value& var(const glslang::TIntermSymbol* s) {
    auto it = st_.vars.find(s->getId());
    if (it != st_.vars.end()) return it->second;
    const auto q = s->getQualifier().storage;
    if (s->getType().getBasicType() == glslang::EbtSampler)
      unsupported(s, "use of sampler '" + std::string(s->getName().c_str()) + "' outside texture(" +
                         std::string(s->getName().c_str()) + ", uv)");
    if (q == glslang::EvqUniform || q == glslang::EvqBuffer)
      unsupported(s, "uniform '" + std::string(s->getName().c_str()) +
                         "' (pass values through shade's parameters or constants)");
    if (q == glslang::EvqVaryingIn || q == glslang::EvqVaryingOut || q == glslang::EvqFragCoord ||
        std::string(s->getName().c_str()).rfind("gl_", 0) == 0)
      unsupported(s, "built-in or stage variable '" + std::string(s->getName().c_str()) + "'");
    // A declared but never assigned variable: GLSL leaves it undefined; we read 0.
    return st_.vars[s->getId()] = zeros(components(s));
  }

  // An out or inout argument: the one reference it names (no traced index on the way).
  LRef lvalue(TIntermTyped* n) {
    TIntermTyped* traced = nullptr;
    std::vector<Target> t = targets(n, &traced);
    if (traced) unsupported(traced, "traced index in an out or inout argument (copy the element to a local)");
    return t.front().ref;
  }
  // The swizzle or struct member b selects from `base`, the whole of what b's left side names.
  LRef part_ref(glslang::TIntermBinary* b, const LRef& base) {
    if (b->getOp() == glslang::EOpVectorSwizzle) {
      LRef r{base.id, {}, b, base.local};
      for (TIntermNode* k : b->getRight()->getAsAggregate()->getSequence())
        r.comps.push_back(base.comps.at(k->getAsConstantUnion()->getConstArray()[0].getIConst()));
      return r;
    }
    const auto [offset, size] = member(b);
    return LRef{base.id, std::vector<int>(base.comps.begin() + offset, base.comps.begin() + offset + size), b,
                base.local};
  }
  // What an assignment writes: one reference, or with a traced index on the way (a[i].x, m[i][j],
  // s.items[i].w) one per element it may name, each written where the index equals it. *traced,
  // when asked for, is set to the first traced index met.
  struct Target {
    Var mask;
    LRef ref;
  };
  std::vector<Target> targets(TIntermTyped* n, TIntermTyped** traced = nullptr) {
    if (auto* s = n->getAsSymbolNode()) {
      LRef r;
      r.id = s->getId();
      r.node = n;
      r.local = s->getQualifier().storage == glslang::EvqTemporary;
      const int k = var(s).size();
      for (int i = 0; i < k; ++i) r.comps.push_back(i);
      return {Target{Var(1.0), r}};
    }
    auto* b = n->getAsBinaryNode();
    const TOperator op = b ? b->getOp() : glslang::EOpNull;
    if (op == glslang::EOpIndexDirect || op == glslang::EOpIndexIndirect) {
      std::vector<Target> base = targets(b->getLeft(), traced);
      Var i;
      const bool fixed = constant_scalar(b->getRight(), &i);
      if (!fixed && traced && !*traced) *traced = b->getRight();
      std::vector<Target> out;
      for (const Target& t : base) {
        if (fixed) {
          out.push_back({t.mask, element_ref(b, t.ref, i)});
          continue;
        }
        const int count = static_cast<int>(t.ref.comps.size()) / components(b);
        for (int k = 0; k < count; ++k) {
          const Var kk(static_cast<double>(k));
          out.push_back({land(t.mask, equal(i, kk)), element_ref(b, t.ref, kk)});
        }
      }
      return out;
    }
    if (op == glslang::EOpVectorSwizzle || op == glslang::EOpIndexDirectStruct) {
      std::vector<Target> out = targets(b->getLeft(), traced);
      for (Target& t : out) t.ref = part_ref(b, t.ref);
      return out;
    }
    unsupported(n, "assignment target");
  }
  // Element i (a constant) of `base`, the whole of what `b` indexes.
  LRef element_ref(glslang::TIntermBinary* b, const LRef& base, Var i) {
    double k = 0;
    cval(i, &k);
    const int idx = static_cast<int>(k), es = components(b);
    if (idx < 0 || (idx + 1) * es > static_cast<int>(base.comps.size())) fail(b, "index out of range");
    LRef r{base.id, {}, b, base.local};
    for (int j = 0; j < es; ++j) r.comps.push_back(base.comps[idx * es + j]);
    return r;
  }
  Value read(const LRef& r) {
    const Value& v = st_.vars.at(r.id);
    Value out;
    for (int i : r.comps) out.c.push_back(v.c[i]);
    return out;
  }
  // Writes under the active mask (select against the old value where some lanes are inactive).
  // A local is not masked by an earlier return (so a while loop's counter stays constant after a
  // conditional return); globals and parameters are, since the caller reads them.
  // A local declared inside the innermost loop (after its start: its counter's `int j = 0` in an
  // outer loop's body, a temporary of the body) is written unmasked: no lane reads it once the
  // loop ends, and lanes that broke or continued no longer read it in this iteration either
  // (everything they could reach is written under the masks). So an inner loop's counter stays
  // a constant after a traced break of the outer loop, and the inner loop unrolls.
  void write(const LRef& r, const Value& x) {
    if (dead()) return;
    const bool fresh = r.local && !loop_vars_.empty() && !loop_vars_.back().count(r.id);
    const Var m = fresh ? Var(1.0) : r.local ? land(st_.brk, st_.cont) : active();
    Value& v = st_.vars.at(r.id);
    for (std::size_t i = 0; i < r.comps.size(); ++i) v.c[r.comps[i]] = sel(m, x.c[i], v.c[r.comps[i]]);
  }

  // ---------- statements ----------
  void exec(TIntermNode* n) {
    if (!n || dead()) return;
    if (auto* a = n->getAsAggregate()) {
      if (a->getOp() == glslang::EOpSequence) {
        for (TIntermNode* s : a->getSequence()) {
          if (dead()) return;
          exec(s);
        }
        return;
      }
    }
    if (auto* s = n->getAsSelectionNode()) {
      if (s->getBasicType() == glslang::EbtVoid) {
        branch(
            s->getCondition(), [&] { exec(s->getTrueBlock()); }, [&] { exec(s->getFalseBlock()); });
        return;
      }
    }
    if (auto* l = n->getAsLoopNode()) return loop(l);
    if (auto* b = n->getAsBranchNode()) return jump(b);
    if (auto* sw = n->getAsSwitchNode()) return switch_statement(sw);
    if (auto* t = n->getAsTyped()) {
      eval(t);
      return;
    }
    unsupported(n, "statement");
  }

  // if/else (and ?:): a constant condition runs one side; otherwise both sides run on copies of the
  // state and every variable and mask they change merges with select.
  void branch(TIntermTyped* cond, const std::function<void()>& yes, const std::function<void()>& no) {
    branch_on(scalar(cond), yes, no);
  }
  void branch_on(Var c, const std::function<void()>& yes, const std::function<void()>& no) {
    double k;
    if (cval(c, &k)) {
      (k != 0 ? yes : no)();
      return;
    }
    const State before = st_;
    yes();
    State t = std::move(st_);
    st_ = before;
    no();
    State& e = st_;
    // A variable only one side has is local to it (or first assigned there: undefined elsewhere).
    for (auto& [id, ev] : e.vars) {
      auto it = t.vars.find(id);
      if (it != t.vars.end()) ev = select_value(c, it->second, ev);
    }
    e.alive = sel(c, t.alive, e.alive);
    e.brk = sel(c, t.brk, e.brk);
    e.cont = sel(c, t.cont, e.cont);
    e.ret = select_value(c, t.ret, e.ret);
    for (auto& [id, tv] : t.vars)
      if (!e.vars.count(id)) e.vars[id] = tv;
  }

  template <class F>
  auto with_masks_off(F f) {
    const Var a = st_.alive, b = st_.brk, c = st_.cont;
    st_.alive = st_.brk = st_.cont = Var(1.0);
    auto r = f();
    st_.alive = a;
    st_.brk = b;
    st_.cont = c;
    return r;
  }

  void loop(glslang::TIntermLoop* l) {
    const Var saved_brk = st_.brk, saved_cont = st_.cont;
    // Lanes that broke out of (or continued) an enclosing loop do not run this one.
    st_.brk = land(saved_brk, saved_cont);
    std::set<int> existing;
    for (const auto& [id, v] : st_.vars) existing.insert(id);
    loop_vars_.push_back(std::move(existing));
    auto test = [&]() -> bool {
      if (!l->getTest()) return true;
      const Var c = with_masks_off([&] { return scalar(l->getTest()); });
      double k;
      if (!cval(c, &k))
        unsupported(l->getTest(),
                    "loop with a variable bound (the condition must be constant at every iteration)");
      return k != 0;
    };
    int it = 0;
    for (;; ++it) {
      if (it >= kMaxLoopIterations)
        fail(l, "loop runs more than " + std::to_string(kMaxLoopIterations) + " iterations (unrolled)");
      if (l->testFirst() && !test()) break;
      st_.cont = Var(1.0);
      exec(l->getBody());
      st_.cont = Var(1.0);
      if (is(st_.brk, 0) || is(st_.alive, 0)) break;
      // The counter update runs for every lane: lanes that broke or returned no longer read it.
      if (l->getTerminal()) with_masks_off([&] { return eval(l->getTerminal()); });
      if (!l->testFirst() && !test()) break;
    }
    st_.brk = saved_brk;
    st_.cont = saved_cont;
    loop_vars_.pop_back();
  }
  // switch: the body's statements in order, each under "some label at or above it matched" (a
  // case's value equal to the selector, or default when none is), so control falls through until a
  // break, which ends the switch for the lanes that take it (the loop's break mask, saved around it).
  // A constant selector runs only the matching path.
  void switch_statement(glslang::TIntermSwitch* sw) {
    const Var c = scalar(sw->getCondition()->getAsTyped());
    const glslang::TIntermSequence& body = sw->getBody()->getSequence();
    auto label = [](TIntermNode* s) -> glslang::TIntermBranch* {
      auto* b = s->getAsBranchNode();
      return b && (b->getFlowOp() == glslang::EOpCase || b->getFlowOp() == glslang::EOpDefault) ? b : nullptr;
    };
    Var none(1.0);  // no case value equals the selector: default's condition
    for (TIntermNode* s : body)
      if (auto* b = label(s); b && b->getFlowOp() == glslang::EOpCase)
        none = land(none, lnot(equal(c, scalar(b->getExpression()))));
    const Var saved_brk = st_.brk;  // a break ends the switch only: restored after it
    Var entered(0.0);
    for (TIntermNode* s : body) {
      if (dead()) break;
      if (auto* b = label(s)) {
        entered =
            lor(entered, b->getFlowOp() == glslang::EOpCase ? equal(c, scalar(b->getExpression())) : none);
        continue;
      }
      branch_on(
          entered, [&] { exec(s); }, [] {});
    }
    st_.brk = saved_brk;
  }

  void jump(glslang::TIntermBranch* b) {
    switch (b->getFlowOp()) {
      case glslang::EOpReturn: {
        if (b->getExpression()) {
          const Value v = eval(b->getExpression());
          st_.ret = select_value(active(), v, st_.ret);
        }
        st_.alive = land(st_.alive, lnot(land(st_.brk, st_.cont)));
        return;
      }
      case glslang::EOpBreak:
        st_.brk = land(st_.brk, lnot(st_.cont));
        return;
      case glslang::EOpContinue:
        st_.cont = Var(0.0);
        return;
      case glslang::EOpKill:
        unsupported(b, "discard");
      default:
        unsupported(b, "jump statement");
    }
  }

  // ---------- expressions ----------
  Var scalar(TIntermTyped* n) {
    const Value v = eval(n);
    if (v.size() != 1) fail(n, "expected a scalar");
    return v.c[0];
  }

  Value eval(TIntermTyped* n) {
    if (auto* k = n->getAsConstantUnion()) return constant(k);
    if (auto* s = n->getAsSymbolNode()) return var(s);
    if (auto* b = n->getAsBinaryNode()) return binary(b);
    if (auto* u = n->getAsUnaryNode()) return unary(u);
    if (auto* a = n->getAsAggregate()) return aggregate(a);
    if (auto* s = n->getAsSelectionNode()) {
      // cond ? a : b on values: both sides traced, merged with select.
      const Var c = scalar(s->getCondition());
      Value ra, rb;
      branch_on(
          c, [&] { ra = eval(s->getTrueBlock()->getAsTyped()); },
          [&] { rb = eval(s->getFalseBlock()->getAsTyped()); });
      double k;
      if (cval(c, &k)) return k != 0 ? ra : rb;
      return select_value(c, ra, rb);
    }
    unsupported(n, "expression");
  }

  Value constant(glslang::TIntermConstantUnion* k) {
    const glslang::TConstUnionArray& a = k->getConstArray();
    Value v;
    for (int i = 0; i < a.size(); ++i) {
      const glslang::TConstUnion& c = a[i];
      switch (c.getType()) {
        case glslang::EbtFloat:
        case glslang::EbtDouble:
          v.c.push_back(Var(c.getDConst()));
          break;
        case glslang::EbtInt:
          v.c.push_back(Var(static_cast<double>(c.getIConst())));
          break;
        case glslang::EbtUint:
          v.c.push_back(Var(static_cast<double>(c.getUConst())));
          break;
        case glslang::EbtBool:
          v.c.push_back(Var(c.getBConst() ? 1.0 : 0.0));
          break;
        default:
          unsupported(k, "constant type");
      }
    }
    const int n = components(k);
    if (v.size() == 1 && n > 1) v.c.assign(n, v.c[0]);
    return v;
  }

  // Component-wise f over operands, scalars broadcast.
  Value zip(const std::vector<Value>& xs, const std::function<Var(const std::vector<Var>&)>& f) {
    int n = 1;
    for (const auto& x : xs) n = std::max(n, x.size());
    Value r;
    std::vector<Var> args(xs.size());
    for (int i = 0; i < n; ++i) {
      for (std::size_t k = 0; k < xs.size(); ++k) args[k] = xs[k].size() == 1 ? xs[k].c[0] : xs[k].c.at(i);
      r.c.push_back(f(args));
    }
    return r;
  }

  // Integer operations: constants fold; on traced values only those exact in float are allowed.
  Value int_binary(glslang::TIntermBinary* b, TOperator op, const Value& x, const Value& y) {
    return zip({x, y}, [&](const std::vector<Var>& a) -> Var {
      double p, q;
      if (cval(a[0], &p) && cval(a[1], &q)) {
        const long long i = static_cast<long long>(p), j = static_cast<long long>(q);
        switch (op) {
          case glslang::EOpDiv:
            if (j == 0) fail(b, "integer division by zero");
            return Var(static_cast<double>(i / j));
          case glslang::EOpMod:
            if (j == 0) fail(b, "integer modulo by zero");
            return Var(static_cast<double>(i % j));
          case glslang::EOpAnd:
            return Var(static_cast<double>(i & j));
          case glslang::EOpInclusiveOr:
            return Var(static_cast<double>(i | j));
          case glslang::EOpExclusiveOr:
            return Var(static_cast<double>(i ^ j));
          case glslang::EOpLeftShift:
            return Var(static_cast<double>(i << j));
          case glslang::EOpRightShift:
            return Var(static_cast<double>(i >> j));
          default:
            break;
        }
      }
      switch (op) {
        case glslang::EOpDiv:
          unsupported(b, "integer division of non-constant values");
        case glslang::EOpMod:
          unsupported(b, "integer modulo (%) of non-constant values");
        default:
          unsupported(b, "integer bit operation on non-constant values");
      }
    });
  }

  Value arith(glslang::TIntermBinary* b, TOperator op, const Value& x, const Value& y, bool integer) {
    switch (op) {
      case glslang::EOpAdd:
        return zip({x, y}, [&](const std::vector<Var>& a) { return add(a[0], a[1]); });
      case glslang::EOpSub:
        return zip({x, y}, [&](const std::vector<Var>& a) { return sub(a[0], a[1]); });
      case glslang::EOpMul:
      case glslang::EOpVectorTimesScalar:
      case glslang::EOpMatrixTimesScalar:
        return zip({x, y}, [&](const std::vector<Var>& a) { return mul(a[0], a[1]); });
      case glslang::EOpVectorTimesMatrix:
      case glslang::EOpMatrixTimesVector:
      case glslang::EOpMatrixTimesMatrix:
        return linear_product(b, op, x, y);
      case glslang::EOpDiv:
        if (integer) return int_binary(b, op, x, y);
        return zip({x, y}, [&](const std::vector<Var>& a) { return div(a[0], a[1]); });
      case glslang::EOpMod:
      case glslang::EOpAnd:
      case glslang::EOpInclusiveOr:
      case glslang::EOpExclusiveOr:
      case glslang::EOpLeftShift:
      case glslang::EOpRightShift:
        return int_binary(b, op, x, y);
      default:
        unsupported(b, "operator");
    }
  }

  static TOperator compound_base(TOperator op) {
    switch (op) {
      case glslang::EOpAddAssign:
        return glslang::EOpAdd;
      case glslang::EOpSubAssign:
        return glslang::EOpSub;
      case glslang::EOpMulAssign:
      case glslang::EOpVectorTimesScalarAssign:
      case glslang::EOpMatrixTimesScalarAssign:
        return glslang::EOpMul;
      case glslang::EOpVectorTimesMatrixAssign:
        return glslang::EOpVectorTimesMatrix;
      case glslang::EOpMatrixTimesMatrixAssign:
        return glslang::EOpMatrixTimesMatrix;
      case glslang::EOpDivAssign:
        return glslang::EOpDiv;
      case glslang::EOpModAssign:
        return glslang::EOpMod;
      case glslang::EOpAndAssign:
        return glslang::EOpAnd;
      case glslang::EOpInclusiveOrAssign:
        return glslang::EOpInclusiveOr;
      case glslang::EOpExclusiveOrAssign:
        return glslang::EOpExclusiveOr;
      case glslang::EOpLeftShiftAssign:
        return glslang::EOpLeftShift;
      case glslang::EOpRightShiftAssign:
        return glslang::EOpRightShift;
      default:
        return glslang::EOpNull;
    }
  }

  // An index that is not a constant: the element as a sum of steps of the index, element 0 plus, for
  // each k >= 1, step(i - (k - 1/2)) (element k - element k-1). Indices are whole numbers, so at a
  // pixel it picks element i; smoothed, each step is the probability that i >= k, and the mean is
  // the exact mixture of the elements (a chain of selects would treat the steps as independent). An
  // index outside the array reads the nearest end (GLSL leaves it undefined).
  Value dynamic_element(const Value& base, Var i, int es) {
    const int n = base.size() / es;
    Value r{std::vector<Var>(base.c.begin(), base.c.begin() + es)};
    for (int k = 1; k < n; ++k) {
      const Var s = atomic("step", sub(i, Var(k - 0.5)));
      for (int j = 0; j < es; ++j)
        r.c[j] = add(r.c[j], mul(s, sub(base.c[k * es + j], base.c[(k - 1) * es + j])));
    }
    return r;
  }
  bool constant_scalar(TIntermTyped* n, Var* v) {
    const Value x = eval(n);
    if (x.size() != 1) fail(n, "expected a scalar index");
    *v = x.c[0];
    return cval(*v, nullptr);
  }
  Value binary(glslang::TIntermBinary* b) {
    const TOperator op = b->getOp();
    if (op == glslang::EOpAssign || compound_base(op) != glslang::EOpNull) {
      const TOperator base_op = op == glslang::EOpAssign ? glslang::EOpNull : compound_base(op);
      const Value y = eval(b->getRight());
      // With a traced index on the way every element it may name takes the new value where the
      // index names it (a[i] = y, a[i].x += y).
      Value v = y;
      for (const Target& t : targets(b->getLeft())) {
        const Value old = read(t.ref);
        v = base_op == glslang::EOpNull ? y : arith(b, base_op, old, y, is_integer(b->getLeft()));
        if (static_cast<int>(t.ref.comps.size()) != v.size()) fail(b, "assignment of mismatched sizes");
        write(t.ref, select_value(t.mask, v, old));
      }
      return v;
    }
    switch (op) {
      case glslang::EOpIndexDirect:
      case glslang::EOpIndexIndirect: {
        const Value base = eval(b->getLeft());
        const int es = components(b);
        Var i;
        if (!constant_scalar(b->getRight(), &i)) return dynamic_element(base, i, es);
        double k = 0;
        cval(i, &k);
        const int idx = static_cast<int>(k);
        if (idx < 0 || (idx + 1) * es > base.size()) fail(b, "index out of range");
        return Value{std::vector<Var>(base.c.begin() + idx * es, base.c.begin() + (idx + 1) * es)};
      }
      case glslang::EOpVectorSwizzle: {
        const Value base = eval(b->getLeft());
        Value r;
        for (TIntermNode* k : b->getRight()->getAsAggregate()->getSequence())
          r.c.push_back(base.c.at(k->getAsConstantUnion()->getConstArray()[0].getIConst()));
        return r;
      }
      case glslang::EOpIndexDirectStruct: {
        const Value base = eval(b->getLeft());
        const auto [offset, size] = member(b);
        return Value{std::vector<Var>(base.c.begin() + offset, base.c.begin() + offset + size)};
      }
      case glslang::EOpComma:
        eval(b->getLeft());
        return eval(b->getRight());
      case glslang::EOpLogicalAnd: {
        const Var x = scalar(b->getLeft());
        if (is(x, 0)) return Value{{Var(0.0)}};
        return Value{{land(x, scalar(b->getRight()))}};
      }
      case glslang::EOpLogicalOr: {
        const Var x = scalar(b->getLeft());
        if (is(x, 1)) return Value{{Var(1.0)}};
        return Value{{lor(x, scalar(b->getRight()))}};
      }
      case glslang::EOpLogicalXor: {
        const Var x = scalar(b->getLeft()), y = scalar(b->getRight());
        return Value{{sub(add(x, y), mul(Var(2.0), mul(x, y)))}};
      }
      default:
        break;
    }
    const Value x = eval(b->getLeft()), y = eval(b->getRight());
    switch (op) {
      case glslang::EOpLessThan:
        return Value{{less(x.c[0], y.c[0])}};
      case glslang::EOpGreaterThan:
        return Value{{less(y.c[0], x.c[0])}};
      case glslang::EOpLessThanEqual:
        return Value{{lnot(less(y.c[0], x.c[0]))}};
      case glslang::EOpGreaterThanEqual:
        return Value{{lnot(less(x.c[0], y.c[0]))}};
      case glslang::EOpEqual:
      case glslang::EOpNotEqual: {
        Var all(1.0);
        for (int i = 0; i < x.size(); ++i) all = land(all, equal(x.c[i], y.c[i]));
        return Value{{op == glslang::EOpEqual ? all : lnot(all)}};
      }
      default:
        return arith(b, op, x, y, is_integer(b));
    }
  }

  // Float -> int (and int -> float, bool <-> number) conversions; ints are carried as whole floats.
  // int(x) of a traced float is trunc(x) (exact); integer arithmetic on it is limited above. A value
  // that is already a whole number (a floor, a step, sums and products of them) converts to itself:
  // int(floor(y)) is floor(y), one jump rather than a trunc smoothed on top of a smoothed floor.
  Var to_int(Var x) {
    double k;
    if (cval(x, &k)) return Var(std::trunc(k));
    if (whole(x.id(), 0)) return x;
    return atomic("trunc", x);
  }
  // True when node `id` takes only whole-number values (depth bounds the walk on long sums).
  bool whole(int id, int depth) const {
    if (depth > 32) return false;
    const ir::Node& n = g_.node(id);
    switch (n.op) {
      case ir::Op::Const:
        return n.value == std::floor(n.value);
      case ir::Op::Less:
        return true;
      case ir::Op::Add:
      case ir::Op::Sub:
      case ir::Op::Mul:
      case ir::Op::Min:
      case ir::Op::Max:
        return whole(n.a, depth + 1) && whole(n.b, depth + 1);
      case ir::Op::Neg:
        return whole(n.a, depth + 1);
      case ir::Op::Mod:
        return n.value == std::floor(n.value) && whole(n.a, depth + 1);
      case ir::Op::Select:
        return whole(n.a, depth + 1) && whole(n.b, depth + 1);
      case ir::Op::Call: {
        static const int staircases[] = {ir::atomic_index("floor"), ir::atomic_index("ceil"),
                                         ir::atomic_index("trunc"), ir::atomic_index("step"),
                                         ir::atomic_index("sign"),  ir::atomic_index("square")};
        for (int a : staircases)
          if (n.atomic == a) return true;
        return false;
      }
      default:
        return false;
    }
  }
  Var to_bool(Var x) { return lnot(equal(x, Var(0.0))); }

  Value unary(glslang::TIntermUnary* u) {
    const TOperator op = u->getOp();
    TIntermTyped* arg = u->getOperand();
    switch (op) {
      case glslang::EOpPostIncrement:
      case glslang::EOpPostDecrement:
      case glslang::EOpPreIncrement:
      case glslang::EOpPreDecrement: {
        const double d = op == glslang::EOpPostIncrement || op == glslang::EOpPreIncrement ? 1 : -1;
        Value old, now;
        for (const Target& t : targets(arg)) {
          old = read(t.ref);
          now = zip({old}, [&](const std::vector<Var>& a) { return add(a[0], Var(d)); });
          write(t.ref, select_value(t.mask, now, old));
        }
        return op == glslang::EOpPostIncrement || op == glslang::EOpPostDecrement ? old : now;
      }
      default:
        break;
    }
    const Value x = eval(arg);
    if (op >= glslang::EOpConvInt8ToBool && op <= glslang::EOpConvDoubleToFloat) {
      const auto to = u->getBasicType();
      const auto from = arg->getBasicType();
      if (to == glslang::EbtBool) return zip({x}, [&](const std::vector<Var>& a) { return to_bool(a[0]); });
      if ((to == glslang::EbtInt || to == glslang::EbtUint) && from == glslang::EbtFloat)
        return zip({x}, [&](const std::vector<Var>& a) { return to_int(a[0]); });
      if (to == glslang::EbtUint && from == glslang::EbtInt) {
        for (Var v : x.c) {
          double k;
          if (!cval(v, &k)) unsupported(u, "int to uint conversion of a non-constant value");
        }
      }
      return x;  // int/bool -> float, int <-> uint: the same whole number
    }
    switch (op) {
      case glslang::EOpNegative:
        return zip({x}, [&](const std::vector<Var>& a) { return -a[0]; });
      case glslang::EOpLogicalNot:
        return zip({x}, [&](const std::vector<Var>& a) { return lnot(a[0]); });
      case glslang::EOpBitwiseNot:
        unsupported(u, "bitwise not");
      default:
        return builtin(u, op, {x});
    }
  }

  Value aggregate(TIntermAggregate* a) {
    const TOperator op = a->getOp();
    if (op == glslang::EOpFunctionCall) return call(a);
    if (op == glslang::EOpSequence) {
      Value last;
      for (TIntermNode* s : a->getSequence()) {
        if (auto* t = s->getAsTyped())
          last = eval(t);
        else
          exec(s);
      }
      return last;
    }
    if (op == glslang::EOpTexture) return texture(a);
    std::vector<Value> args;
    if (op > glslang::EOpConstructGuardStart && op < glslang::EOpConstructGuardEnd) {
      for (TIntermNode* s : a->getSequence()) args.push_back(eval(s->getAsTyped()));
      return construct(a, args);
    }
    for (TIntermNode* s : a->getSequence()) args.push_back(eval(s->getAsTyped()));
    return builtin(a, op, args);
  }

  Value construct(TIntermAggregate* a, const std::vector<Value>& args) {
    const int n = components(a);
    const glslang::TType& type = a->getType();
    if (type.isMatrix() && !type.isArray() && args.size() == 1) {
      // matN(s): s on the diagonal; matN(m): m's overlapping part, the identity elsewhere.
      const glslang::TType& from = a->getSequence()[0]->getAsTyped()->getType();
      const int cols = type.getMatrixCols(), rows = type.getMatrixRows();
      const int fc = from.isMatrix() ? from.getMatrixCols() : 0,
                fr = from.isMatrix() ? from.getMatrixRows() : 0;
      if (from.isMatrix() || args[0].size() == 1) {
        Value r;
        for (int c = 0; c < cols; ++c)
          for (int i = 0; i < rows; ++i)
            r.c.push_back(c < fc && i < fr ? args[0].c[c * fr + i]
                          : c == i         ? (fc ? Var(1.0) : args[0].c[0])
                                           : Var(0.0));
        return r;
      }
    }
    const auto to = a->getBasicType();
    Value flat;
    for (std::size_t i = 0; i < args.size(); ++i) {
      const auto from = a->getSequence()[i]->getAsTyped()->getBasicType();
      for (Var v : args[i].c) {
        if (to == glslang::EbtBool && from != glslang::EbtBool)
          v = to_bool(v);
        else if ((to == glslang::EbtInt || to == glslang::EbtUint) && from == glslang::EbtFloat)
          v = to_int(v);
        flat.c.push_back(v);
      }
    }
    if (flat.size() == 1 && n > 1 && !a->getType().isArray() && !a->getType().isStruct())
      flat.c.assign(n, flat.c[0]);
    if (flat.size() < n) fail(a, "constructor has too few components");
    flat.c.resize(n);
    return flat;
  }

  Value texture(TIntermAggregate* a) {
    const auto& seq = a->getSequence();
    auto* s = seq[0]->getAsSymbolNode();
    if (!s || seq.size() != 2) unsupported(a, "texture() form (use texture(sampler2D slot, vec2 uv))");
    const glslang::TSampler& sm = s->getType().getSampler();
    if (sm.dim != glslang::Esd2D || sm.isShadow() || sm.isArrayed() || sm.getBasicType() != glslang::EbtFloat)
      unsupported(a, "texture lookup other than a float sampler2D slot");
    if (s->getQualifier().storage != glslang::EvqUniform)
      unsupported(a, "texture lookup of a non-uniform sampler");
    const std::string slot = s->getName().c_str();
    const Value uv = eval(seq[1]->getAsTyped());
    bool known = false;
    for (const auto& t : textures_) known = known || t == slot;
    if (!known) textures_.push_back(slot);
    Value r;
    for (int c = 0; c < 3; ++c) r.c.push_back(Var::node(g_.texture(slot, c, uv.c[0].id(), uv.c[1].id())));
    r.c.push_back(Var(1.0));  // slots are RGB: alpha reads 1
    return r;
  }

  // ---------- built-in functions ----------
  Var pow_int(Var x, long long n) {
    if (n == 0) return Var(1.0);
    if (n < 0) {
      if (n == -1) return atomic("inv", x);
      if (n == -2) return atomic("inv2", x);
      return atomic("inv", pow_int(x, -n));
    }
    if (n == 1) return x;
    if (n <= 8) return atomic(("pow" + std::to_string(n)).c_str(), x);
    return mul(atomic("pow8", x), pow_int(x, n - 8));
  }
  Var pow_var(Var x, Var y) {
    double k;
    if (cval(y, &k)) {
      if (k == std::floor(k) && std::fabs(k) <= 64) return pow_int(x, static_cast<long long>(k));
      if (k == 0.5) return atomic("sqrt", x);
      if (k == -0.5) return atomic("inv", atomic("sqrt", x));
    }
    return atomic("exp", mul(y, atomic("log", x)));  // GLSL pow is undefined for x < 0 anyway
  }
  Var mod_var(Var a, Var b) {
    double k;
    if (cval(b, &k)) {
      if (k == 0) return sub(a, mul(b, atomic("floor", div(a, b))));
      return dsl::mod(a, k);
    }
    return sub(a, mul(b, atomic("floor", div(a, b))));  // a - b floor(a / b), as GLSL defines it
  }
  Var clamp_var(Var x, Var lo, Var hi) {
    double l, h;
    if (cval(lo, &l) && cval(hi, &h) && h > l) {
      if (l == 0 && h == 1) return atomic("saturate", x);
      return add(lo, mul(Var(h - l), atomic("saturate", div(sub(x, lo), Var(h - l)))));
    }
    return dsl::min(dsl::max(x, lo), hi);
  }
  Var smooth(Var e0, Var e1, Var x) {
    return atomic("smoothstep", div(sub(x, e0), sub(e1, e0)));  // the edges may be traced values too
  }
  // GLSL's atan(y, x) in [-pi, pi] through the atan atomic of a ratio in [0, 1], the way libm
  // computes it: t = atan(min(|x|, |y|) / max(|x|, |y|)), reflected into the octant of (x, y). Every
  // reflection meets its neighbour continuously (at |x| = |y|, x = 0, y = 0 with x > 0), so the
  // selects blend equal values there; the only jump is GLSL's own, on the negative x axis.
  Var atan2_of(Var y, Var x) {
    const Var ax = atomic("abs", x), ay = atomic("abs", y);
    Var t = atomic("atan", div(dsl::min(ax, ay), dsl::max(ax, ay)));
    t = sel(less(ax, ay), sub(Var(M_PI / 2), t), t);
    t = sel(less(x, Var(0.0)), sub(Var(M_PI), t), t);
    return sel(less(y, Var(0.0)), -t, t);
  }
  Var dot_of(const Value& a, const Value& b) {
    Var s(0.0);
    for (int i = 0; i < a.size(); ++i) s = add(s, mul(a.c[i], b.c[i]));
    return s;
  }
  Var length_of(const Value& a) {
    if (a.size() == 1) return atomic("abs", a.c[0]);
    return atomic("sqrt", dot_of(a, a));
  }

  Value builtin(TIntermTyped* n, TOperator op, const std::vector<Value>& x) {
    auto each = [&](const char* name) {
      return zip({x[0]}, [&](const std::vector<Var>& a) { return atomic(name, a[0]); });
    };
    switch (op) {
      case glslang::EOpSin:
        return each("sin");
      case glslang::EOpCos:
        return each("cos");
      case glslang::EOpTan:
        return each("tan");
      case glslang::EOpSinh:
        return each("sinh");
      case glslang::EOpCosh:
        return each("cosh");
      case glslang::EOpTanh:
        return each("tanh");
      case glslang::EOpExp:
        return each("exp");
      case glslang::EOpLog:
        return each("log");
      case glslang::EOpSqrt:
        return each("sqrt");
      case glslang::EOpAbs:
        return each("abs");
      case glslang::EOpSign:
        return each("sign");
      case glslang::EOpFloor:
        return each("floor");
      case glslang::EOpCeil:
        return each("ceil");
      case glslang::EOpFract:
        return each("fract");
      case glslang::EOpTrunc:
        return each("trunc");
      case glslang::EOpRound:
      case glslang::EOpRoundEven:  // halves differ from roundEven only on a measure-zero set
        return zip({x[0]}, [&](const std::vector<Var>& a) { return atomic("floor", add(a[0], Var(0.5))); });
      case glslang::EOpExp2:
        return zip({x[0]}, [&](const std::vector<Var>& a) { return atomic("exp", mul(a[0], Var(M_LN2))); });
      case glslang::EOpLog2:
        return zip({x[0]},
                   [&](const std::vector<Var>& a) { return mul(atomic("log", a[0]), Var(1 / M_LN2)); });
      case glslang::EOpInverseSqrt:
        return zip({x[0]}, [&](const std::vector<Var>& a) { return atomic("inv", atomic("sqrt", a[0])); });
      case glslang::EOpRadians:
        return zip({x[0]}, [&](const std::vector<Var>& a) { return mul(a[0], Var(M_PI / 180)); });
      case glslang::EOpDegrees:
        return zip({x[0]}, [&](const std::vector<Var>& a) { return mul(a[0], Var(180 / M_PI)); });
      case glslang::EOpPow:
        return zip(x, [&](const std::vector<Var>& a) { return pow_var(a[0], a[1]); });
      case glslang::EOpMod:
        return zip(x, [&](const std::vector<Var>& a) { return mod_var(a[0], a[1]); });
      case glslang::EOpMin:
        return zip(x, [&](const std::vector<Var>& a) { return dsl::min(a[0], a[1]); });
      case glslang::EOpMax:
        return zip(x, [&](const std::vector<Var>& a) { return dsl::max(a[0], a[1]); });
      case glslang::EOpClamp:
        return zip(x, [&](const std::vector<Var>& a) { return clamp_var(a[0], a[1], a[2]); });
      case glslang::EOpMix:
        if (n->getAsAggregate() &&
            n->getAsAggregate()->getSequence()[2]->getAsTyped()->getBasicType() == glslang::EbtBool)
          return zip(x, [&](const std::vector<Var>& a) { return sel(a[2], a[1], a[0]); });
        return zip(x, [&](const std::vector<Var>& a) { return add(a[0], mul(sub(a[1], a[0]), a[2])); });
      case glslang::EOpStep:
        return zip(x, [&](const std::vector<Var>& a) { return atomic("step", sub(a[1], a[0])); });
      case glslang::EOpSmoothStep:
        return zip(x, [&](const std::vector<Var>& a) { return smooth(a[0], a[1], a[2]); });
      case glslang::EOpLength:
        return Value{{length_of(x[0])}};
      case glslang::EOpDistance: {
        const Value d = zip(x, [&](const std::vector<Var>& a) { return sub(a[0], a[1]); });
        return Value{{length_of(d)}};
      }
      case glslang::EOpDot:
        return Value{{dot_of(x[0], x[1])}};
      case glslang::EOpNormalize: {
        if (x[0].size() == 1) return each("sign");
        const Var k = atomic("inv", atomic("sqrt", dot_of(x[0], x[0])));
        return zip({x[0]}, [&](const std::vector<Var>& a) { return mul(a[0], k); });
      }
      case glslang::EOpCross: {
        const auto& a = x[0].c;
        const auto& b = x[1].c;
        return Value{{sub(mul(a[1], b[2]), mul(a[2], b[1])), sub(mul(a[2], b[0]), mul(a[0], b[2])),
                      sub(mul(a[0], b[1]), mul(a[1], b[0]))}};
      }
      case glslang::EOpReflect: {  // I - 2 dot(N, I) N
        const Var d = mul(Var(2.0), dot_of(x[1], x[0]));
        return zip(x, [&](const std::vector<Var>& a) { return sub(a[0], mul(d, a[1])); });
      }
      case glslang::EOpFaceForward: {  // dot(Nref, I) < 0 ? N : -N
        const Var c = less(dot_of(x[2], x[1]), Var(0.0));
        return zip({x[0]}, [&](const std::vector<Var>& a) { return sel(c, a[0], -a[0]); });
      }
      case glslang::EOpLessThan:
        return zip(x, [&](const std::vector<Var>& a) { return less(a[0], a[1]); });
      case glslang::EOpGreaterThan:
        return zip(x, [&](const std::vector<Var>& a) { return less(a[1], a[0]); });
      case glslang::EOpLessThanEqual:
        return zip(x, [&](const std::vector<Var>& a) { return lnot(less(a[1], a[0])); });
      case glslang::EOpGreaterThanEqual:
        return zip(x, [&](const std::vector<Var>& a) { return lnot(less(a[0], a[1])); });
      case glslang::EOpVectorEqual:
        return zip(x, [&](const std::vector<Var>& a) { return equal(a[0], a[1]); });
      case glslang::EOpVectorNotEqual:
        return zip(x, [&](const std::vector<Var>& a) { return lnot(equal(a[0], a[1])); });
      case glslang::EOpAny: {
        Var r(0.0);
        for (Var v : x[0].c) r = lor(r, v);
        return Value{{r}};
      }
      case glslang::EOpAll: {
        Var r(1.0);
        for (Var v : x[0].c) r = land(r, v);
        return Value{{r}};
      }
      case glslang::EOpVectorLogicalNot:
        return zip({x[0]}, [&](const std::vector<Var>& a) { return lnot(a[0]); });
      case glslang::EOpMul:  // matrixCompMult
        return zip(x, [&](const std::vector<Var>& a) { return mul(a[0], a[1]); });
      case glslang::EOpOuterProduct: {  // column c times row r: |c| rows, |r| columns
        Value r;
        for (Var rj : x[1].c)
          for (Var ci : x[0].c) r.c.push_back(mul(ci, rj));
        return r;
      }
      case glslang::EOpTranspose: {
        const glslang::TType& t = n->getAsAggregate()
                                      ? n->getAsAggregate()->getSequence()[0]->getAsTyped()->getType()
                                      : n->getAsUnaryNode()->getOperand()->getType();
        const int cols = t.getMatrixCols(), rows = t.getMatrixRows();
        Value r;
        for (int i = 0; i < rows; ++i)
          for (int c = 0; c < cols; ++c) r.c.push_back(x[0].c[c * rows + i]);
        return r;
      }
      case glslang::EOpDeterminant:
      case glslang::EOpMatrixInverse: {
        int k = 1;
        while (k * k < x[0].size()) ++k;
        if (k * k != x[0].size()) fail(n, "determinant or inverse of a non-square matrix");
        return op == glslang::EOpDeterminant ? Value{{det_of(x[0].c, k)}} : inverse_of(x[0].c, k);
      }
      case glslang::EOpAtan:
        if (x.size() == 1) return each("atan");
        return zip(x, [&](const std::vector<Var>& a) { return atan2_of(a[0], a[1]); });
      case glslang::EOpAsin:  // atan(x, sqrt(1 - x^2)): no division by 0 at x = +-1
        return zip({x[0]}, [&](const std::vector<Var>& a) {
          return atan2_of(a[0], atomic("sqrt", sub(Var(1.0), atomic("pow2", a[0]))));
        });
      case glslang::EOpAcos:
        return zip({x[0]}, [&](const std::vector<Var>& a) {
          return atan2_of(atomic("sqrt", sub(Var(1.0), atomic("pow2", a[0]))), a[0]);
        });
      // The inverse hyperbolic functions through log, as GLSL drivers write them (asinh odd by
      // construction: log(|x| + sqrt(x^2 + 1)) loses nothing to cancellation for negative x).
      case glslang::EOpAsinh:
        return zip({x[0]}, [&](const std::vector<Var>& a) {
          const Var r =
              atomic("log", add(atomic("abs", a[0]), atomic("sqrt", add(atomic("pow2", a[0]), Var(1.0)))));
          return mul(atomic("sign", a[0]), r);
        });
      case glslang::EOpAcosh:  // x >= 1 (GLSL: undefined below)
        return zip({x[0]}, [&](const std::vector<Var>& a) {
          return atomic("log", add(a[0], atomic("sqrt", sub(atomic("pow2", a[0]), Var(1.0)))));
        });
      case glslang::EOpAtanh:  // |x| < 1
        return zip({x[0]}, [&](const std::vector<Var>& a) {
          return mul(Var(0.5), atomic("log", div(add(Var(1.0), a[0]), sub(Var(1.0), a[0]))));
        });
      case glslang::EOpDPdx:
      case glslang::EOpDPdy:
      case glslang::EOpFwidth:
        unsupported(n, "screen-space derivatives (dFdx/dFdy/fwidth): the smoothing supplies the footprint");
      default:
        unsupported(n, std::string("built-in function or operator '") + op_text(n) + "'");
    }
  }

  static std::string op_text(TIntermTyped* n) {
    if (auto* a = n->getAsAggregate()) {
      std::string s = a->getName().c_str();
      if (!s.empty()) return s.substr(0, s.find('('));
    }
    return "#" + std::to_string(static_cast<int>(n->getAsOperator() ? n->getAsOperator()->getOp() : 0));
  }

  // ---------- user functions (inlined) ----------
  Value call(TIntermAggregate* a) {
    const std::string mangled = a->getName().c_str();
    const std::string base = mangled.substr(0, mangled.find('('));
    std::vector<Value> args;
    for (TIntermNode* s : a->getSequence()) args.push_back(eval(s->getAsTyped()));
    if (prelude_functions_.count(mangled)) {
      // A prelude atomic: straight to the catalog function, component-wise.
      return zip({args[0]}, [&](const std::vector<Var>& v) { return atomic(base.c_str(), v[0]); });
    }
    auto it = functions_.find(mangled);
    if (it == functions_.end()) fail(a, "function '" + base + "' is declared but never defined");
    return inline_call(it->second, args, a->getSequence(), a);
  }

  Value inline_call(TIntermAggregate* def, const std::vector<Value>& args,
                    const glslang::TIntermSequence& arg_nodes, const TIntermNode* site) {
    const std::string name = def->getName().c_str();
    if (active_.count(name))
      fail(site, "unsupported recursion ('" + name.substr(0, name.find('(')) + "' calls itself)");
    if (static_cast<int>(active_.size()) >= kMaxCallDepth) fail(site, "calls nested too deeply");
    const auto& seq = def->getSequence();
    TIntermAggregate* params = seq.empty() ? nullptr : seq[0]->getAsAggregate();
    TIntermNode* body = seq.size() > 1 ? seq[1] : nullptr;
    // Out/inout arguments: where to copy back.
    std::vector<std::pair<LRef, long long>> outs;
    const Var alive = st_.alive, brk = st_.brk, cont = st_.cont;
    Value ret = std::move(st_.ret);
    for (std::size_t i = 0; params && i < params->getSequence().size(); ++i) {
      auto* p = params->getSequence()[i]->getAsSymbolNode();
      if (!p) continue;
      const auto q = p->getQualifier().storage;
      st_.vars[p->getId()] = q == glslang::EvqOut ? zeros(components(p)) : args.at(i);
      if ((q == glslang::EvqOut || q == glslang::EvqInOut) && i < arg_nodes.size())
        outs.push_back({lvalue(arg_nodes[i]->getAsTyped()), p->getId()});
    }
    active_.insert(name);
    st_.alive = st_.brk = st_.cont = Var(1.0);
    st_.ret = zeros(components(def));  // a path that never returns reads 0 (undefined in GLSL)
    exec(body);
    Value result = std::move(st_.ret);
    active_.erase(name);
    st_.alive = alive;
    st_.brk = brk;
    st_.cont = cont;
    st_.ret = std::move(ret);
    for (const auto& [ref, id] : outs) write(ref, st_.vars.at(id));
    return result;
  }

  ir::Graph& g_;
  std::string file_;
  std::map<std::string, TIntermAggregate*> functions_;
  std::set<std::string> prelude_functions_;
  std::set<std::string> active_;
  std::vector<std::string> textures_;
  State st_;
  // Per enclosing loop, innermost last: the variables that existed when it began (write).
  std::vector<std::set<int>> loop_vars_;
};

// True when an output depends on node `id`.
bool reaches(const ir::Graph& g, int id) {
  for (int k : g.depth_first_order())
    if (k == id) return true;
  return false;
}

// The graph without the nodes no output needs (tracing leaves masks and defaults behind), inputs
// and texture slots kept in their order; node order stays topological.
ir::Graph compact(const ir::Graph& g) {
  std::vector<char> live(g.size(), 0);
  for (int k : g.depth_first_order()) live[k] = 1;
  ir::Graph out;
  for (const auto& in : g.inputs()) out.input(in.name, in.varying);
  for (const auto& t : g.textures()) out.texture_slot(t);
  std::vector<int> id(g.size(), -1);
  for (int i = 0; i < g.size(); ++i) {
    const ir::Node& n = g.node(i);
    if (n.op == ir::Op::Input) {
      id[i] = out.input(g.inputs()[static_cast<int>(n.value)].name,
                        g.inputs()[static_cast<int>(n.value)].varying);
      continue;
    }
    if (!live[i]) continue;
    ir::Node m = n;
    if (m.a >= 0) m.a = id[m.a];
    if (m.b >= 0) m.b = id[m.b];
    if (m.c >= 0) m.c = id[m.c];
    id[i] = n.op == ir::Op::Const ? out.constant(n.value) : out.add(m);
  }
  for (std::size_t k = 0; k < g.outputs().size(); ++k)
    out.add_output(g.output_names()[k], id[g.outputs()[k]]);
  return out;
}

}  // namespace

std::string without_version_line(const std::string& source) {
  std::istringstream in(source);
  std::string line, out;
  bool seen_code = false;
  while (std::getline(in, line)) {
    const auto p = line.find_first_not_of(" \t");
    if (!seen_code && p != std::string::npos && line.compare(p, 8, "#version") == 0)
      line = "";
    else if (p != std::string::npos && line.compare(p, 2, "//") != 0)
      seen_code = true;
    out += line + "\n";
  }
  return out;
}

Pattern trace_source(const std::string& source, const std::string& file) {
  init_glslang();
  const std::string user = without_version_line(source);
  const std::string pre = "#version 450\n" + prelude();
  const char* strings[2] = {pre.c_str(), user.c_str()};
  const int lengths[2] = {static_cast<int>(pre.size()), static_cast<int>(user.size())};
  const char* names[2] = {"<bandlimit prelude>", file.c_str()};
  glslang::TShader shader(EShLangFragment);
  shader.setStringsWithLengthsAndNames(strings, lengths, names, 2);
  if (!shader.parse(GetDefaultResources(), 450, ECoreProfile, false, false, EShMsgDefault)) {
    std::string log = shader.getInfoLog();
    // "ERROR: file:L: ..." -> "file:L: ..." one per line; drop glslang's summary line.
    std::istringstream in(log);
    std::string line, msg;
    while (std::getline(in, line)) {
      if (line.rfind("ERROR: ", 0) == 0) line = line.substr(7);
      if (line.empty() || line.find("compilation errors") != std::string::npos) continue;
      msg += (msg.empty() ? "" : "\n") + line;
    }
    throw Error(msg.empty() ? file + ": GLSL parse failed" : msg);
  }
  TIntermAggregate* root = shader.getIntermediate()->getTreeRoot()->getAsAggregate();
  if (!root) throw Error(file + ": empty GLSL translation unit");
  std::map<std::string, TIntermAggregate*> functions;
  std::set<std::string> prelude_functions;
  TIntermAggregate* shade = nullptr;
  std::vector<TIntermAggregate*> shade_like;
  for (TIntermNode* n : root->getSequence()) {
    TIntermAggregate* a = n->getAsAggregate();
    if (!a || a->getOp() != glslang::EOpFunction) continue;
    const std::string name = a->getName().c_str();
    functions[name] = a;
    if (a->getLoc().string == 0) prelude_functions.insert(name);
    if (name == "shade(vf2;f1;")
      shade = a;
    else if (name.rfind("shade(", 0) == 0)
      shade_like.push_back(a);
  }
  if (!shade) {
    if (!shade_like.empty()) {
      const glslang::TSourceLoc& loc = shade_like[0]->getLoc();
      throw Error(file + ":" + std::to_string(loc.line) + ":" + std::to_string(loc.column) +
                  ": shade has the wrong parameters; declare it vec3 shade(vec2 uv, float time)");
    }
    throw Error(file + ": no function vec3 shade(vec2 uv, float time) (the pattern's entry point)");
  }
  const glslang::TType& rt = shade->getType();
  if (rt.getBasicType() != glslang::EbtFloat || rt.getVectorSize() != 3 || rt.isArray() || rt.isMatrix()) {
    const glslang::TSourceLoc& loc = shade->getLoc();
    throw Error(file + ":" + std::to_string(loc.line) + ":" + std::to_string(loc.column) +
                ": shade returns " + rt.getCompleteString().c_str() +
                "; declare it vec3 shade(vec2 uv, float time)");
  }
  Pattern p;
  p.file = file;
  ir::Graph traced;
  {
    dsl::Tracer tracer(traced);
    const Var u = Var::input("u", true), v = Var::input("v", true), time = Var::input("time", false);
    Walker w(traced, file, functions, prelude_functions);
    w.run_globals(root);
    Value rgb = w.call_shade(shade, u, v, time);
    traced.add_output("r", rgb.c.at(0).id());
    traced.add_output("g", rgb.c.at(1).id());
    traced.add_output("b", rgb.c.at(2).id());
    p.textures = w.textures();
  }
  p.graph = compact(traced);
  p.uses_time = reaches(p.graph, p.graph.input("time", false));
  return p;
}

Pattern trace_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open the GLSL file");
  std::stringstream ss;
  ss << in.rdbuf();
  return trace_source(ss.str(), path);
}

}  // namespace bl::glsl
