// Catalog fuzz: mutates the shipped catalog (types, numbers, expressions, names, deleted and unknown
// fields, swapped and dropped pieces, changed classes, ...) and runs rulegen in-process (load,
// validate, derive, emit) on each mutant. Every outcome must be exit 0, or exit 2 with a message
// naming the file and (for an entry) the entry and the field: never exit 3, a crash or a hang
// (ctest's TIMEOUT). Deterministic: case i uses seed kSeed + i with std::mt19937_64, whose output
// the standard fixes; no std:: distributions (their output is implementation-defined).
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <regex>
#include <sstream>

#include "pipeline.hpp"

namespace {
using nlohmann::json;

constexpr int kCases = 1200;
constexpr uint64_t kSeed = 20261123;

const json& shipped() {
  static const json j = [] {
    std::ifstream in(BL_DEFAULT_CATALOG);
    return json::parse(in);
  }();
  return j;
}

struct Rng {
  std::mt19937_64 g;
  explicit Rng(uint64_t s) : g(s) {}
  size_t below(size_t n) { return n ? static_cast<size_t>(g() % n) : 0; }
  bool coin(int one_in) { return below(one_in) == 0; }
  template <class T>
  const T& pick(const std::vector<T>& v) {
    return v[below(v.size())];
  }
};

// Values of every type, and the expressions that broke the loader before (issue 15).
json random_value(Rng& r) {
  static const std::vector<json> values = {
      nullptr,
      true,
      false,
      0,
      1,
      -1,
      7,
      3.5,
      -0.25,
      1e308,
      9007199254740993LL,
      "",
      "x",
      "y",
      "inf",
      "-inf",
      "+inf",
      "1/0",
      "0/0",
      "sqrt(-1)",
      "log(-1)",
      "abs(x)",
      "sgn(x)",
      "x^40",
      "x^(1/3)",
      "Pi",
      "-Pi/2",
      "1/2",
      "nonsense(",
      "zeta(x)",
      "Li2(x)",
      "exp(x^2)",
      "tanh(x)",
      "1/x",
      "log(x)",
      "x*abs(x)",
      "step(x)",
      "sin(10*Pi*x)^2",
      "1e400",
      "10^400",
      "integers",
      json::array(),
      json::object(),
      json::array({1}),
      json::array({0, 1}),
      json::array({"-inf", "inf"}),
      json::array({1, 0}),
      json::array({"integers"}),
      json::object({{"on", json::array({0, 1})}, {"f", "x"}}),
      json::object({{"a", 1}}),
      json::array({json::object({{"on", json::array({0, 1})}, {"inverse", "y"}})})};
  return r.pick(values);
}

// Edits of an expression or number written as text.
json mutate_text(Rng& r, const std::string& s) {
  static const std::vector<std::string> tails = {
      " + sgn(x)", "*2", " + 1", "^2", " + sin(10*Pi*x)^2", "/x", " + abs(x)", "(", ")", " + y", " - x"};
  switch (r.below(5)) {
    case 0:
      return s + r.pick(tails);
    case 1:
      return std::regex_replace(s, std::regex("x"), r.coin(2) ? "(x+1)" : "(2*x)");
    case 2:
      return std::regex_replace(s, std::regex("[0-9]"), r.coin(2) ? "3" : "0");
    case 3:
      return s.empty() ? s : s.substr(0, r.below(s.size()));
    default:
      return "-(" + s + ")";
  }
}

json mutate_number(Rng& r, const json& v) {
  const double d = v.get<double>();
  switch (r.below(6)) {
    case 0:
      return v.is_number_integer() ? json(v.get<long long>() + 1) : json(d + 1);
    case 1:
      return v.is_number_integer() ? json(-v.get<long long>()) : json(-d);
    case 2:
      return 0;
    case 3:
      return std::to_string(static_cast<long long>(d)) + "/3";
    case 4:
      return d * 1.5;
    default:
      return "Pi";
  }
}

// All paths (object keys and list indices) of j, below and including the root.
void paths(const json& j, const json::json_pointer& at, std::vector<json::json_pointer>& out) {
  out.push_back(at);
  if (j.is_object())
    for (auto& [k, v] : j.items()) paths(v, at / k, out);
  else if (j.is_array())
    for (size_t i = 0; i < j.size(); ++i) paths(j[i], at / i, out);
}

// One mutation somewhere in `e` (an entry, or the whole catalog).
void mutate(Rng& r, json& e, const std::vector<std::string>& names) {
  std::vector<json::json_pointer> ps;
  paths(e, json::json_pointer(), ps);
  const json::json_pointer p = ps[r.below(ps.size())];
  json& v = e[p];
  const bool root = p.empty();
  switch (r.below(9)) {
    case 0:
      if (!root) v = random_value(r);
      break;
    case 1:
      if (v.is_string())
        v = mutate_text(r, v.get<std::string>());
      else if (v.is_number())
        v = mutate_number(r, v);
      else if (!root)
        v = random_value(r);
      break;
    case 2:  // delete a field or a list element
      if (v.is_object() && !v.empty()) {
        auto it = v.begin();
        std::advance(it, r.below(v.size()));
        v.erase(it.key());
      } else if (v.is_array() && !v.empty()) {
        v.erase(v.begin() + static_cast<long>(r.below(v.size())));
      }
      break;
    case 3:  // swap two list elements (pieces, bounds, monotone pieces, entries)
      if (v.is_array() && v.size() >= 2)
        std::swap(v[r.below(v.size())], v[r.below(v.size())]);
      else if (v.is_array() && v.size() == 1)
        v.push_back(v[0]);  // a duplicate
      break;
    case 4:  // an unknown or misplaced field
      if (v.is_object())
        v[r.pick(std::vector<std::string>{"F2", "period", "pieces", "of", "scale", "flat", "kinks",
                                          "singular", "parity", "zzz"})] = random_value(r);
      break;
    case 5:
      if (e.is_object() && e.contains("name"))
        e["name"] = r.coin(2) ? json(r.pick(names))
                              : json(r.pick(std::vector<std::string>{"Sin", "", "a-b", "for", "moment", "x",
                                                                     "sin_sq", "_a"}));
      break;
    case 6:
      if (e.is_object() && e.contains("class"))
        e["class"] = r.pick(std::vector<std::string>{"entire", "piecewise", "periodic", "combination",
                                                     "antiderivative", "wavy"});
      break;
    case 7:  // exchange the values of two fields of the entry
      if (e.is_object() && e.size() >= 2) {
        auto a = e.begin(), b = e.begin();
        std::advance(a, r.below(e.size()));
        std::advance(b, r.below(e.size()));
        std::swap(a.value(), b.value());
      }
      break;
    default:  // wrap in a list or object
      if (!root) v = r.coin(2) ? json::array({v}) : json::object({{"value", v}});
      break;
  }
}

// The entries that `of` refers to (a combination needs them in its catalog).
std::vector<json> dependencies(const json& entry, const json& cat) {
  std::vector<json> out;
  if (!entry.contains("of") || !entry["of"].is_string()) return out;
  const std::string of = entry["of"].get<std::string>();
  for (const json& e : cat["atomics"])
    if (of.find(e["name"].get<std::string>() + "(") != std::string::npos) out.push_back(e);
  return out;
}

int g_outcomes[4];  // exits 0, 2 and anything else, for the summary

class Summary : public ::testing::Environment {
  void TearDown() override {
    std::printf("catalog fuzz: %d mutants accepted (exit 0), %d rejected with a message (exit 2), %d other\n",
                g_outcomes[0], g_outcomes[2], g_outcomes[3]);
  }
};
const auto* const kSummary = ::testing::AddGlobalTestEnvironment(new Summary);

class CatalogFuzz : public ::testing::TestWithParam<int> {};

TEST_P(CatalogFuzz, ExitsZeroOrTwoWithAMessage) {
  const int i = GetParam();
  Rng r(kSeed + static_cast<uint64_t>(i));
  const json& cat = shipped();
  std::vector<std::string> names;
  for (const json& e : cat["atomics"]) names.push_back(e["name"]);
  json mutant;
  const bool whole = r.coin(25);  // the whole catalog (duplicate, dropped, reordered entries; top level)
  if (whole) {
    mutant = cat;
    mutate(r, mutant, names);
  } else {
    json entry = cat["atomics"][r.below(cat["atomics"].size())];
    mutant = {{"atomics", dependencies(entry, cat)}};
    const int n = 1 + static_cast<int>(r.below(3));
    for (int k = 0; k < n; ++k) mutate(r, entry, names);
    mutant["atomics"].push_back(entry);
  }
  const std::string text = mutant.dump();
  bl::rulegen::Options opt;
  opt.catalog_text = text;
  opt.quiet = true;
  opt.max_moment = 0;  // moments do not depend on the catalog
  opt.out =
      (std::filesystem::temp_directory_path() / ("bl_catalog_fuzz_" + std::to_string(getpid()))).string();
  std::ostringstream out, err;
  const auto t0 = std::chrono::steady_clock::now();
  const int rc = bl::rulegen::run(opt, out, err);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++g_outcomes[rc == 0 ? 0 : (rc == 2 ? 2 : 3)];
  std::error_code ignored;
  std::filesystem::remove_all(opt.out, ignored);
  const std::string msg = err.str();
  SCOPED_TRACE("case " + std::to_string(i) + ": " + text);
  EXPECT_TRUE(rc == 0 || rc == 2) << "exit " << rc << ": " << msg;
  EXPECT_LT(s, 10.0) << "slow case";
  if (rc == 2) {
    EXPECT_EQ(msg.rfind("rulegen: error: catalog text: ", 0), 0u) << msg;  // the origin (file) first
    if (!whole) {
      EXPECT_NE(msg.find("catalog entry '"), std::string::npos) << msg;
      EXPECT_NE(msg.find("field '"), std::string::npos) << msg;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Mutants, CatalogFuzz, ::testing::Range(0, kCases));

}  // namespace
