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

// Visits every subscript of the tree (glslang's traverser); the enclosing function and loops come from
// the traversal's path of ancestors.
class IndexCheck : public TIntermTraverser {
 public:
  IndexCheck(const std::vector<std::string>& files, std::vector<Violation>* out) : files_(files), out_(out) {}

  bool visitBinary(TVisit, TIntermBinary* b) override {
    if (b->getOp() == EOpIndexIndirect && is_local(b->getLeft())) check(b);
    return true;
  }

 private:
  const std::vector<std::string>& files_;
  std::vector<Violation>* out_;

  struct Symbols : TIntermTraverser {
    std::vector<TIntermSymbol*> found;
    void visitSymbol(TIntermSymbol* s) override { found.push_back(s); }
  };

  // ++i, i++, --i, i--, i += k, i -= k: the loop's counter (nullptr for any other terminal).
  static TIntermSymbol* counter_of(TIntermTyped* t) {
    TIntermTyped* target = nullptr;
    if (TIntermUnary* u = t->getAsUnaryNode()) {
      const TOperator op = u->getOp();
      if (op == EOpPreIncrement || op == EOpPostIncrement || op == EOpPreDecrement || op == EOpPostDecrement)
        target = u->getOperand();
    } else if (TIntermBinary* b = t->getAsBinaryNode()) {
      if (b->getOp() == EOpAddAssign || b->getOp() == EOpSubAssign) target = b->getLeft();
    }
    return target ? target->getAsSymbolNode() : nullptr;
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

  void check(TIntermBinary* b) {
    std::vector<long long> counters;  // of the loops around b
    std::string function = "?";
    for (TIntermNode* n : path) {
      if (TIntermLoop* loop = n->getAsLoopNode())
        if (TIntermSymbol* c = loop->getTerminal() ? counter_of(loop->getTerminal()) : nullptr)
          counters.push_back(c->getId());
      if (TIntermAggregate* a = n->getAsAggregate())
        if (a->getOp() == EOpFunction) function = a->getName().c_str();
    }
    Symbols used;
    b->getRight()->traverse(&used);
    for (TIntermSymbol* s : used.found) {
      const bool counter = std::find(counters.begin(), counters.end(), s->getId()) != counters.end();
      const bool piece_count = s->getName() == "n" && s->getQualifier().storage != EvqTemporary;
      if (counter || piece_count) continue;
      const TSourceLoc& loc = b->getLoc();
      const std::string file =
          loc.string >= 0 && loc.string < static_cast<int>(files_.size()) ? files_[loc.string] : "?";
      out_->push_back({file, function, s->getName().c_str(), loc.line});
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
  IndexCheck check(names, &out);
  shader.getIntermediate()->getTreeRoot()->traverse(&check);
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
