// The GPU cost fit (tuner/gpu_fit.hpp): it recovers prices that generated the draws, leaves unused
// functions at the scaled prior, prices a program as CostModel::cost does under the fitted model
// (features and cost cannot drift apart), floors, and names what it cannot fit.
#include "tuner/gpu_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>

#include "compiler/functions.hpp"
#include "compiler/lower.hpp"
#include "compiler/supersample.hpp"
#include "dsl/math.hpp"
#include "rules/rule.hpp"

namespace bl::tuner {
namespace {

// A prior covering every op and function: op k at 0.1 + 0.01 k, function f at 1 + 0.001 f.
CostModel prior() {
  CostModel m;
  m.machine = "test-cpu";
  m.method = "compiled";
  for (int o = 0; o <= static_cast<int>(compiler::LOp::TexStat); ++o)
    m.op_ns[lop_name(static_cast<compiler::LOp>(o))] = 0.1 + 0.01 * o;
  m.op_ns["pixel"] = 0.5;
  m.op_ns["output"] = 0.2;
  for (std::size_t f = 0; f < compiler::functions().size(); ++f)
    m.fn_ns[compiler::functions()[f].cpp] = 1.0 + 0.001 * static_cast<double>(f);
  return m;
}

TEST(GpuFit, RecoversThePricesThatMadeTheDraws) {
  const CostModel p = prior();
  const std::vector<std::string> names = {"pixel",
                                          "output",
                                          "add",
                                          "mul",
                                          "sqrt",
                                          "sample",
                                          "bl::plain::sin",
                                          "bl::plain::floor",
                                          "bl::gaussian::fract",
                                          "bl::box::fract"};
  // The truth: prior x 0.01 x a factor in [0.5, 2] per name (the sample loop: 0.03 ns).
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> factor(0.5, 2.0), count(0.0, 6.0);
  std::map<std::string, double> truth;
  for (const std::string& n : names)
    truth[n] = n == "sample" ? 0.03 : 0.01 * factor(rng) * (p.op_ns.count(n) ? p.op_ns.at(n) : p.fn_ns.at(n));
  std::vector<GpuSample> draws;
  for (int i = 0; i < 80; ++i) {
    GpuSample s;
    s.scene = "synthetic";
    s.label = "d" + std::to_string(i);
    for (const std::string& n : names) s.x[n] = n == "pixel" ? 1.0 : std::round(count(rng));
    for (const auto& [n, c] : s.x) s.measured_ns += c * truth.at(n);
    draws.push_back(s);
  }
  GpuFitOptions o;
  o.lambda = 1e-10;
  o.floor_ns = 0;
  const GpuFit f = fit_gpu_cost_model(draws, p, o, "test-gpu");
  EXPECT_EQ(f.model.machine, "test-gpu");
  EXPECT_EQ(f.model.method, "gpu-fit");
  EXPECT_EQ(f.used, 80);
  for (const std::string& n : names) {
    const double got = f.model.op_ns.count(n) ? f.model.op_ns.at(n) : f.model.fn_ns.at(n);
    EXPECT_NEAR(got / truth.at(n), 1.0, 1e-6) << n;
  }
  // A function no draw calls keeps the prior's price times the fitted GPU / CPU ratio.
  EXPECT_NEAR(f.model.fn_ns.at("bl::tent::sin"), f.alpha * p.fn_ns.at("bl::tent::sin"), 1e-12);
  EXPECT_TRUE(f.model.covers_all()) << f.model.missing();
  // Draws under a soft floor ((floor^4 + T^4)^(1/4), every draw above 1.5 floors): the fit inverts it.
  std::vector<GpuSample> soft = draws;
  double least = 1e30;
  for (const GpuSample& s : draws) least = std::min(least, s.measured_ns);
  GpuFitOptions so = o;
  so.floor_ns = least / 2, so.floor_norm = 4;
  for (GpuSample& s : soft)
    s.measured_ns = std::pow(std::pow(so.floor_ns, 4) + std::pow(s.measured_ns, 4), 0.25);
  const GpuFit fs = fit_gpu_cost_model(soft, p, so, "test-gpu");
  EXPECT_EQ(fs.used, 80);
  EXPECT_DOUBLE_EQ(fs.model.floor_norm, 4);
  for (const std::string& n : names) {
    const double got = fs.model.op_ns.count(n) ? fs.model.op_ns.at(n) : fs.model.fn_ns.at(n);
    EXPECT_NEAR(got / truth.at(n), 1.0, 1e-6) << n << " under a soft floor";
  }
  // A strong ridge keeps every price at the scaled prior.
  o.lambda = 1e12;
  const GpuFit r = fit_gpu_cost_model(draws, p, o, "test-gpu");
  EXPECT_NEAR(r.model.op_ns.at("mul") / (r.alpha * p.op_ns.at("mul")), 1.0, 1e-6);
}

TEST(GpuFit, FeaturesPriceAProgramAsTheCostModelDoes) {
  ir::Graph g;
  dsl::Tracer t(g);
  const dsl::Var u = dsl::Var::input("u", true), v = dsl::Var::input("v", true);
  g.add_output("r", (dsl::sin(u * 3.0) + dsl::fract(v * 5.0) * dsl::cos(u * 3.0)).id());
  g.add_output("g", dsl::sqrt(dsl::abs(u - v)).id());
  CostModel m = prior();
  for (auto& [n, c] : m.op_ns) c *= 0.01;
  for (auto& [n, c] : m.fn_ns) c *= 0.01;
  m.op_ns["sample"] = 0.004;
  m.method = "gpu-fit";
  m.floor_ns = 0.02;
  for (const char* rule : {"none", "gaussian", "box", "dorn"}) {
    const compiler::Program p = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule(rule)));
    EXPECT_NEAR(m.cost(p), predict(m, throughput_features(p)), 1e-12) << rule;
    EXPECT_GT(m.cost(p), m.floor_ns) << rule;
  }
  const compiler::Program plain =
      compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("none")));
  for (int n : {1, 4, 16}) {
    const compiler::Program one = compiler::one_sample(plain, n, 0.5);
    EXPECT_NEAR(m.sequential_cost(one, n), predict(m, repeated(throughput_features(one), n)), 1e-12) << n;
  }
  // The floor: a program cheaper than it costs the floor, alone and n times over.
  const double tp = m.throughput(plain);
  m.floor_ns = 100;
  EXPECT_DOUBLE_EQ(m.cost(plain), 100);
  EXPECT_DOUBLE_EQ(m.sequential_cost(plain, 4), 100);
  EXPECT_DOUBLE_EQ(predict(m, throughput_features(plain)), 100);
  // A soft floor: (floor^4 + T^4)^(1/4), in cost and predict alike.
  m.floor_ns = tp, m.floor_norm = 4;
  EXPECT_NEAR(m.cost(plain), tp * std::pow(2.0, 0.25), 1e-12 * tp);
  EXPECT_NEAR(predict(m, throughput_features(plain)), tp * std::pow(2.0, 0.25), 1e-12 * tp);
}

TEST(GpuFit, SavedAndLoadedWithItsFloor) {
  GpuFitOptions o;
  o.floor_ns = 0.25;
  GpuSample s;
  s.scene = "a";
  s.x = {{"pixel", 1}, {"mul", 40}};
  s.measured_ns = 1.0;
  const GpuFit f = fit_gpu_cost_model({s}, prior(), o, "test-gpu");
  const std::string path =
      (std::filesystem::temp_directory_path() / ("bl_gpu_fit_" + std::to_string(::getpid()) + ".json"))
          .string();
  save_cost_model(path, f.model);
  const CostModel back = load_cost_model(path, "test-gpu");
  std::filesystem::remove(path);
  EXPECT_EQ(back.method, "gpu-fit");
  EXPECT_DOUBLE_EQ(back.floor_ns, 0.25);
  EXPECT_DOUBLE_EQ(back.floor_norm, 0);  // a hard max unless fitted otherwise
  EXPECT_DOUBLE_EQ(back.op_ns.at("mul"), f.model.op_ns.at("mul"));
  EXPECT_NEAR(predict(back, s.x), 1.0, 1e-6);  // one draw, two prices, no ridge to speak of: exact
}

TEST(GpuFit, NamesWhatItCannotFit) {
  GpuFitOptions o;
  o.floor_ns = 1.0;
  GpuSample s;
  s.scene = "a";
  s.x = {{"pixel", 1}, {"mul", 3}};
  s.measured_ns = 1.2;  // below 1.5 floors
  try {
    fit_gpu_cost_model({s}, prior(), o, "g");
    ADD_FAILURE() << "no draw above the floor was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("floor"), std::string::npos) << e.what();
  }
  s.measured_ns = 5;
  s.x["bl::no::such"] = 1;
  try {
    fit_gpu_cost_model({s}, prior(), o, "g");
    ADD_FAILURE() << "a feature without a prior price was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("bl::no::such"), std::string::npos) << e.what();
  }
  EXPECT_THROW(repeated(s.x, 0), std::invalid_argument);
}

}  // namespace
}  // namespace bl::tuner
