// The emitted GLSL library indexes its local arrays by loop counters and constants only.
//
// A GPU keeps a function's array in registers only when every index is known once its loops are
// unrolled; one index computed from data (r[deg + 1] with deg a polynomial's degree) sends the whole
// array, and every array copied into it, to local memory. On the H200 that was 312-670 local-memory
// slots and 3-46 ns/px in bricks_bumps' box/tent floor^2 programs (docs/gpu_timing.md, stop 42).
// This walks glslang's AST of generated/*.glsl and names every subscript of a local array or vector
// whose index reads anything but the counters of enclosing loops, constants, or a piece count `n`
// (a literal at every call site of the generated tables).
#include <glslang/Include/intermediate.h>
#include <glslang/MachineIndependent/localintermediate.h>
#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace glslang;

std::string read(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Violation {
  std::string file, function, index;
  int line;
};

// Walks one function body with the loop counters in scope.
class IndexCheck {
 public:
  IndexCheck(std::vector<std::string> files, std::string function, std::vector<Violation>* out)
      : files_(std::move(files)), function_(std::move(function)), out_(out) {}

  void walk(TIntermNode* n, std::vector<long long>& counters) {
    if (!n) return;
    if (TIntermLoop* loop = n->getAsLoopNode()) {
      const std::size_t before = counters.size();
      if (TIntermTyped* t = loop->getTerminal()) counter_of(t, &counters);
      walk(loop->getTest(), counters);
      walk(loop->getTerminal(), counters);
      walk(loop->getBody(), counters);
      counters.resize(before);
      return;
    }
    if (TIntermBinary* b = n->getAsBinaryNode()) {
      if (b->getOp() == EOpIndexIndirect && is_local(b->getLeft())) check(b, counters);
      walk(b->getLeft(), counters);
      walk(b->getRight(), counters);
      return;
    }
    if (TIntermUnary* u = n->getAsUnaryNode()) return walk(u->getOperand(), counters);
    if (TIntermAggregate* a = n->getAsAggregate()) {
      for (TIntermNode* c : a->getSequence()) walk(c, counters);
      return;
    }
    if (TIntermSelection* s = n->getAsSelectionNode()) {
      walk(s->getCondition(), counters);
      walk(s->getTrueBlock(), counters);
      walk(s->getFalseBlock(), counters);
      return;
    }
    if (TIntermBranch* br = n->getAsBranchNode()) return walk(br->getExpression(), counters);
    if (TIntermSwitch* sw = n->getAsSwitchNode()) {
      walk(sw->getCondition(), counters);
      walk(sw->getBody(), counters);
    }
  }

 private:
  std::vector<std::string> files_;
  std::string function_;
  std::vector<Violation>* out_;

  // ++i, i++, --i, i--, i += k, i -= k: the loop's counter.
  static void counter_of(TIntermTyped* t, std::vector<long long>* counters) {
    TIntermTyped* target = nullptr;
    if (TIntermUnary* u = t->getAsUnaryNode()) {
      const TOperator op = u->getOp();
      if (op == EOpPreIncrement || op == EOpPostIncrement || op == EOpPreDecrement || op == EOpPostDecrement)
        target = u->getOperand();
    } else if (TIntermBinary* b = t->getAsBinaryNode()) {
      if (b->getOp() == EOpAddAssign || b->getOp() == EOpSubAssign) target = b->getLeft();
    }
    if (target && target->getAsSymbolNode()) counters->push_back(target->getAsSymbolNode()->getId());
  }

  // An array or vector that lives in the function: a local or a parameter (not a uniform, a global
  // constant table or a built-in).
  static bool is_local(TIntermTyped* base) {
    while (TIntermBinary* b = base->getAsBinaryNode()) base = b->getLeft();
    TIntermSymbol* s = base->getAsSymbolNode();
    if (!s) return true;  // an indexed temporary (a call's result): conservatively local
    switch (s->getQualifier().storage) {
      case EvqTemporary:
      case EvqIn:
      case EvqOut:
      case EvqInOut:
      case EvqConstReadOnly:
        return true;
      default:
        return false;
    }
  }

  static void symbols(TIntermNode* n, std::vector<TIntermSymbol*>* out) {
    if (!n) return;
    if (TIntermSymbol* s = n->getAsSymbolNode()) return out->push_back(s);
    if (TIntermBinary* b = n->getAsBinaryNode()) {
      symbols(b->getLeft(), out);
      return symbols(b->getRight(), out);
    }
    if (TIntermUnary* u = n->getAsUnaryNode()) return symbols(u->getOperand(), out);
    if (TIntermAggregate* a = n->getAsAggregate())
      for (TIntermNode* c : a->getSequence()) symbols(c, out);
    if (TIntermSelection* s = n->getAsSelectionNode()) {
      symbols(s->getCondition(), out);
      symbols(s->getTrueBlock(), out);
      symbols(s->getFalseBlock(), out);
    }
  }

  void check(TIntermBinary* b, const std::vector<long long>& counters) {
    std::vector<TIntermSymbol*> used;
    symbols(b->getRight(), &used);
    for (TIntermSymbol* s : used) {
      const bool counter = std::find(counters.begin(), counters.end(), s->getId()) != counters.end();
      const bool piece_count = s->getName() == "n" && s->getQualifier().storage != EvqTemporary;
      if (counter || piece_count) continue;
      const TSourceLoc& loc = b->getLoc();
      const std::string file =
          loc.string >= 0 && loc.string < static_cast<int>(files_.size()) ? files_[loc.string] : "?";
      out_->push_back({file, function_, s->getName().c_str(), loc.line});
    }
  }
};

// Every violation in the translation unit made of `files` (paths) followed by `extra` source.
std::vector<Violation> violations(const std::vector<std::string>& files, const std::string& extra) {
  static const bool once = InitializeProcess();
  (void)once;
  std::vector<std::string> text{"#version 450\n"}, names{"<version>"};
  for (const std::string& f : files) {
    text.push_back(read(f));
    names.push_back(f);
  }
  text.push_back(extra);
  names.push_back("<test>");
  std::vector<const char*> strs, nms;
  std::vector<int> lens;
  for (std::size_t i = 0; i < text.size(); ++i) {
    strs.push_back(text[i].c_str());
    lens.push_back(static_cast<int>(text[i].size()));
    nms.push_back(names[i].c_str());
  }
  TShader shader(EShLangFragment);
  shader.setStringsWithLengthsAndNames(strs.data(), lens.data(), nms.data(), static_cast<int>(strs.size()));
  if (!shader.parse(GetDefaultResources(), 450, ECoreProfile, false, false, EShMsgDefault))
    throw std::runtime_error(std::string("glslang: ") + shader.getInfoLog());
  std::vector<Violation> out;
  TIntermAggregate* root = shader.getIntermediate()->getTreeRoot()->getAsAggregate();
  for (TIntermNode* n : root->getSequence()) {
    TIntermAggregate* fn = n->getAsAggregate();
    if (!fn || fn->getOp() != EOpFunction) continue;
    IndexCheck check(names, fn->getName().c_str(), &out);
    std::vector<long long> counters;
    check.walk(fn, counters);
  }
  return out;
}

std::string describe(const std::vector<Violation>& v) {
  std::string s;
  for (const Violation& x : v)
    s += x.file + ":" + std::to_string(x.line) + ": " + x.function + " indexes a local array by '" + x.index +
         "'\n";
  return s;
}

const std::string kMain = "layout(location = 0) out vec4 color;\nvoid main() { color = vec4(0.0); }\n";

TEST(GlslConstantIndex, TheGeneratedLibraryIndexesByLoopCountersOnly) {
  const std::string g = BL_GENERATED_DIR;
  const auto v = violations(
      {g + "/bandlimit.glsl", g + "/bandlimit_bivariate.glsl", g + "/bandlimit_clamped.glsl"}, kMain);
  EXPECT_TRUE(v.empty()) << describe(v);
}

// Whole emitted programs (bl_shade and its library slice): every .frag of the directory in
// BL_FRAG_DIR (ctest runs this case on the compiled fixtures, tests/runtime/CMakeLists.txt).
TEST(GlslConstantIndex, EveryFixtureProgram) {
  const char* dir = std::getenv("BL_FRAG_DIR");
  ASSERT_NE(dir, nullptr) << "set BL_FRAG_DIR to a directory of emitted .frag files";
  int programs = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().extension() != ".frag") continue;
    std::string src = read(e.path().string());
    src = src.substr(src.find('\n') + 1);  // its own #version line
    const auto v = violations({}, src);
    EXPECT_TRUE(v.empty()) << e.path().string() << ":\n" << describe(v);
    ++programs;
  }
  EXPECT_GT(programs, 0) << "no .frag files in " << dir;
}

// The check itself: a data-dependent index is named, a loop counter and a constant are not.
TEST(GlslConstantIndex, NamesADataDependentIndex) {
  const std::string src =
      "float f(float c[8], int deg) {\n"
      "  float g[8];\n"
      "  for (int k = 0; k < 8; ++k) g[k] = c[k];\n"
      "  for (int k = 7; k >= 0; --k) g[k] += g[2];\n"
      "  return g[deg + 1];\n"
      "}\n" +
      kMain;
  const auto v = violations({}, src);
  ASSERT_EQ(v.size(), 1u) << describe(v);
  EXPECT_EQ(v[0].index, "deg");
  EXPECT_EQ(v[0].line, 5);
  EXPECT_EQ(v[0].file, "<test>");
}

// A counter is in scope only inside its loop.
TEST(GlslConstantIndex, ACounterOutsideItsLoopIsData) {
  const std::string src =
      "uniform int u;\n"
      "float f(float c[8]) {\n"
      "  int k = u;\n"
      "  float s = 0.0;\n"
      "  for (int i = 0; i < 8; ++i) s += c[i];\n"
      "  return s + c[k];\n"
      "}\n" +
      kMain;
  const auto v = violations({}, src);
  ASSERT_EQ(v.size(), 1u) << describe(v);
  EXPECT_EQ(v[0].index, "k");
}

}  // namespace
